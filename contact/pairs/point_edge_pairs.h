// Pair kind (2D self-contact): a boundary node against a boundary edge of
// another part of the boundary (geometry/point_edge.h). Candidates from a
// spatial hash of the edges' boxes (geometry/spatial_hash.h); barrier gap
// PointEdgeGap (contact/contact_terms.h), weight: the node's; friction: the
// node's velocity relative to the edge's closest point along the lagged edge
// tangent. The intersection check also tests every two boundary edges that
// share no node for crossing (a crossing without a node near the other edge).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"
#include "geometry/spatial_hash.h"

namespace ipstep {

struct PointEdgePair {
  int slot;  // point: index into mesh->nodes
  int edge;  // index into mesh->edges
  bool operator<(const PointEdgePair& o) const {
    return slot != o.slot ? slot < o.slot : edge < o.edge;
  }
  bool operator==(const PointEdgePair& o) const { return slot == o.slot && edge == o.edge; }
};

// A 2D self-contact's friction lagged at the start of the step.
struct PointEdgeFrictionLag {
  int p, a, b;
  Eigen::Vector2d tangent;
  double alpha;
  double normal_force;
};

class PointEdgePairs
    : public PairKind<PointEdgePairs, PointEdgePair, NoPairData, PointEdgeFrictionLag> {
 public:
  using Pair = PointEdgePair;
  // Active only in 2D with self-contact on; `initial`: the initial positions
  // (the hash's cell size is the mean edge length there, at least 2 d_hat).
  PointEdgePairs(const PairSetContext& context, const double* initial);

  const char* name() const override { return "point-edge"; }
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;

 private:
  using Base = PairKind<PointEdgePairs, PointEdgePair, NoPairData, PointEdgeFrictionLag>;
  friend Base;
  // The distance with its gradients over (p, a, b) and the closest point's
  // parameter on the edge.
  struct Measured : PairDistance<3> {
    double alpha = 0.0;
  };

  static Eigen::Vector2d Node(const double* x, int node) {
    return Eigen::Vector2d(x[2 * node], x[2 * node + 1]);
  }
  // Point-edge combinations whose boxes (from a to b, grown by `grow`) overlap.
  void Candidates(const double* a, const double* b, double grow, std::vector<Pair>* pairs) const;
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->weights[pair.slot]; }
  double Distance(const double* x, double t, const Pair& p) const;
  Measured Measure(const double* x, double t, const Pair& p) const;
  // Every candidate with a free node.
  bool Admits(const CandidateRegion&, const Pair&, NoPairData*) const { return true; }
  std::string Describe(const Pair& pair) const;
  // Boundary edges that cross without a node near the other edge.
  std::string FindCrossing(const double* x, double t) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const Measured& measured,
                       PointEdgeFrictionLag* lag) const;
  // Two one-sided terms per contact (the exact 2D split).
  int FrictionTerms(const std::vector<PointEdgeFrictionLag>& lags, const FrictionSettings& friction,
                    IncrementalPotential* potential) const;

  bool active_;
  mutable SpatialHash hash_;
  mutable std::vector<int> scratch_ids_;
};

// Instantiated once, in the .cc (where ForEachCandidate is defined).
extern template class PairKind<PointEdgePairs, PointEdgePair, NoPairData, PointEdgeFrictionLag>;

}  // namespace ipstep
