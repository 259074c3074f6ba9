#include "geometry/bvh.h"

#include <algorithm>

namespace ipstep {

void Bvh::Build(const std::vector<Eigen::Vector3d>& lower,
                const std::vector<Eigen::Vector3d>& upper) {
  lower_ = lower;
  upper_ = upper;
  order_.resize(lower.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  nodes_.clear();
  nodes_.reserve(2 * order_.size() / kLeafSize + 2);
  if (!order_.empty()) BuildRange(0, static_cast<int>(order_.size()));
}

int Bvh::BuildRange(int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::Vector3d lo = lower_[order_[begin]], hi = upper_[order_[begin]];
  Eigen::Vector3d centre_lo = 0.5 * (lo + hi), centre_hi = centre_lo;
  for (int k = begin + 1; k < end; ++k) {
    const int i = order_[k];
    lo = lo.cwiseMin(lower_[i]);
    hi = hi.cwiseMax(upper_[i]);
    const Eigen::Vector3d centre = 0.5 * (lower_[i] + upper_[i]);
    centre_lo = centre_lo.cwiseMin(centre);
    centre_hi = centre_hi.cwiseMax(centre);
  }
  nodes_[index].lower = lo;
  nodes_[index].upper = hi;
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= kLeafSize) return index;
  int axis = 0;
  (centre_hi - centre_lo).maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) {
                     return lower_[a][axis] + upper_[a][axis] < lower_[b][axis] + upper_[b][axis];
                   });
  const int left = BuildRange(begin, middle);
  const int right = BuildRange(middle, end);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void Bvh::Query(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                std::vector<int>* ids) const {
  ids->clear();
  if (nodes_.empty()) return;
  auto overlaps = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return (lo.array() <= upper.array()).all() && (lower.array() <= hi.array()).all();
  };
  stack_.clear();
  stack_.push_back(0);
  while (!stack_.empty()) {
    const Node& node = nodes_[stack_.back()];
    stack_.pop_back();
    if (!overlaps(node.lower, node.upper)) continue;
    if (node.left < 0) {
      for (int k = node.begin; k < node.end; ++k) {
        const int i = order_[k];
        if (overlaps(lower_[i], upper_[i])) ids->push_back(i);
      }
    } else {
      stack_.push_back(node.left);
      stack_.push_back(node.right);
    }
  }
}

}  // namespace ipstep
