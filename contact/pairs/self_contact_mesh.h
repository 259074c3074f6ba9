// What the two 3D self-contact pair kinds (point_triangle_pairs.h,
// edge_edge_pairs.h) share: node positions, node slots (the collision mesh's
// table, NodeSlot), the boxes of primitives over a linear motion and their
// tree (geometry/bvh.h), which the broad phase (self_broad_phase.h) queries,
// the tangent basis of a contact normal.
//
// Broad phase: the BVH was measured faster than the spatial hash on a folded
// 100 x 100 cloth (bench/broad_phase_bench.cc, numbers in the commit and
// docs), and it needs no cell size.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "contact/collision_mesh.h"
#include "geometry/bvh.h"

namespace ipstep {

class SelfContactMesh {
 public:
  explicit SelfContactMesh(const CollisionMesh* mesh) : mesh_(mesh) {}
  const CollisionMesh& mesh() const { return *mesh_; }
  int slot(int node) const { return NodeSlot(*mesh_, node); }
  // Coordinates of a configuration up to the mesh's largest node (what the
  // mesh's primitives read of it).
  int num_coordinates() const { return 3 * static_cast<int>(mesh_->node_slots.size()); }

  static Eigen::Vector3d Vertex(const double* x, int node) {
    return Eigen::Vector3d(x[3 * node], x[3 * node + 1], x[3 * node + 2]);
  }

  // Box of `nodes` over the motion a -> b, grown by `grow`.
  template <size_t N>
  static void MotionBox(const double* a, const double* b, const std::array<int, N>& nodes,
                        double grow, Eigen::Vector3d* lower, Eigen::Vector3d* upper) {
    *lower = Vertex(a, nodes[0]);
    *upper = *lower;
    for (size_t k = 0; k < N; ++k) {
      const Eigen::Vector3d p = Vertex(a, nodes[k]), q = Vertex(b, nodes[k]);
      *lower = lower->cwiseMin(p).cwiseMin(q);
      *upper = upper->cwiseMax(p).cwiseMax(q);
    }
    *lower -= Eigen::Vector3d::Constant(grow);
    *upper += Eigen::Vector3d::Constant(grow);
  }

  // Builds `bvh` over the primitives (faces or edges) over a -> b, grown by
  // `grow`.
  template <size_t N>
  static void BuildTree(const std::vector<std::array<int, N>>& primitives, const double* a,
                        const double* b, double grow, Bvh* bvh) {
    std::vector<Eigen::Vector3d> lower(primitives.size()), upper(primitives.size());
    for (size_t i = 0; i < primitives.size(); ++i) {
      MotionBox(a, b, primitives[i], grow, &lower[i], &upper[i]);
    }
    bvh->Build(lower, upper);
  }

 private:
  const CollisionMesh* mesh_;
};

// Orthonormal tangent basis (3 x 2) of the plane normal to the unit n.
inline Eigen::Matrix<double, 3, 2> SelfTangentBasis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n[0]) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t0 = (helper - helper.dot(n) * n).normalized();
  Eigen::Matrix<double, 3, 2> basis;
  basis << t0, n.cross(t0);
  return basis;
}

}  // namespace ipstep
