// What the contact effect (contact/contact_effect.h) manages: the collision
// mesh and the obstacles, the pair kinds (contact/pair_set.h, registered in
// contact/pair_kinds.cc) and the barrier and friction terms they put into the
// incremental potential, the barrier stiffness (contact/adaptive_kappa.h), the
// lagged friction, the obstacles' time and its staging within a step
// (contact/obstacle_time.h) and the work of moving obstacles. The contact
// filter (contact/contact_filter.h) is the step filter that keeps the
// iterates free of penetration with the geometry queries below and passes the
// step's events (BeginStep, RefreshTerms, ...) on to this state.
//
// A pair's barrier term (family "contact", in the state's own term group) is
//   w_U kappa w_i B(d)  (contact/barrier.h)
// with w_i the weight of the pair's node, edge or face (contact/collision_mesh.h);
// its friction term (family "friction", contact/friction.h) is
//   w_R mu lambda f0(|v_t|),  lambda = kappa w_i (-B'(d)) lagged,
// with mu the pair's obstacle's own coefficient or contact.self_contact_mu
// (FrictionSettings), kappa for self-contact pairs contact.self_contact_kappa
// when given.
//
// Within a step:
//  * BeginStep(x_n) collects the candidate pairs: those that can come within
//    d_hat during the step (distance at x_n below d_hat plus twice the
//    predictor's displacement plus the obstacle's travel). Terms of pairs out of
//    reach are exactly zero, so a generous set costs little.
//  * RefreshTerms(x) after each solve adds every pair within d_hat of the
//    solution that the set missed, and asks for another solve. The set only
//    grows within a step, so this terminates.
//  * Moving obstacles: the solve needs a start free of penetration at the
//    obstacles' positions. When an obstacle would sweep into x_n during the
//    step, its time is advanced in stages: each solve uses the obstacles at a
//    time tau, and RefreshTerms moves tau towards t_{n+1} as far as continuous
//    collision detection against the current solution allows (0.8 of the way
//    to impact), then solves again. The step is feasible only once tau = t_{n+1}
//    (obstacles_reached_end; the filter's CheckState says kBoundaryNotReached
//    before). A step whose state is kept short of it starts the next one there
//    (State::boundary_lag).
//  * Lagged closest points (edges and faces against sphere centres) are
//    re-lagged and the step solved again while a lag is more than 1 % farther
//    than the true closest point, at most 3 times per step.
//  * Friction: normal forces and tangent bases are lagged at x_n; with
//    friction iterations > 1 they are re-lagged at the solution and the step is
//    solved again, up to that many lags in total.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/adaptive_kappa.h"
#include "contact/collision_mesh.h"
#include "contact/contact_options.h"
#include "contact/obstacle_time.h"
#include "contact/pair_set.h"
#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

class ContactState {
 public:
  static constexpr char kContactFamily[] = "contact";
  static constexpr char kFrictionFamily[] = "friction";

  // `potential` and `state` must outlive this (the simulation owns all). Adds
  // the barrier terms of the pairs already within d_hat at the state's x.
  ContactState(IncrementalPotential* potential, const State* state, CollisionMesh mesh,
               ContactOptions options);

  void EnableFriction(const FrictionOptions& options);
  bool has_friction() const { return friction_enabled_; }

  // ---- Geometry over every pair kind (the filter's queries).
  // Empty if positions x are free of penetration (gaps > 0) at time t;
  // otherwise a description of the first penetrating pair.
  std::string FindPenetration(const double* x, double t) const;
  // Smallest TimeOfImpact of the kinds from a at obstacle time t_a to b at
  // t_b (PairSet::kNoImpact if none).
  double Sweep(const double* a, const double* b, double t_a, double t_b) const;
  // Every kind's PairSet::ShrinkToClear of the fraction t of from -> to.
  double ShrinkToClear(const double* from, const double* to, double t) const;
  // Over every kind's combinations closer than `reach` at the current
  // obstacle time: the smallest gap (infinity if none) and their number.
  void Near(const double* x, double reach, double* min_distance, int* count) const;
  double MinDistance(const double* x, double reach) const {
    double best;
    int count;
    Near(x, reach, &best, &count);
    return best;
  }
  // The pair kinds' broad phase so far (PairSet::BroadPhaseSeconds) [s].
  double BroadPhaseSeconds() const;

