// The contact step filter (core/step_filter.h): keeps every iterate free of
// penetration and tunnelling, maintains the barrier terms of the pairs in reach,
// the adaptive barrier stiffness, the lagged friction terms, and reports
// min_distance / active_contacts.
//
// Pairs: contact nodes against obstacles, contact edges (2D boundary edges, 3D
// cloth springs; contact/collision_mesh.h) against the edge features of
// spheres / circles and 2D boxes (Obstacle::EdgeDistance), 3D cloth faces
// against the face features of spheres and 3D boxes (centre, corners;
// Obstacle::FaceDistance) and 3D cloth edges against 3D box edges
// (Obstacle::BoxEdgeDistance; both in contact/mesh_obstacle_pairs.h), and (2D
// self-contact) boundary nodes against boundary edges of other parts of the
// boundary (spatial-hash broad phase). A pair's barrier term (family "contact") is
//   w_U kappa w_i B(d)  (contact/barrier.h)
// with w_i the node's, the edge's or the face's weight. Edge-obstacle, face
// and box-edge pairs have no friction terms. Against sphere / circle centres
// and 2D box corners, an edge's or face's barrier gap is the distance of its
// closest point lagged at the step start (re-lagged and re-solved while it is
// more than 1 % farther than the true closest point, at most 3 times per
// step): the true point-segment distance is concave in the segment's rocking
// mode and Gauss-Newton then converged linearly (docs/contact.md). Faces
// against 3D box corners and edges against 3D box edges use the true distance
// (a lagged point's excess is first order in the slide there; see
// contact/mesh_obstacle_pairs.h). Continuous collision detection, evaluation
// failures and the checks use the true distance.
// A node-obstacle pair's friction term (family "friction", contact/friction.h) is
//   w_R mu lambda f0(|v_t|),  lambda = kappa w_i (-B'(d)) lagged.
//
// Within a step:
//  * BeginStep(x_n) picks the candidate pairs: those that can come within d_hat
//    during the step (distance at x_n below d_hat plus twice the predictor's
//    displacement plus the obstacle's travel). Terms of pairs out of reach are
//    exactly zero, so a generous set costs little.
//  * RefreshTerms(x) after each solve adds every pair within d_hat of the
//    solution that the set missed (and its neighbours within 2 d_hat), and asks
//    for another solve. The set only grows within a step, so this terminates.
//  * Moving obstacles: the solve needs a start free of penetration at the
//    obstacles' positions. When an obstacle would sweep into x_n during the
//    step, its time is advanced in stages: each solve uses the obstacles at a
//    time tau, and RefreshTerms moves tau towards t_{n+1} as far as continuous
//    collision detection against the current solution allows (0.8 of the way to
//    impact), then solves again. The step is feasible only once tau = t_{n+1}.
//  * Friction: normal forces and tangent bases are lagged at x_n; with
//    friction_iterations > 1 they are re-lagged at the solution and the step is
//    solved again, up to that many lags in total.
//  * Adaptive kappa (when no fixed kappa is given): starts at kappa_min, the
//    stiffness at which a barrier at d_hat/2 is as stiff as a node's inertia
//    (m / w_U per unit weight); when contact first appears it is set, as in IPC,
//    to the value that best balances the barrier gradient against the gradient
//    of the rest of the incremental potential, kappa = -g_B.g_E / |g_B|^2,
//    clamped to [kappa_min, kappa_max = 1e4 kappa_min]; at the start of a step
//    it doubles (up to kappa_max) while the smallest gap is below d_hat / 100
//    and still shrinking.
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/collision_mesh.h"
#include "contact/mesh_obstacle_pairs.h"
#include "contact/obstacle.h"
#include "contact/spatial_hash.h"
#include "core/incremental_potential.h"
#include "core/state.h"
#include "core/step_filter.h"

namespace ipstep {

struct ContactOptions {
  double d_hat = 1e-3;
  double kappa = 0.0;  // > 0: fixed; 0: adaptive
  bool self_contact = false;
  std::vector<Obstacle> obstacles;
};

struct FrictionOptions {
  double mu = 0.0;
  double epsilon_v = 1e-3;  // [m/s]
  int iterations = 1;       // lags per step (1: lagged at the step start only)
};

class ContactManager : public StepFilter {
 public:
  static constexpr char kContactFamily[] = "contact";
  static constexpr char kFrictionFamily[] = "friction";

