// The collision mesh: the nodes, edges and faces that take part in contact,
// with their weights, built from the surface the scene declares
// (Scene::surface, problems/scene.h; the grid, chain and particle generators
// declare theirs, a scene listing nodes and springs declares it with the
// "surface" key). Nothing is guessed from the springs.
//
// Primitives: the declared edges plus the edges of the declared triangles
// (each once, as (low, high) node ids, sorted), the triangles as declared
// (faces, 3D), and the declared points.
// Weights (the scale of a pair's barrier, contact/contact_state.h):
//  * node: its share of the surface measure: a third of the rest area of its
//    triangles plus half the rest length of its declared edges; a point
//    without either has weight 1 (a particle);
//  * edge: half the mean weight of its two nodes (2D: about half its length;
//    3D: about a third of a triangle), so an edge's barrier is on the scale of a
//    node's;
//  * face: its rest area (the faces over a point add up to the area once).
#pragma once

#include <array>
#include <vector>

#include "problems/scene.h"

namespace ipstep {

struct CollisionMesh {
  std::vector<int> nodes;                 // contact nodes, ascending
  std::vector<double> weights;            // per entry of `nodes`
  std::vector<std::array<int, 2>> edges;  // node ids, low < high, sorted
  std::vector<double> edge_weights;       // per entry of `edges`
  std::vector<std::array<int, 3>> faces;  // 3D triangles, as declared
  std::vector<double> face_weights;       // per entry of `faces`
  // Slot (index in `nodes`) of every node id up to the largest contact node,
  // -1 for a node not in contact: one dense table for every pair kind (a
  // lookup per primitive vertex in the 3D self-contact kinds' inner loops).
  // Filled by IndexNodeSlots.
  std::vector<int> node_slots;
};

// Fills mesh->node_slots from mesh->nodes; call after changing `nodes`
// (BuildCollisionMesh and the contact state's constructor do).
void IndexNodeSlots(CollisionMesh* mesh);

// Index of contact node `node` in mesh.nodes (mesh.node_slots).
inline int NodeSlot(const CollisionMesh& mesh, int node) { return mesh.node_slots[node]; }

// Throws InputError (key "surface") when the scene has springs between listed
// nodes but declares no surface, or a triangle or edge is degenerate at rest.
CollisionMesh BuildCollisionMesh(const Scene& scene);

}  // namespace ipstep
