// Pair kind: a contact node against an obstacle (plane, sphere / circle, box),
// with friction. Barrier gap: the point-obstacle distance
// (Obstacle::Distance; PointObstacleGap in contact/contact_terms.h), weight:
// the node's. Friction: the node's velocity relative to the obstacle's, in
// the tangent basis of the obstacle's normal lagged at the node.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"

namespace ipstep {

struct NodeObstaclePair {
  int slot;  // index into mesh->nodes
  int obstacle;
  bool operator<(const NodeObstaclePair& o) const {
    return slot != o.slot ? slot < o.slot : obstacle < o.obstacle;
  }
  bool operator==(const NodeObstaclePair& o) const {
    return slot == o.slot && obstacle == o.obstacle;
  }
};

// A node-obstacle contact's friction lagged at the start of the step.
struct NodeObstacleFrictionLag {
  int node;
  Eigen::Matrix3d tangents;
  Eigen::Vector3d obstacle_velocity;  // at the lag's time
  double normal_force;
  const Obstacle* obstacle;  // its friction coefficient (FrictionSettings)
};

class NodeObstaclePairs
    : public PairKind<NodeObstaclePairs, NodeObstaclePair, NoPairData, NodeObstacleFrictionLag> {
 public:
  using Pair = NodeObstaclePair;
  explicit NodeObstaclePairs(const PairSetContext& context) : Base(context) {}

  const char* name() const override { return "node-obstacle"; }
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;

 private:
  using Base = PairKind<NodeObstaclePairs, NodeObstaclePair, NoPairData, NodeObstacleFrictionLag>;
  friend Base;

  Eigen::Vector3d Point(const double* x, int slot) const;
  // Every node-obstacle combination (no broad phase).
  template <class F>
  void ForEachCandidate(const double* a, const double* b, double grow, const F& f) const;
  bool HasFreeNode(const Pair& pair) const { return (*c_.node_free)[pair.slot]; }
  double Weight(const Pair& pair) const { return c_.mesh->weights[pair.slot]; }
  double Distance(const double* x, double t, const Pair& pair) const;
  PairDistance<1> Measure(const double* x, double t, const Pair& pair) const;
  bool Admits(const CandidateRegion& region, const Pair& pair, NoPairData* data) const;
  std::string Describe(const Pair& pair) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const PairDistance<1>& measured,
                       NodeObstacleFrictionLag* lag) const;
  // 3D: one term per contact (side 0); 2D: the exact split, one term per side.
  int FrictionTerms(const std::vector<NodeObstacleFrictionLag>& lags,
                    const FrictionSettings& friction, IncrementalPotential* potential) const;
};

// Instantiated once, in the .cc (where ForEachCandidate is defined).
extern template class PairKind<NodeObstaclePairs, NodeObstaclePair, NoPairData,
                               NodeObstacleFrictionLag>;

}  // namespace ipstep
