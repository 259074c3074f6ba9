// The run loop: steps a Simulation to the end, counts what happened and
// decides when the run stops. The one loop of ipstep, ipstep_compare and
// ipstep_bench (they only add flags and formatting) and of library users:
//   Simulation sim(scene, options);
//   const RunSummary run = RunTrajectory(sim, RunOptions{});
//   std::printf("%s\n", run.message.c_str());
#pragma once

#include <csignal>
#include <functional>
#include <string>

#include "sim/simulation.h"
#include "sim/step_size_controller.h"

namespace ipstep {

struct RunOptions {
  // Steps to take; -1: the rest of the simulation's steps() (steps() -
  // steps_taken()).
  int steps = -1;
  // Stop at the first failed step (not converged, also as substeps), with
  // termination kStepFailed. Otherwise failed steps are counted and the run goes
  // on.
  bool stop_on_failure = false;
  // Stop at the first diverged step (sim/divergence.h), with termination
  // kDiverged. Otherwise the run goes on and every later step is "diverged" too.
  bool stop_on_divergence = true;
  // Stop once the loop has run this long [s] with steps left (kTimeout); 0: no
  // limit.
  double max_wall_seconds = 0.0;
  // Stop after the step in progress once this points to a non-zero value
  // (kInterrupted): e.g. a flag a SIGINT handler sets (apps/run_signals.h).
  // Read between steps only; nullptr: never.
  const volatile std::sig_atomic_t* interrupt = nullptr;
  // Called before step k (1-based, counting this run's steps) and after it with
  // its report (status "diverged: ..." once the run diverged). May be empty.
  std::function<void(int step)> before_step;
  std::function<void(const StepReport& report)> after_step;
  // Error-controlled steps to adaptive_options.t_end (sim/step_size_controller.h)
  // instead of the simulation's fixed ones; `steps` must be -1. A rejected
  // attempt goes back to the step's start (Simulation::Restore): only accepted
  // steps reach after_step, carrying their h, error estimate and rejections.
  // The simulation's own substeps are not used (the controller retries).
  bool adaptive = false;
  AdaptiveOptions adaptive_options;
};

enum class RunTermination {
  kCompleted,    // every planned step taken (failed steps, if any, are counted)
  kStepFailed,   // stopped at a failed step (RunOptions::stop_on_failure)
  kDiverged,     // stopped at a diverged step (RunOptions::stop_on_divergence)
  kTimeout,      // stopped by RunOptions::max_wall_seconds
  kStepLimit,    // an adaptive run took the most steps a run takes (10^7) before its end
  kInterrupted,  // stopped by RunOptions::interrupt, after its last step's after_step
};
// completed, step failed, diverged, timeout, step limit, interrupted
const char* RunTerminationName(RunTermination termination);

struct RunSummary {
  bool adaptive = false;
  int steps_planned = 0;  // 0 for an adaptive run (its steps follow from the error)
  int steps_done = 0;
  int failed = 0;      // steps not converged, also as substeps (diverged steps included)
  int substepped = 0;  // steps that converged only as substeps
  // Adaptive runs: attempts rejected (error over budget or a failed solve) and
  // steps taken at the smallest step with the error still over its budget.
  int rejected = 0;
  int over_budget = 0;
  double min_time_step = 0.0;  // [s] over the steps taken
  double max_time_step = 0.0;
  long iterations = 0;
  long evaluations = 0;
  int max_step_iterations = 0;
  double worst_residual = 0.0;  // largest stopping measure at the end of a step [m/s]
  double wall_seconds = 0.0;    // the whole loop, callbacks included
  double step_seconds = 0.0;    // the steps alone (sum of StepReport::wall_seconds)
  EnergyReport initial_energies;
  EnergyReport final_energies;
  // max over steps of |E_n - E_0| / E_s(t_n), the divergence rule's energy
  // scale (sim/divergence.h); meaningful for every scene (also E_0 = 0).
  double max_energy_drift = 0.0;
  double energy_scale = 0.0;  // E_s at the end [J]
  int first_failed_step = 0;  // 0: none
  std::string first_failure;  // its status
  int diverged_at = 0;        // 0: did not diverge
  std::string divergence;     // why (sim/divergence.h)
  RunTermination termination = RunTermination::kCompleted;
  std::string message;  // one line: how the run ended
  // Contact (the contact effect): the barrier stiffness kappa at the end of
  // the run, and whether it is adaptive (contact/adaptive_kappa.h: then it
  // follows the step size, kappa_min ~ m / (w_U / w_I) ~ m / h^2, so runs at
  // different steps or error tolerances simulate different barriers and their
  // errors against one reference include that difference; a fixed
  // contact.kappa, --contact_kappa, makes them comparable). 0 and false
  // without contact.
  double contact_kappa = 0.0;
  bool contact_kappa_adaptive = false;

  double iterations_per_step() const {
    return steps_done > 0 ? static_cast<double>(iterations) / steps_done : 0.0;
  }
  // Per step taken, not per step planned.
  double ms_per_step() const { return steps_done > 0 ? 1e3 * step_seconds / steps_done : 0.0; }
  bool diverged() const { return diverged_at > 0; }
};

// The simulation options of an adaptive run, set before the simulation is
// built (the ipstep program's --adaptive, the Python module's adaptive=True):
// the solve's tolerance from the error budget (AdaptiveSolverTolerance) unless
// `keep_tolerance` (the user gave one), a stall below the budget accepted
// (accept_residual = AdaptiveStallResidual), and no substeps (the controller
// retries failed steps smaller itself). Throws InputError for invalid
// `adaptive` (ValidateAdaptiveOptions).
void ConfigureAdaptiveSimulation(const AdaptiveOptions& adaptive, bool keep_tolerance,
                                 SimulationOptions* options);

// Throws InputError naming the option if `options` cannot run `sim` (out of
// range; adaptive steps with steps set, invalid AdaptiveOptions or an
// integrator without time error). RunTrajectory calls it first; a program
// calls it before it prints anything.
void ValidateRunOptions(const Simulation& sim, const RunOptions& options);

// Runs `sim` from its current state. Never throws for what happens in a step
// (a failure or a divergence is in the summary); throws InputError for
// options out of range.
RunSummary RunTrajectory(Simulation& sim, const RunOptions& options = RunOptions{});

}  // namespace ipstep
