// Pair kind (3D): an edge of the collision mesh against an edge of a 3D box
// (Obstacle::BoxEdgeDistance), with friction
// (contact/primitive_obstacle_friction.h). Registered after the face-obstacle
// pairs (contact/pairs/face_obstacle_pairs.h), the other half of a 3D mesh's
// contact with obstacle features.
//
// Barrier (EdgeBoxEdgeGap in contact/contact_terms.h): weight the edge's
// (contact/collision_mesh.h); the gap is the true segment-segment distance
// (a lagged closest point would exceed it by its offset, first order in how
// far the cloth slides within a solve: face_obstacle_pairs.h). Friction:
// lagged at the true distance, the closest point's (1 - s, s), the normal
// from the box edge towards it (the sum of the distance's vertex gradients)
// and the normal force kappa w (-B'(d)).
//
// FindPenetration also refuses, beyond the pairs' distances, a mesh edge
// passing through a 3D box and a box edge piercing a face (static states that
// continuous motion cannot reach without touching first, but an initial state
// can).
//
// Cost: each edge is bounded by a ball (centre: its midpoint; radius: half its
// length); an edge whose ball is far from a box skips all of its edges with
// one distance to the box, and each box edge with one point-segment distance,
// before any exact distance.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"
#include "contact/primitive_obstacle_friction.h"

namespace ipstep {

struct BoxEdgePair {
  int edge;  // index into mesh->edges
  int obstacle;
  int box_edge;  // Obstacle::BoxEdge
  bool operator<(const BoxEdgePair& o) const {
    if (edge != o.edge) return edge < o.edge;
    return obstacle != o.obstacle ? obstacle < o.obstacle : box_edge < o.box_edge;
  }
  bool operator==(const BoxEdgePair& o) const {
    return edge == o.edge && obstacle == o.obstacle && box_edge == o.box_edge;
  }
};

class BoxEdgePairs
    : public PairKind<BoxEdgePairs, BoxEdgePair, NoPairData, PrimitiveObstacleFrictionLag> {
 public:
  using Pair = BoxEdgePair;
  // Edges whose nodes are all fixed get no pairs. Empty unless some obstacle
  // has box edges (3D boxes) and the mesh has edges.
  explicit BoxEdgePairs(const PairSetContext& context);

  const char* name() const override { return "box-edge"; }
  bool active() const { return active_; }
  // First fraction of the path from a (obstacle time t_a) to b (t_b) at which
  // an edge reaches its collision-detection goal (conservative, see
  // Obstacle::BoxEdgeTimeOfImpact); kNoImpact if none.
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;

 private:
  using Base = PairKind<BoxEdgePairs, BoxEdgePair, NoPairData, PrimitiveObstacleFrictionLag>;
  friend Base;
  // The distance with its gradients over the edge's ends and the closest
  // point's parameter s on the edge.
  struct Measured : PairDistance<2> {
    double s = 0.0;
  };

  Eigen::Vector3d Vertex(const double* x, int node) const { return ToPoint(x + 3 * node, 3); }
  // Calls f(pair) for every combination whose lower bound at x, time t, is
  // below cutoff(edge) + travel[obstacle] (travel null: 0).
  template <class Cutoff, class F>
  void ForEachNear(const double* x, double t, const Cutoff& cutoff,
                   const std::vector<double>* travel, const F& f) const;
  // The base's candidates: within `grow` at x, time t; Extend's: at the
  // region's start, within d_hat + the edge's reach + the obstacle's travel.
  template <class F>
  void ForEachCandidateAt(const double* x, double t, double grow, const F& f) const;
  template <class F>
  void ForEachCandidateIn(const CandidateRegion& region, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->edge_weights[pair.edge]; }
  double Distance(const double* x, double t, const Pair& pair) const;
  Measured Measure(const double* x, double t, const Pair& pair) const;
  // Extend's distance bound for `edge`, before the obstacle's travel.
  double ExtendCutoff(const CandidateRegion& region, int edge) const;
  bool Admits(const CandidateRegion& region, const Pair& pair, NoPairData* data) const;
  std::string Describe(const Pair& pair) const;
  // A mesh edge through a 3D box, a box edge through a face.
  std::string FindCrossing(const double* x, double t) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const Measured& measured,
                       PrimitiveObstacleFrictionLag* lag) const;

  bool active_ = false;
  std::vector<std::array<int, 2>> edge_slots_;  // slots of each edge's nodes
};

// Instantiated once, in the .cc (where ForEachNear is defined).
extern template class PairKind<BoxEdgePairs, BoxEdgePair, NoPairData, PrimitiveObstacleFrictionLag>;

}  // namespace ipstep
