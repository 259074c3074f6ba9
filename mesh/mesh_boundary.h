// The boundary of a simplex mesh: the facets (edges in 2D, triangles in 3D)
// that belong to exactly one element, oriented outwards.
#pragma once

#include <array>
#include <vector>

#include "mesh/simplex_mesh.h"

namespace ipstep {

// Boundary facets, the first `dimension` entries used. 2D: edges (a, b) with
// the mesh on their left (the boundary runs counterclockwise); 3D: triangles
// (a, b, c) whose normal (b - a) x (c - a) points out of the mesh. Needs a
// positively oriented mesh.
std::vector<std::array<int, 3>> BoundaryFacets(const SimplexMesh& mesh);

// Nodes on the boundary, ascending.
std::vector<int> BoundaryNodes(const SimplexMesh& mesh);

// Adds the node sets "boundary" and "all" (replacing sets of those names).
void AddStandardNodeSets(SimplexMesh* mesh);

}  // namespace ipstep
