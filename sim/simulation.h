// A simulation run: the state built from a scene, the incremental potential with
// exactly the effects the scene lists, an integrator and (for variational
// integrators) a step solver. Everything is built once; Step() advances by h.
// The kind of integrator MakeIntegrator made chooses the step path: a
// variational step predicts, solves and updates; an explicit one advances from
// the forces at its start. The potential has inertia terms when the
// integrator's weights weigh inertia (w_I > 0: dynamic variational integrators).
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/forces.h"
#include "core/incremental_potential.h"
#include "core/state.h"
#include "energies/effect.h"
#include "energies/effect_registry.h"
#include "integrators/make_integrator.h"
#include "problems/scene.h"
#include "sim/energy_balance.h"
#include "solver/step_solver.h"

namespace ipstep {

class StiffModeFilter;  // sim/stiff_mode_filter.h

struct SimulationOptions {
  IntegratorOptions integrator;
  OptimizerOptions optimizer;
  double time_step = 0.0;  // [s]; 0: the scene's time_step
  int steps = -1;          // -1: the scene's steps
  // [s]; > 0: run to this time, steps = t_end / time_step, which must be a
  // whole number (within 1e-9; an InputError names the step that would fit);
  // not with steps >= 0.
  double t_end = 0.0;
  // Energy balance (sim/energy_balance.h), variational integrators: a step
  // whose energy grows by more than this fraction of the energy in motion
  // fails with status "energy growth". 0: no check.
  double energy_tolerance = 0.1;
  // A failed step is retried from its start as 2, 4, ... substeps, up to this
  // many (1: no retry); the run then continues at the scene's step.
  int max_substeps = 1;
  // A step whose optimiser stops above its tolerance (stalled, iteration
  // limit) with a stopping measure at most this [m/s] is accepted as
  // converged (status "converged within the error budget: ..."); 0: never.
  // Adaptive runs set it from their error budget (sim/step_size_controller.h).
  double accept_residual = 0.0;
  // The effects the scene's "effects" are looked up in; null: DefaultEffects()
  // (sim/default_effects.h). Must outlive the simulation's construction.
  const EffectRegistry* effects = nullptr;
  // Per effect name, parameters that replace the scene's (merged key by key
  // into the effect's parameters object, e.g. {"contact": {"kappa": 1e5}});
  // an override for an effect the scene does not list is an InputError
  // naming "effect_overrides.<effect>".
  std::map<std::string, nlohmann::json> effect_overrides;
};

struct StepReport {
  int step = 0;
  double time = 0.0;
  double time_step = 0.0;  // h of this step [s]
  bool converged = true;
  std::string status = "converged";
  int iterations = 0;
  int evaluations = 0;
  double wall_seconds = 0.0;
  double residual = 0.0;         // stopping measure [m/s]
  int substeps = 1;              // 1, or the substeps of a retried step
  std::string retry_reason;      // a retried step: the status of its first attempt
  double energy_growth = 0.0;    // E_{n+1} - E_n - W [J] (sim/energy_balance.h); 0 unchecked
  double prescribed_work = 0.0;  // W [J]: work of prescribed motions (same); 0 unchecked
  // Adaptive runs (sim/run_trajectory.h): the integrator's local error estimate
  // [m] and the attempts rejected before this step was accepted; NaN and 0
  // otherwise.
  double error_estimate = std::numeric_limits<double>::quiet_NaN();
  int rejected = 0;
  EnergyReport energies;
  std::vector<double> diagnostics;  // values of Simulation::DiagnosticNames()
};

class Simulation {
 public:
  // Throws InputError for invalid options or scene/effect parameters.
  Simulation(const Scene& scene, const SimulationOptions& options);
  ~Simulation();
  Simulation(const Simulation&) = delete;  // terms and solvers point into it
  Simulation& operator=(const Simulation&) = delete;

  // One step of time_step(), retried as substeps (SimulationOptions::max_substeps).
  // A step that fails keeps its state unless it penetrates: then it goes
  // back to its start state (time goes on, State::boundary_lag); a state
  // whose moving boundaries were not reached ("moving boundary not reached")
  // is kept where they got to.
  StepReport Step();
  // One step of h [s] (in the range of SimulationOptions::time_step); without
  // `retry_as_substeps` a failed step is not retried (an adaptive run's
  // controller retries it).
  StepReport Step(double h, bool retry_as_substeps = true);