  // `potential` and `state` must outlive the manager (the simulation owns all).
  ContactManager(IncrementalPotential* potential, const State* state, CollisionMesh surface,
                 ContactOptions options);

  // Empty if positions x are free of penetration (gaps > 0) at time t;
  // otherwise a description of the first penetrating pair.
  std::string FindPenetration(const double* x, double t) const;

  void EnableFriction(const FrictionOptions& options);
  bool has_friction() const { return friction_enabled_; }

  // StepFilter.
  void OnAccepted(const double* x) override;
  bool IsStepValid(const double* x) const override;
  double MaxStepSize(const double* from, const double* to) const override;
  bool IsFeasible(const double* x) const override;
  void BeginStep(const double* x_n) override;
  bool RefreshTerms(const double* x) override;
  std::vector<std::string> DiagnosticNames() const override;
  std::vector<double> Diagnostics(const double* x) const override;
  // What this filter put into the barrier energy over the step: at BeginStep,
  // the change of U_b(x_n, t_n) by the step's stiffness and pairs (adaptive
  // kappa, pairs coming into reach); then the moving obstacles' work on the
  // body, the integral of dU_b/dt (the barrier energy's rate at fixed
  // positions, central differences in the obstacle time) along the step by
  // the trapezoidal rule between (x_start, t_n) and (x_end, t_{n+1}) (one end
  // if the other cannot be evaluated).
  double PrescribedWork(const double* x_start, const double* x_end) override;
  // U_b (the barrier terms' energy) at positions x and obstacle time t.
  bool BarrierEnergy(const double* x, double t, double* energy);

  // Smallest gap over pairs closer than `reach` at the current obstacle time
  // (infinity if none).
  double MinDistance(const double* x, double reach) const;
  int CountPairsWithin(const double* x, double reach) const;

  double kappa() const { return kappa_; }
  double kappa_min() const { return kappa_min_; }
  bool adaptive_kappa() const { return adaptive_; }
  double d_hat() const { return options_.d_hat; }
  double obstacle_time() const { return tau_; }
  const CollisionMesh& surface() const { return surface_; }
  const std::vector<Obstacle>& obstacles() const { return options_.obstacles; }
  int num_barrier_pairs() const {
    return static_cast<int>(obstacle_pairs_.size() + edge_pairs_.size() +
                            edge_obstacle_pairs_.size() + mesh_pairs_->size());
  }
  int num_friction_contacts() const { return num_friction_contacts_; }
  std::string Summary() const;

 private:
  struct ObstaclePair {
    int slot;  // index into surface_.nodes
    int obstacle;
    bool operator<(const ObstaclePair& o) const {
      return slot != o.slot ? slot < o.slot : obstacle < o.obstacle;
    }
    bool operator==(const ObstaclePair& o) const {
      return slot == o.slot && obstacle == o.obstacle;
    }
  };
  struct EdgePair {
    int slot;  // point
    int edge;  // index into surface_.edges
    bool operator<(const EdgePair& o) const {
      return slot != o.slot ? slot < o.slot : edge < o.edge;
    }
    bool operator==(const EdgePair& o) const { return slot == o.slot && edge == o.edge; }
  };

  struct EdgeObstaclePair {
    int edge;  // index into surface_.edges
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

  Eigen::Vector3d NodePoint(const double* x, int slot) const {
    return ToPoint(x + dim_ * surface_.nodes[slot], dim_);
  }
  Eigen::Vector2d Node2(const double* x, int node) const {
    return Eigen::Vector2d(x[2 * node], x[2 * node + 1]);
  }
  bool PairHasFreeNode(const EdgePair& pair) const;
  Eigen::Vector3d EdgeEnd(const double* x, int edge, int end) const {
    return ToPoint(x + dim_ * surface_.edges[edge][end], dim_);
  }
  // Edge-feature distance of pair p at x at the current obstacle time.
  double EdgeObstacleDistance(const double* x, const EdgeObstaclePair& p,
                              Eigen::Vector3d* grad_a = nullptr,
                              Eigen::Vector3d* grad_b = nullptr) const {
    return options_.obstacles[p.obstacle].EdgeDistance(p.feature, EdgeEnd(x, p.edge, 0),
                                                       EdgeEnd(x, p.edge, 1), tau_, grad_a, grad_b);
  }
  // Every edge-feature pair (edges with a free node when `free_only`).
  std::vector<EdgeObstaclePair> AllEdgeObstaclePairs(bool free_only) const;
  // First impact fraction of the edges moving linearly from a (obstacle time
  // t_a) to b (time t_b) against the obstacles' edge features
  // (Obstacle::EdgeTimeOfImpact, conservative); Obstacle::kNoImpact if none.
  double EdgeObstacleTimeOfImpact(const double* a, const double* b, double t_a, double t_b) const;

