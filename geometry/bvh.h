// Broad phase: a bounding volume hierarchy of axis-aligned boxes (a binary
// tree, each node's box the union of its children's, leaves of at most
// kLeafSize boxes). Built top-down, splitting at the median centre along the
// longest axis of the centres' extent: O(n log n), depth O(log n). A query
// visits only subtrees whose box overlaps the query box. Rebuilt for every
// query set (the contact filter's queries are over a different motion each
// time; a build is a few sorts of n indices).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace ipstep {

class Bvh {
 public:
  static constexpr int kLeafSize = 4;

  // Boxes [lower[i], upper[i]], id i.
  void Build(const std::vector<Eigen::Vector3d>& lower, const std::vector<Eigen::Vector3d>& upper);
  // Ids of boxes overlapping (closed) [lower, upper], in tree order (unsorted,
  // no repeats) appended to *ids after clearing it.
  void Query(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
             std::vector<int>* ids) const;
  size_t size() const { return order_.size(); }

 private:
  struct Node {
    Eigen::Vector3d lower, upper;
    int begin = 0, end = 0;  // range of order_ (leaves)
    int left = -1, right = -1;
  };
  int BuildRange(int begin, int end);

  std::vector<Eigen::Vector3d> lower_, upper_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
  mutable std::vector<int> stack_;
};

}  // namespace ipstep
