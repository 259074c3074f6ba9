// Pair kind: a contact edge (2D boundary edge, 3D cloth edge) against an edge
// feature of an obstacle (sphere / circle centre, 2D box corner;
// Obstacle::EdgeDistance): the features an edge can touch with both end nodes
// outside the obstacle. Barrier gap (EdgeObstacleGap, contact/contact_terms.h),
// weight: the edge's. Against sphere / circle centres the gap is the distance
// of the edge's closest point lagged at the step start (re-lagged by Lag while
// it is more than 1 % farther than the true closest point): the true
// point-segment distance is concave in the segment's rocking mode and
// Gauss-Newton then converged linearly (docs/contact.md). 2D box corners (no
// radius) use the true distance: with a lag, a corner the edge slides along
// sees sqrt(d^2 + s^2) >> d and the barrier vanishes.
// 2D also checks that no edge crosses a circle or a box corner between two
// configurations (a segment meets a half-space only where an end point does, so
// planes need no check): TimeOfImpact reports such a path as blocked and
// ShrinkToClear halves the step until it is clear.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"

namespace ipstep {

struct EdgeObstaclePair {
  int edge;  // index into mesh->edges
  int obstacle;
  int feature;  // Obstacle::EdgeFeature
  bool operator<(const EdgeObstaclePair& o) const {
    if (edge != o.edge) return edge < o.edge;
    return obstacle != o.obstacle ? obstacle < o.obstacle : feature < o.feature;
  }
  bool operator==(const EdgeObstaclePair& o) const {
    return edge == o.edge && obstacle == o.obstacle && feature == o.feature;
  }
};

// Per pair: the lagged closest-point parameter (read by its term).
class EdgeObstaclePairs : public PairKind<EdgeObstaclePairs, EdgeObstaclePair, double> {
 public:
  using Pair = EdgeObstaclePair;
  explicit EdgeObstaclePairs(const PairSetContext& context);

  const char* name() const override { return "edge-obstacle"; }
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  double ShrinkToClear(const double* from, const double* to, double t) const override;
  // The 2D crossings (Conflict), then the pairs' distances.
  std::string FindPenetration(const double* x, double t) const override;

  bool TermsReadLags() const override { return !pairs_.empty(); }
  double Lag(const double* x) override;
  void SaveLags() override { saved_ = pairs_.data(); }
  void RestoreLags() override { pairs_.data() = saved_; }

 private:
  using Base = PairKind<EdgeObstaclePairs, EdgeObstaclePair, double>;
  friend Base;

  Eigen::Vector3d End(const double* x, int edge, int end) const {
    return ToPoint(x + c_.dimension * c_.mesh->edges[edge][end], c_.dimension);
  }
  // Every edge-feature combination (no broad phase).
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->edge_weights[pair.edge]; }
  double Distance(const double* x, double t, const Pair& p) const;
  PairDistance<2> Measure(const double* x, double t, const Pair& p) const;
  // A new pair's lag: the closest point at the start.
  bool Admits(const CandidateRegion& region, const Pair& pair, double* alpha) const;
  std::string Describe(const Pair& pair) const;
  void SetGap(size_t k, Term* term) const;
  // 2D: empty if no edge at x (time t) meets a circle or box and, moving
  // linearly from a, no circle centre or box corner crosses an edge (a == x:
  // the static check only); else a description.
  std::string Conflict(const double* a, const double* x, double t) const;

  std::vector<std::array<int, 2>> edge_slots_;  // slots of each edge's nodes
  std::vector<double> saved_;
};

// Instantiated once, in the .cc (where ForEachCandidate is defined).
extern template class PairKind<EdgeObstaclePairs, EdgeObstaclePair, double>;

}  // namespace ipstep
