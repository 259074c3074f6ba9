#include "io/surface_triangles.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ipstep {
namespace {

Eigen::Vector3d Position(const Scene& scene, int node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < scene.dimension; ++k) p[k] = scene.positions[scene.dimension * node + k];
  return p;
}

}  // namespace

std::vector<std::array<int, 3>> SurfaceTriangles(const Scene& scene) {
  if (!scene.surface.triangles.empty()) return scene.surface.triangles;
  return SpringTriangles(scene);
}

std::vector<std::array<int, 3>> SpringTriangles(const Scene& scene) {
  const int n = scene.num_nodes();
  std::vector<std::vector<int>> neighbours(n);
  for (const Spring& s : scene.springs) {
    if (s.i == s.j || s.i < 0 || s.j < 0 || s.i >= n || s.j >= n) continue;
    neighbours[s.i].push_back(s.j);
    neighbours[s.j].push_back(s.i);
  }
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  const auto common_neighbours = [&neighbours](int a, int b) {
    std::vector<int> common;
    std::set_intersection(neighbours[a].begin(), neighbours[a].end(), neighbours[b].begin(),
                          neighbours[b].end(), std::back_inserter(common));
    return common;
  };
  // Springs that pass through a node joined to both their ends (bending
  // springs over the middle node): not edges of the surface.
  std::set<std::pair<int, int>> spanning;
  for (int a = 0; a < n; ++a) {
    for (int b : neighbours[a]) {
      if (b <= a) continue;
      const Eigen::Vector3d pa = Position(scene, a), d = Position(scene, b) - pa;
      for (int c : common_neighbours(a, b)) {
        const Eigen::Vector3d r = Position(scene, c) - pa;
        const double along = r.dot(d);
        if (along > 0.0 && along < d.squaredNorm() && d.cross(r).norm() <= 1e-9 * d.squaredNorm()) {
          spanning.insert({a, b});
        }
      }
    }
  }
  // Triangles a < b < c of springs, by perimeter.
  std::vector<std::pair<double, std::array<int, 3>>> candidates;
  for (int a = 0; a < n; ++a) {
    for (int b : neighbours[a]) {
      if (b <= a || spanning.count({a, b}) > 0) continue;
      for (int c : common_neighbours(a, b)) {
        if (c <= b || spanning.count({a, c}) > 0 || spanning.count({b, c}) > 0) continue;
        const Eigen::Vector3d pa = Position(scene, a), pb = Position(scene, b),
                              pc = Position(scene, c);
        const double perimeter = (pb - pa).norm() + (pc - pb).norm() + (pa - pc).norm();
        const double twice_area = (pb - pa).cross(pc - pa).norm();
        if (!(twice_area > 1e-9 * perimeter * perimeter)) continue;  // degenerate
        candidates.push_back({perimeter, {a, b, c}});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  // Kept triangles' third nodes per edge (i < j).
  std::map<std::pair<int, int>, std::vector<int>> opposite;
  std::vector<std::array<int, 3>> triangles;
  for (const auto& candidate : candidates) {
    const std::array<int, 3>& t = candidate.second;
    bool overlaps = false;
    for (int e = 0; e < 3 && !overlaps; ++e) {
      const int i = t[e], j = t[(e + 1) % 3], k = t[(e + 2) % 3];
      const auto found = opposite.find({std::min(i, j), std::max(i, j)});
      if (found == opposite.end()) continue;
      const Eigen::Vector3d pi = Position(scene, i), edge = Position(scene, j) - pi;
      const Eigen::Vector3d side = edge.cross(Position(scene, k) - pi);
      for (int other : found->second) {
        if (side.dot(edge.cross(Position(scene, other) - pi)) > 0.0) overlaps = true;
      }
    }
    if (overlaps) continue;
    triangles.push_back(t);
    for (int e = 0; e < 3; ++e) {
      const int i = t[e], j = t[(e + 1) % 3];
      opposite[{std::min(i, j), std::max(i, j)}].push_back(t[(e + 2) % 3]);
    }
  }
  return triangles;
}

}  // namespace ipstep
