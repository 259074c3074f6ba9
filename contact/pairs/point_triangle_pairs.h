// 3D self-contact: every contact node against every face of the collision
// mesh that does not contain it (contact/collision_mesh.h: the faces must be
// ONE triangulation of the surface for this to mean anything). Active when
// dimension == 3 and the mesh has faces.
//
// Barrier: PointTriangleGap (contact/self_gap_terms.h) with the BarrierLoss,
// weight the node's (its area share), analytic curvature. Candidates: the
// faces' boxes over the motion grown by d_hat + max_reach overlap the node's
// box (BVH, geometry/bvh.h), then the exact distance at the start, minus how
// far the primitives move, below d_hat + the pair's reach. Time of impact:
// additive conservative advancement (geometry/self_ccd.h) of every pair whose
// boxes grown by the margin overlap. FindPenetration: distances at most the
// margin, and (independently of the distances) any two faces without a
// common node that intersect (geometry/triangle_intersection.h). Friction:
// lagged normal force kappa w (-B'(d)), tangent basis of the closest points'
// direction, relative velocity of the node and its closest point on the
// face at the lagged barycentric weights (SelfFriction).
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

class PointTrianglePairs : public PairSet {
 public:
  // Registered only when the scene turns self-contact on
  // (contact/pair_kinds.cc).
  explicit PointTrianglePairs(const PairSetContext& context);

  const char* name() const override { return "point-triangle"; }
  bool active() const { return active_; }

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
    int node;  // node id
    int face;  // index into mesh->faces
    bool operator<(const Pair& o) const { return node != o.node ? node < o.node : face < o.face; }
    bool operator==(const Pair& o) const { return node == o.node && face == o.face; }
  };
  const std::vector<Pair>& pairs() const { return pairs_.pairs(); }
  // Distance of a pair at x (gradients over (p, a, b, c) and closest-point
  // weights when not null).
  double Distance(const double* x, const Pair& pair, Eigen::Vector3d* grad = nullptr,
                  Eigen::Vector3d* weights = nullptr) const;

 private:
  bool PairHasFreeNode(const Pair& pair) const;
  // Calls f(pair) for every node-face combination (no common node) whose
  // boxes over a -> b overlap once the faces' are grown by `grow`.
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;

  PairSetContext context_;
  SelfContactMesh geometry_;
  bool active_ = false;
  SortedPairs<Pair> pairs_;
  std::vector<SelfFrictionLag> friction_;
  mutable Bvh bvh_;
  mutable std::vector<int> ids_;
  mutable CandidateCache<Pair> candidates_;  // ForEachCandidate's broad-phase output
  mutable double broad_phase_seconds_ = 0.0;
};

}  // namespace ipstep