  // The state a step starts from, to go back to (a failed step retried as
  // substeps, a rejected adaptive step): the state, the run's energy balance
  // and the step count.
  struct Checkpoint {
    State state;
    RunEnergyBalance energy;
    int steps_taken = 0;
  };
  Checkpoint Save() const;
  void Restore(const Checkpoint& checkpoint);

  const Scene& scene() const { return scene_; }
  const State& state() const { return state_; }
  // What every integrator has (name, order, LocalError).
  const Integrator& integrator() const { return integrator_.common(); }
  // The variational integrator; null when it is explicit (then the step has no
  // solver and no predictor).
  const VariationalIntegrator* variational_integrator() const {
    return integrator_.variational.get();
  }
  const IncrementalPotential& potential() const { return *potential_; }
  // The step solver (variational integrators; throws std::logic_error otherwise).
  const StepSolver& step_solver() const;
  double time_step() const { return time_step_; }
  int steps() const { return steps_; }
  int steps_taken() const { return steps_taken_; }
  const Eigen::VectorXd& gravity() const { return gravity_; }
  // One line per active effect (what was built), in scene order.
  const std::vector<std::string>& effect_summaries() const { return effect_summaries_; }
  // The built effects (energies/effect.h), in the order they were built.
  const EffectList& effects() const { return effects_; }
  // The effect of exactly type T (ContactEffect, contact/contact_effect.h), or null.
  template <class T>
  const T* FindEffect() const {
    return effects_.Find<T>();
  }
  EnergyReport Energies() const;
  // Replaces the Ceres step solver by another StepSolver over the same potential
  // and state (e.g. a reference solver in bench/). Variational integrators only.
  using StepSolverFactory =
      std::function<std::unique_ptr<StepSolver>(IncrementalPotential*, const State*)>;
  void ReplaceStepSolver(const StepSolverFactory& factory);

  // Forces [N] of the impulsive terms (Term::impulsive: contact barrier,
  // friction) at x with the terms as they are, -grad E_impulsive / w_U; false
  // when there are none (or they cannot be evaluated).
  bool ImpulsiveForces(const Eigen::VectorXd& x, Eigen::VectorXd* forces) const;

  // The local error estimate [m] of the step just taken from `before` with h
  // (Integrator::LocalErrorVector; largest over free nodes), with
  // `filter_stiff_modes` through the step's own matrix (the step solver's
  // factorisation when it kept one, else sim/stiff_mode_filter.h; variational
  // integrators with inertia only, the others' raw estimate).
  double LocalError(const State& before, double h, bool filter_stiff_modes);

  // Extra per-step columns contributed by step filters (e.g. contact).
  std::vector<std::string> DiagnosticNames() const;
  void set_iteration_sink(IterationSink sink);

  // A step is solved again from its result while a step filter refreshes its
  // terms (contact set, lagged friction), at most this many times.
  static constexpr int kMaxRefreshes = 40;
  // The pulled-back start stops at this fraction of the collision-free distance.
  static constexpr double kFeasibleStartFraction = 0.9;

 private:
  void BuildState();
  void BuildPotential();
  void ApplyBoundaryConditions(double t, Eigen::VectorXd* x) const;
  // One step of h from the state (Step: h, or a substep of it).
  void Advance(double h, StepReport* report);
  // Returns false when the prescribed nodes in x are short of their targets
  // (a step whose staging ran out: sim/prescribed_staging.h).
  bool SolveStep(double h, Eigen::VectorXd* x, StepReport* report);
  // A start a filter's staging proposes after its refresh (StepFilter::
  // ProposeStart), taken into x when every other filter accepts it.
  void TakeProposedStart(Eigen::VectorXd* x);

  Scene scene_;
  SimulationOptions options_;
  double time_step_;
  int steps_;
  int steps_taken_ = 0;
  State state_;
  Eigen::VectorXd gravity_;
  // Exactly one kind is set (MakeIntegrator): it chooses the step path of Advance.
  MadeIntegrator integrator_;
  std::unique_ptr<IncrementalPotential> potential_;
  std::unique_ptr<StiffModeFilter> stiff_mode_filter_;  // built by the first filtered LocalError
  std::unique_ptr<StepSolver> solver_;
  EffectList effects_;
  std::vector<std::string> effect_summaries_;
  RunEnergyBalance run_energy_;
};

}  // namespace ipstep
