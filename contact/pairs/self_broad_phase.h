// The broad phase of the 3D self-contact pair kinds (point_triangle_pairs.h,
// edge_edge_pairs.h): a BVH (geometry/bvh.h) over one side's primitives (the
// faces, or the edges) with their boxes over a motion, queried with the box of
// each primitive of the other side (a node, or an edge), its last answer kept
// (contact/pairs/candidate_cache.h). A kind says only which primitives the
// tree holds, which ones query it and which pairs of the two it keeps.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "contact/pairs/candidate_cache.h"
#include "contact/pairs/self_contact_mesh.h"
#include "core/scoped_timer.h"
#include "geometry/bvh.h"

namespace ipstep {

template <class Pair>
class SelfBroadPhase {
 public:
  // Calls f(pair) for every pair that keep(i, j, &pair) makes (returning true),
  // over the queries i in [0, num_queries) in order and, for each, the tree's
  // primitives j in ascending order whose boxes over a -> b grown by `grow`
  // overlap the box of query_nodes(i) (a std::array of node ids) over a -> b.
  // A repeat of the last query (a, b, grow) over configurations of
  // `num_coordinates` gives the kept candidates again.
  template <size_t N, class QueryNodes, class Keep, class F>
  void ForEachCandidate(const double* a, const double* b, double grow, int num_coordinates,
                        const std::vector<std::array<int, N>>& tree, size_t num_queries,
                        const QueryNodes& query_nodes, const Keep& keep, const F& f) const {
    auto find = [&](std::vector<Pair>* candidates) {
      Query(a, b, grow, tree, num_queries, query_nodes, [&](size_t i, std::vector<int>* ids) {
        std::sort(ids->begin(), ids->end());
        for (int j : *ids) {
          Pair pair;
          if (keep(i, j, &pair)) candidates->push_back(pair);
        }
      });
    };
    candidates_.ForEach(a, b, num_coordinates, grow, &seconds_, find, f);
  }

  // Calls on_query(i, &ids) for every query i as above, ids the overlapping
  // primitives in the tree's order (not cached; timed as broad phase).
  template <size_t N, class QueryNodes, class OnQuery>
  void Overlaps(const double* a, const double* b, double grow,
                const std::vector<std::array<int, N>>& tree, size_t num_queries,
                const QueryNodes& query_nodes, const OnQuery& on_query) const {
    ScopedTimer timer(&seconds_);
    Query(a, b, grow, tree, num_queries, query_nodes, on_query);
  }

  // Wall time of the tree builds and queries so far [s].
  double seconds() const { return seconds_; }

 private:
  template <size_t N, class QueryNodes, class OnQuery>
  void Query(const double* a, const double* b, double grow,
             const std::vector<std::array<int, N>>& tree, size_t num_queries,
             const QueryNodes& query_nodes, const OnQuery& on_query) const {
    SelfContactMesh::BuildTree(tree, a, b, grow, &bvh_);
    for (size_t i = 0; i < num_queries; ++i) {
      Eigen::Vector3d lower, upper;
      SelfContactMesh::MotionBox(a, b, query_nodes(i), 0.0, &lower, &upper);
      bvh_.Query(lower, upper, &ids_);
      on_query(i, &ids_);
    }
  }

  mutable Bvh bvh_;
  mutable std::vector<int> ids_;
  mutable CandidateCache<Pair> candidates_;
  mutable double seconds_ = 0.0;
};

}  // namespace ipstep