  // 2D boundary edges against circles and boxes (an edge can cross a small
  // circle or a box corner with both end nodes outside; planes need no check: a
  // segment meets a half-space only where an end point does). Static: the
  // segment at x keeps more than `margin_` from the obstacle at time t. Path
  // from a: the circle's centre and the box's corners do not cross the edge
  // moving linearly from a to x (a == x: static check only). Empty if clear,
  // else a description.
  std::string EdgeObstacleConflict(const double* a, const double* x, double t) const;

  // Point-edge candidates whose boxes (from a to b, grown by `grow`) overlap.
  void EdgeCandidates(const double* a, const double* b, double grow,
                      std::vector<EdgePair>* pairs) const;
  // Adds to the sets the obstacle pairs whose distance at a is below d_hat +
  // reach[slot] + the obstacle's remaining travel, and the point-edge pairs
  // whose boxes over a -> b, grown by d_hat + edge_grow, overlap; returns true
  // if any pair was new.
  bool ExtendPairs(const double* a, const double* b, const std::vector<double>& reach,
                   double edge_grow);
  void RebuildBarrierTerms();
  // Sets the lagged closest points (edge-obstacle parameters, and the
  // barycentrics of the face-sphere pairs) at x; returns the largest relative
  // excess (d_lagged - d) / d over pairs within d_hat before.
  double LagEdgeAlpha(const double* x);
  void LagFriction(const double* x, double t);
  void RebuildFrictionTerms();
  // Moves the obstacle time towards t_next as far as x allows.
  void AdvanceObstacles(const double* x);
  void UpdateKappa(const double* x_n);
  double ObstacleTravel(int obstacle) const;

  IncrementalPotential* potential_;
  const State* state_;
  StepContext* context_;
  int dim_;
  CollisionMesh surface_;
  ContactOptions options_;
  std::vector<bool> slot_free_;
  double margin_;  // smallest admissible gap
  bool has_moving_obstacles_ = false;

  double kappa_ = 0.0;
  double kappa_min_ = 0.0;
  double kappa_max_ = 0.0;
  bool adaptive_ = false;
  bool kappa_balanced_ = false;
  double previous_min_gap_ = std::numeric_limits<double>::infinity();

  double t_n_ = 0.0;
  double t_next_ = 0.0;
  double tau_ = 0.0;
  double begin_energy_input_ = 0.0;  // PrescribedWork
  Eigen::VectorXd accepted_;

  std::vector<ObstaclePair> obstacle_pairs_;           // sorted
  std::vector<EdgePair> edge_pairs_;                   // sorted
  std::vector<EdgeObstaclePair> edge_obstacle_pairs_;  // sorted
  // Lagged closest-point parameter of each edge-obstacle pair (its barrier's
  // gap is the distance of that fixed point of the edge; see RefreshTerms).
  std::vector<double> edge_obstacle_alpha_;
  int alpha_lags_ = 0;
  // 3D faces against face features, 3D edges against box edges.
  std::unique_ptr<MeshObstaclePairs> mesh_pairs_;
  std::vector<std::array<int, 2>> edge_slots_;  // slots of each edge's nodes

  bool friction_enabled_ = false;
  FrictionOptions friction_;
  int lags_done_ = 0;
  int num_friction_contacts_ = 0;
  struct LaggedObstacleFriction {
    int node;
    Eigen::Matrix3d tangents;
    Eigen::Vector3d obstacle_velocity;
    double normal_force;
  };
  struct LaggedEdgeFriction {
    int p, a, b;
    Eigen::Vector2d tangent;
    double alpha;
    double normal_force;
  };
  std::vector<LaggedObstacleFriction> lagged_obstacle_;
  std::vector<LaggedEdgeFriction> lagged_edge_;

  mutable SpatialHash hash_;
  mutable std::vector<int> scratch_ids_;
};

}  // namespace ipstep
