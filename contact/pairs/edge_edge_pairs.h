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
// constructor or SetRestPositions (the filter passes the scene's initial
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

#include "contact/pair_set.h"
#include "contact/pairs/candidate_cache.h"
#include "contact/pairs/self_contact_mesh.h"
#include "contact/self_gap_terms.h"
#include "contact/sorted_pairs.h"

namespace ipstep {

class EdgeEdgePairs : public PairSet {
 public:
  // `rest`: rest positions (a full configuration) for the mollifier, or null
  // (then those of the first Extend). Registered only when the scene turns
  // self-contact on (contact/pair_kinds.cc).
  explicit EdgeEdgePairs(const PairSetContext& context, const double* rest = nullptr);

  const char* name() const override { return "edge-edge"; }
  bool active() const { return active_; }
  // Rest positions (full state vector) for the mollifier's thresholds.
  void SetRestPositions(const double* x);

  void Clear() override { pairs_.Clear(); }
  size_t size() const override { return pairs_.size(); }
  bool ChangedSinceClear() const override { return pairs_.Changed(); }
  bool Extend(const CandidateRegion& region) override;
  bool Missing(const double* x) const override;

  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  double BroadPhaseSeconds() const override { return broad_phase_seconds_; }
  std::string FindPenetration(const double* x, double t) const override;
  void Near(const double* x, double t, double reach, double* min_distance,
            int* count) const override;
  void AddBarrierGradient(const double* x, double t, double scale,
                          Eigen::VectorXd* g) const override;

  void AddBarrierTerms(IncrementalPotential* potential) const override;
  void LagFriction(const double* x, double t) override;
  int AddFrictionTerms(const FrictionSettings& friction,
                       IncrementalPotential* potential) const override;

  struct Pair {
    int e;  // indices into mesh->edges, e < f
    int f;
    bool operator<(const Pair& o) const { return e != o.e ? e < o.e : f < o.f; }
    bool operator==(const Pair& o) const { return e == o.e && f == o.f; }
  };
  const std::vector<Pair>& pairs() const { return pairs_.pairs(); }
  double Distance(const double* x, const Pair& pair) const;
  // eps_x of a pair (0 before rest positions are known: no mollifier).
  double MollifierThreshold(const Pair& pair) const;

 private:
  bool PairHasFreeNode(const Pair& pair) const;
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;

  PairSetContext context_;
  SelfContactMesh geometry_;
  bool active_ = false;
  std::vector<double> rest_length2_;  // per edge
  SortedPairs<Pair> pairs_;
  std::vector<SelfFrictionLag> friction_;
  mutable Bvh bvh_;
  mutable std::vector<int> ids_;
  mutable CandidateCache<Pair> candidates_;  // ForEachCandidate's broad-phase output
  mutable double broad_phase_seconds_ = 0.0;
};

}  // namespace ipstep
