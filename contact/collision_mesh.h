// Which nodes and edges take part in contact, and their weights, derived from
// the scene's nodes and springs.
//
// 2D: every connected component of the spring graph is a body; its contact
// boundary is the OUTER boundary of the drawn spring network, traced by walking
// around it (at each node the next edge is the first one counterclockwise from
// the edge we came along, starting rightwards from the lowest node). Springs
// crossing inside (shear diagonals) do not matter; holes are not traced. A node
// without springs is a body of its own (a particle). Weight of a boundary node:
// half the length of its two boundary edges (its share of the boundary length);
// 1 for a particle.
// 3D: every node is a contact node (cloth, particles); weight: the node's area,
// approximated as the square of its shortest spring (exact, a^2, inside a square
// grid of spacing a); 1 for a node without springs.
// Edges (checked against spheres / circles and 2D boxes, contact/obstacle.h):
// 2D the boundary edges; 3D every spring segment of the cloth except those
// that span another node (the bending springs of a grid: their segment is not
// part of the surface, it passes through the middle node at rest), i.e. the
// structural springs and both shear diagonals. Weight of an edge: half the
// mean weight of its two nodes (2D: about half its length; 3D: a^2 / 2 in a
// grid), so an edge's barrier is on the scale of a node's.
// Faces (3D only; checked against spheres and 3D boxes, contact/obstacle.h):
// every triangle of contact edges (3-clique of the edge graph) whose vertices
// are not collinear at the initial positions. In a grid with both shear
// diagonals each quad gives four overlapping triangles (two per diagonal);
// every point of the quad lies in exactly two of them, so the redundancy costs
// terms, not coverage. Weight of a face: a quarter of the mean weight of its
// three nodes (a^2 / 4 in a grid, half the triangle's area: the two triangles
// over each point of a quad add up to the quad's area, as the nodes' weights
// do), so a face's barrier is on the scale of a node's.
#pragma once

#include <array>
#include <vector>

#include "problems/scene.h"

namespace ipstep {

struct CollisionMesh {
  std::vector<int> nodes;                 // contact nodes, ascending
  std::vector<double> weights;            // per entry of `nodes`
  std::vector<std::array<int, 2>> edges;  // 2D: boundary edges; 3D: springs (both nodes in `nodes`)
  std::vector<double> edge_weights;       // per entry of `edges`
  std::vector<std::array<int, 3>> faces;  // 3D: triangles of `edges`, ascending node ids
  std::vector<double> face_weights;       // per entry of `faces`
};

CollisionMesh BuildCollisionMesh(const Scene& scene);

}  // namespace ipstep
