#include "mesh/mesh_boundary.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace ipstep {

std::vector<std::array<int, 3>> BoundaryFacets(const SimplexMesh& mesh) {
  const int dim = mesh.dimension;
  // Facet opposite node a of a positively oriented simplex, oriented outwards.
  // 2D (n0, n1, n2) counterclockwise: edges (n0,n1), (n1,n2), (n2,n0).
  // 3D: the faces (n1,n2,n3), (n0,n3,n2), (n0,n1,n3), (n0,n2,n1) point outwards
  // when det[n1-n0, n2-n0, n3-n0] > 0.
  static const int kEdges[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  static const int kFaces[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>>
      count;  // sorted -> (n, oriented)
  for (const std::array<int, 4>& element : mesh.elements) {
    for (int f = 0; f < dim + 1; ++f) {
      std::array<int, 3> facet = {-1, -1, -1};
      for (int a = 0; a < dim; ++a) facet[a] = element[dim == 2 ? kEdges[f][a] : kFaces[f][a]];
      std::array<int, 3> key = facet;
      std::sort(key.begin(), key.begin() + dim);
      auto& entry = count[key];
      ++entry.first;
      entry.second = facet;
    }
  }
  std::vector<std::array<int, 3>> boundary;
  for (const auto& [key, entry] : count) {
    if (entry.first == 1) boundary.push_back(entry.second);
  }
  return boundary;
}

std::vector<int> BoundaryNodes(const SimplexMesh& mesh) {
  std::vector<bool> on(mesh.num_nodes(), false);
  for (const std::array<int, 3>& facet : BoundaryFacets(mesh)) {
    for (int a = 0; a < mesh.dimension; ++a) on[facet[a]] = true;
  }
  std::vector<int> nodes;
  for (int i = 0; i < mesh.num_nodes(); ++i) {
    if (on[i]) nodes.push_back(i);
  }
  return nodes;
}

void AddStandardNodeSets(SimplexMesh* mesh) {
  mesh->node_sets["boundary"] = BoundaryNodes(*mesh);
  std::vector<int> all(mesh->num_nodes());
  std::iota(all.begin(), all.end(), 0);
  mesh->node_sets["all"] = std::move(all);
}

}  // namespace ipstep
