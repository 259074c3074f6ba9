#include "contact/collision_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/input_error.h"

namespace ipstep {

namespace {

Eigen::Vector3d RestPosition(const Scene& scene, int node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < scene.dimension; ++k) p[k] = scene.positions[scene.dimension * node + k];
  return p;
}

}  // namespace

void IndexNodeSlots(CollisionMesh* mesh) {
  int largest = -1;
  for (int node : mesh->nodes) largest = std::max(largest, node);
  mesh->node_slots.assign(largest + 1, -1);
  for (size_t s = 0; s < mesh->nodes.size(); ++s) {
    mesh->node_slots[mesh->nodes[s]] = static_cast<int>(s);
  }
}

CollisionMesh BuildCollisionMesh(const Scene& scene) {
  const Surface& surface = scene.surface;
  if (!surface.declared) {
    throw InputError(scene.source, "surface",
                     "the scene lists nodes and springs but declares no contact surface: add "
                     "\"surface\": {\"edges\": [[i, j], ...]} (2D boundary) or {\"triangles\": "
                     "[[i, j, k], ...]} (3D), see docs/scenes.md");
  }
  std::map<int, double> weight;
  std::set<std::pair<int, int>> edges;
  const auto fail = [&](const std::string& what) {
    throw InputError(scene.source, "surface", what);
  };
  for (const auto& e : surface.edges) {
    const double l = (RestPosition(scene, e[0]) - RestPosition(scene, e[1])).norm();
    if (!(l > 0.0)) {
      fail("edge (" + std::to_string(e[0]) + ", " + std::to_string(e[1]) + ") has zero length");
    }
    if (!edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])}).second) continue;
    weight[e[0]] += 0.5 * l;
    weight[e[1]] += 0.5 * l;
  }
  CollisionMesh mesh;
  for (const auto& t : surface.triangles) {
    const Eigen::Vector3d a = RestPosition(scene, t[0]), b = RestPosition(scene, t[1]),
                          c = RestPosition(scene, t[2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (!(area > 1e-12 * longest * longest)) {
      fail("triangle (" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " +
           std::to_string(t[2]) + ") is degenerate at rest");
    }
    for (int k = 0; k < 3; ++k) {
      weight[t[k]] += area / 3.0;
      const int i = t[k], j = t[(k + 1) % 3];
      edges.insert({std::min(i, j), std::max(i, j)});
    }
    mesh.faces.push_back(t);
    mesh.face_weights.push_back(area);
  }
  for (int p : surface.points) {
    if (weight.count(p) == 0) weight[p] = 1.0;
  }
  for (const auto& [node, w] : weight) {
    mesh.nodes.push_back(node);
    mesh.weights.push_back(w);
  }
  for (const auto& [a, b] : edges) {
    mesh.edges.push_back({a, b});
    mesh.edge_weights.push_back(0.25 * (weight[a] + weight[b]));
  }
  IndexNodeSlots(&mesh);
  return mesh;
}

}  // namespace ipstep
