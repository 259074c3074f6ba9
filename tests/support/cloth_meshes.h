// Test and benchmark helper: collision meshes of square cloth grids with ONE
// triangulation (two triangles per quad, the diagonal from the lower-left
// corner), edges the triangles' unique edges (contact/collision_mesh.h).
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <set>
#include <vector>

#include <Eigen/Core>

#include "contact/collision_mesh.h"

namespace ipstep::testing {

// Appends an nx x ny grid of spacing `a` to `mesh`, its node ids from
// `first_node` on (node (i, j) is first_node + j nx + i), with positions
// place(i, j) written into x (resized as needed). Weights: a^2 per node,
// a^2 / 2 per edge and face.
inline void AddClothGrid(int nx, int ny, double a, int first_node,
                         const std::function<Eigen::Vector3d(int, int)>& place, CollisionMesh* mesh,
                         std::vector<double>* x) {
  auto id = [&](int i, int j) { return first_node + j * nx + i; };
  x->resize(std::max<size_t>(x->size(), 3 * static_cast<size_t>(id(nx - 1, ny - 1) + 1)), 0.0);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Eigen::Vector3d p = place(i, j);
      for (int k = 0; k < 3; ++k) (*x)[3 * id(i, j) + k] = p[k];
      mesh->nodes.push_back(id(i, j));
      mesh->weights.push_back(a * a);
    }
  }
  std::set<std::array<int, 2>> edges;
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int p00 = id(i, j), p10 = id(i + 1, j), p01 = id(i, j + 1), p11 = id(i + 1, j + 1);
      for (std::array<int, 3> f : {std::array<int, 3>{p00, p10, p11}, {p00, p11, p01}}) {
        std::sort(f.begin(), f.end());
        mesh->faces.push_back(f);
        mesh->face_weights.push_back(0.5 * a * a);
        edges.insert({f[0], f[1]});
        edges.insert({f[1], f[2]});
        edges.insert({f[0], f[2]});
      }
    }
  }
  for (const auto& e : edges) {
    mesh->edges.push_back(e);
    mesh->edge_weights.push_back(0.5 * a * a);
  }
}

// An n x n cloth of spacing a folded in half over the line i = n/2: the
// columns i < n/2 flat at z = 0, the others mirrored back above them at
// height `gap` (shifted by a/2 so that nodes sit over faces, not over nodes).
inline std::vector<double> FoldedCloth(int n, double a, double gap, CollisionMesh* mesh) {
  std::vector<double> x;
  const int half = n / 2;
  AddClothGrid(
      n, n, a, 0,
      [&](int i, int j) {
        if (i < half) return Eigen::Vector3d(i * a, j * a, 0.0);
        return Eigen::Vector3d((n - 1 - i) * a + 0.5 * a, j * a + 0.5 * a, gap);
      },
      mesh, &x);
  return x;
}

}  // namespace ipstep::testing