  // ---- The step (contact/contact_state_step.cc).
  // Obstacle time, stiffness, candidate pairs, lags and terms for the step
  // from x_n (the header comment, "Within a step").
  void BeginStep(const double* x_n);
  // After a solve that reached x: true if the terms changed (pairs, obstacle
  // time, lags) and the step is to be solved again.
  bool RefreshTerms(const double* x);
  // From the kSecantFromStage-th staged solve of a step on: the free nodes moved along
  // by the secant through the last two stages' solutions (extrapolated to
  // t_{n+1}), when that path lets the obstacles advance farther than with the
  // nodes held (StepFilter::ProposeStart); StartRejected goes back to the
  // obstacle time without it (contact/contact_state_staging.cc).
  bool ProposeStart(double* x);
  void StartRejected();
  // The secant starts at the third staged solve (two solutions give a secant).
  // Measured (ipstep --scene=squash_square --contact_kappa=1e5): from the 3rd
  // stage 15.8 Newton iterations per step (max 30; 20.3, max 39, with today's
  // code), from the 25th 89.7 (max 156), without the secant 192 (22 steps
  // substepped); hard/squeeze_fast's step 7 takes 28 iterations instead of 90
  // (docs/contact.md, "Moving boundaries").
  static constexpr int kSecantFromStage = 3;
  // What the contact terms took in over the step (StepFilter::PrescribedWork):
  // at BeginStep, the change of U_b(x_n, t_n) by the step's stiffness and
  // pairs (adaptive kappa, pairs coming into reach); then the moving
  // obstacles' work on the body, the integral of dU_b/dt (the barrier
  // energy's rate at fixed positions, central differences in the obstacle
  // time) along the step by the trapezoidal rule between (x_start, t_n) and
  // (x_end, t_{n+1}) (one end if the other cannot be evaluated); and the work
  // h F . u of friction against moving obstacles.
  double PrescribedWork(const double* x_start, const double* x_end);
  // U_b (the barrier terms' energy) at positions x and obstacle time t.
  bool BarrierEnergy(const double* x, double t, double* energy);
  // -grad U_b at x (the barrier terms as they are, unweighted [N]); false when
  // a term cannot be evaluated there.
  bool BarrierForces(const double* x, Eigen::VectorXd* forces) const;

  double kappa() const { return kappa_.value(); }
  bool adaptive_kappa() const { return kappa_.adaptive(); }
  double d_hat() const { return options_.d_hat; }
  double obstacle_time() const { return time_.tau(); }
  bool has_moving_obstacles() const { return time_.has_moving_obstacles(); }
  // The obstacles' time reached t_{n+1} (ObstacleTime::reached_end).
  bool obstacles_reached_end() const { return time_.reached_end(); }
  const CollisionMesh& mesh() const { return mesh_; }
  const ObstacleList& obstacles() const { return options_.obstacles; }
  // contact.self_contact_mu (< 0: the friction effect's mu).
  double self_contact_mu() const { return options_.self_contact_mu; }
  std::string Summary() const;

 private:
  bool ExtendPairs(const CandidateRegion& region);
  // Per obstacle: for a rotating one, the largest distance of a contact node
  // at a or b from its centre, plus reach (how far the nodes may still go);
  // 0 for the others (ObstacleTime::Travel).
  std::vector<double> RotationRadii(const double* a, const double* b, double reach) const;
  void RebuildBarrierTerms();
  double Lag(const double* x);
  // The coefficients of every pair kind, and whether any is > 0.
  FrictionSettings Friction() const;
  bool AnyFriction() const;
  void LagFriction(const double* x, double t);
  void RebuildFrictionTerms();
  // Moves the obstacle time towards t_{n+1} as far as x allows.
  void AdvanceObstacles(const double* x);
  // The same along the secant of the stages' solutions, from the third stage
  // on (sets proposal_ when it gets farther); returns the extra reach [m].
  double AdvanceObstaclesAlongSecant(const double* x);
  void UpdateKappa(const double* x_n);

  IncrementalPotential* potential_;
  const State* state_;
  StepContext* context_;
  int dim_;
  int num_coordinates_;  // of a configuration x
  CollisionMesh mesh_;
  ContactOptions options_;
  std::vector<bool> node_free_;  // per entry of mesh_.nodes
  double margin_;                // smallest admissible gap
  AdaptiveKappa kappa_;
  ObstacleTime time_;
  double begin_energy_input_ = 0.0;  // PrescribedWork
  int lags_ = 0;                     // closest-point re-lags this step
  // Moving obstacles' stages this step: the last two solutions and times,
  // the proposed start and the obstacle time without it.
  std::vector<Eigen::VectorXd> stage_solutions_;
  std::vector<double> stage_times_;
  Eigen::VectorXd proposal_;
  bool has_proposal_ = false;
  double held_tau_ = 0.0;
  int stages_ = 0;  // solutions of this step at a staged obstacle time

  std::vector<std::unique_ptr<PairSet>> sets_;
  // The potential's term groups of the barrier and friction terms this state
  // owns (it removes and selects them by these, never by family name).
  int barrier_group_ = 0;
  int friction_group_ = 0;

  bool friction_enabled_ = false;
  FrictionOptions friction_;
  int friction_lags_ = 0;  // friction lags this step
};

}  // namespace ipstep
