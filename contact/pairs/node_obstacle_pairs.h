// Pair kind: a contact node against an obstacle (plane, sphere / circle, box),
// with friction. Barrier gap: the point-obstacle distance
// (Obstacle::Distance; PointObstacleGap in contact/contact_terms.h), weight:
// the node's. Friction: the node's velocity relative to the obstacle's, in
// the tangent basis of the obstacle's normal lagged at the node.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_set.h"
#include "contact/sorted_pairs.h"

namespace ipstep {

class NodeObstaclePairs : public PairSet {
 public:
  explicit NodeObstaclePairs(const PairSetContext& context) : c_(context) {}

  const char* name() const override { return "node-obstacle"; }
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
    int slot;  // index into mesh->nodes
    int obstacle;
    bool operator<(const Pair& o) const {
      return slot != o.slot ? slot < o.slot : obstacle < o.obstacle;
    }
    bool operator==(const Pair& o) const { return slot == o.slot && obstacle == o.obstacle; }
  };
  struct LaggedFriction {
    int node;
    Eigen::Matrix3d tangents;
    Eigen::Vector3d obstacle_velocity;  // at the lag's time
    double normal_force;
    const Obstacle* obstacle;  // its friction coefficient (FrictionSettings)
  };

  Eigen::Vector3d Point(const double* x, int slot) const;

  PairSetContext c_;
  SortedPairs<Pair> pairs_;
  std::vector<LaggedFriction> lagged_;
};

}  // namespace ipstep
