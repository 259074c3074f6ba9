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

#include "contact/pair_set.h"
#include "contact/sorted_pairs.h"
#include "geometry/spatial_hash.h"

namespace ipstep {

class PointEdgePairs : public PairSet {
 public:
  // Active only in 2D with self-contact on; `initial`: the initial positions
  // (the hash's cell size is the mean edge length there, at least 2 d_hat).
  PointEdgePairs(const PairSetContext& context, const double* initial);

  const char* name() const override { return "point-edge"; }
  void Clear() override { pairs_.Clear(); }
  size_t size() const override { return pairs_.size(); }
  bool ChangedSinceClear() const override { return pairs_.Changed(); }
  bool Extend(const CandidateRegion& region) override;
  bool Missing(const double* x) const override;

  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  std::string FindPenetration(const double* x, double t) const override;
  void Near(const double* x, double t, double reach, double* min_distance,
            int* count) const override;
  void AddBarrierGradient(const double* x, double t, double scale,
                          Eigen::VectorXd* g) const override;

  void AddBarrierTerms(IncrementalPotential* potential) const override;
  void LagFriction(const double* x, double t) override;
  int AddFrictionTerms(const FrictionSettings& friction,
                       IncrementalPotential* potential) const override;

 private:
  struct Pair {
    int slot;  // point: index into mesh->nodes
    int edge;  // index into mesh->edges
    bool operator<(const Pair& o) const { return slot != o.slot ? slot < o.slot : edge < o.edge; }
    bool operator==(const Pair& o) const { return slot == o.slot && edge == o.edge; }
  };
  struct LaggedFriction {
    int p, a, b;
    Eigen::Vector2d tangent;
    double alpha;
    double normal_force;
  };

  static Eigen::Vector2d Node(const double* x, int node) {
    return Eigen::Vector2d(x[2 * node], x[2 * node + 1]);
  }
  // Point-edge combinations whose boxes (from a to b, grown by `grow`) overlap.
  void Candidates(const double* a, const double* b, double grow, std::vector<Pair>* pairs) const;
  bool HasFreeNode(const Pair& pair) const;
  double Distance(const double* x, const Pair& p) const;

  PairSetContext c_;
  bool active_;
  SortedPairs<Pair> pairs_;
  std::vector<LaggedFriction> lagged_;
  mutable SpatialHash hash_;
  mutable std::vector<int> scratch_ids_;
};

}  // namespace ipstep
