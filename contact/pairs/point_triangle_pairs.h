// 3D self-contact: every contact node against every face of the collision
// mesh that does not contain it (contact/collision_mesh.h: the faces must be
// ONE triangulation of the surface for this to mean anything). Active when
// dimension == 3 and the mesh has faces.
//
// Barrier: PointTriangleGap (contact/self_gap_terms.h) with the BarrierLoss,
// weight the node's (its area share), analytic curvature. Candidates: the
// faces' boxes over the motion grown by d_hat + max_reach overlap the node's
// box (contact/pairs/self_broad_phase.h), then the exact distance at the
// start, minus how far the primitives move, below d_hat + the pair's reach.
// Time of impact: additive conservative advancement (geometry/self_ccd.h) of
// every pair whose boxes grown by the margin overlap. FindPenetration:
// distances at most the margin, and (independently of the distances) any two
// faces without a common node that intersect
// (geometry/triangle_intersection.h). Friction:
// lagged normal force kappa w (-B'(d)), tangent basis of the closest points'
// direction, relative velocity of the node and its closest point on the
// face at the lagged barycentric weights (SelfFriction).
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

struct PointTrianglePair {
  int node;  // node id
  int face;  // index into mesh->faces
  bool operator<(const PointTrianglePair& o) const {
    return node != o.node ? node < o.node : face < o.face;
  }
  bool operator==(const PointTrianglePair& o) const { return node == o.node && face == o.face; }
};

class PointTrianglePairs
    : public PairKind<PointTrianglePairs, PointTrianglePair, NoPairData, SelfFrictionLag> {
 public:
  using Pair = PointTrianglePair;
  // Registered only when the scene turns self-contact on
  // (contact/pair_kinds.cc).
  explicit PointTrianglePairs(const PairSetContext& context);

  const char* name() const override { return "point-triangle"; }
  bool active() const { return active_; }

  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  double BroadPhaseSeconds() const override { return broad_phase_.seconds(); }

 private:
  using Base = PairKind<PointTrianglePairs, PointTrianglePair, NoPairData, SelfFrictionLag>;
  friend Base;
  // The distance with its gradients over (p, a, b, c) and the closest
  // point's barycentric weights.
  struct Measured : PairDistance<4> {
    Eigen::Vector3d weights;
  };

  // Calls f(pair) for every node-face combination (no common node) whose
  // boxes over a -> b overlap once the faces' are grown by `grow`.
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->weights[geometry_.slot(pair.node)]; }
  double Distance(const double* x, double t, const Pair& pair) const;
  Measured Measure(const double* x, double t, const Pair& pair) const;
  bool Admits(const CandidateRegion& region, const Pair& pair, NoPairData* data) const;
  std::string Describe(const Pair& pair) const;
  // Faces without a common node that intersect.
  std::string FindCrossing(const double* x, double t) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const Measured& measured,
                       SelfFrictionLag* lag) const;

  SelfContactMesh geometry_;
  bool active_ = false;
  SelfBroadPhase<Pair> broad_phase_;
};

// Instantiated once, in the .cc (where ForEachCandidate is defined).
extern template class PairKind<PointTrianglePairs, PointTrianglePair, NoPairData, SelfFrictionLag>;

}  // namespace ipstep
