// 3D self-contact: every pair of contact edges without a common node
// (contact/collision_mesh.h; with ONE triangulation of the surface, its
// triangles' unique edges). Active when dimension == 3 and the mesh has faces
// (edges alone, a wire mesh, would work the same; the scene's surface decides).
//
// Barrier: EdgeEdgeGap (contact/self_gap_terms.h), IPC's mollified barrier
// m(c) B(d) for nearly parallel edges (geometry/edge_edge_mollifier.h) as an
// effective gap with the BarrierLoss; weight the first edge's weight (pairs
// are stored with e < f; both edges of a grid have the same weight). The
// mollifier's threshold uses the rest lengths: the positions given to the
// constructor or SetRestPositions (the contact state passes the initial
// positions), or else those of the first Extend.
// Candidates, time of impact, checks: as PointTrianglePairs (additive CCD of
// the segment-segment distance, geometry/self_ccd.h). Friction: the relative
// velocity of the closest points (1 - s) a0 + s a1 - (1 - t) b0 - t b1 at the
// lagged (s, t), normal force kappa w (-m B'(d)).
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"
#include "contact/pairs/self_broad_phase.h"
#include "contact/pairs/self_contact_mesh.h"
#include "contact/self_gap_terms.h"

namespace ipstep {

struct EdgeEdgePair {
  int e;  // indices into mesh->edges, e < f
  int f;
  bool operator<(const EdgeEdgePair& o) const { return e != o.e ? e < o.e : f < o.f; }
  bool operator==(const EdgeEdgePair& o) const { return e == o.e && f == o.f; }
};

class EdgeEdgePairs : public PairKind<EdgeEdgePairs, EdgeEdgePair, NoPairData, SelfFrictionLag> {
 public:
  using Pair = EdgeEdgePair;
  // `rest`: rest positions (a full configuration) for the mollifier, or null
  // (then those of the first Extend). Registered only when the scene turns
  // self-contact on (contact/pair_kinds.cc).
  explicit EdgeEdgePairs(const PairSetContext& context, const double* rest = nullptr);

  const char* name() const override { return "edge-edge"; }
  bool active() const { return active_; }
  // Rest positions (full state vector) for the mollifier's thresholds.
  void SetRestPositions(const double* x);

  bool Extend(const CandidateRegion& region) override;
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  double BroadPhaseSeconds() const override { return broad_phase_.seconds(); }

  double Distance(const double* x, const Pair& pair) const;
  // eps_x of a pair (0 before rest positions are known: no mollifier).
  double MollifierThreshold(const Pair& pair) const;

 private:
  using Base = PairKind<EdgeEdgePairs, EdgeEdgePair, NoPairData, SelfFrictionLag>;
  friend Base;
  // The segment-segment distance with its gradients over (a0, a1, b0, b1),
  // the closest points' parameters s, t and the four positions.
  struct Measured : PairDistance<4> {
    double s = 0.0, t = 0.0;
    std::array<Eigen::Vector3d, 4> points;
  };

  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->edge_weights[pair.e]; }
  double Distance(const double* x, double t, const Pair& pair) const {
    (void)t;
    return Distance(x, pair);
  }
  Measured Measure(const double* x, double t, const Pair& pair) const;
  bool Admits(const CandidateRegion& region, const Pair& pair, NoPairData* data) const;
  std::string Describe(const Pair& pair) const;
  // grad (m B) = B grad m + m B' grad d (the mollified barrier of the terms).
  void AddPairBarrierGradient(const Pair& pair, const Measured& measured, double scale,
                              Eigen::VectorXd* g) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const Measured& measured,
                       SelfFrictionLag* lag) const;

  SelfContactMesh geometry_;
  bool active_ = false;
  std::vector<double> rest_length2_;  // per edge
  SelfBroadPhase<Pair> broad_phase_;
};

// Instantiated once, in the .cc (where ForEachCandidate is defined).
extern template class PairKind<EdgeEdgePairs, EdgeEdgePair, NoPairData, SelfFrictionLag>;

}  // namespace ipstep
