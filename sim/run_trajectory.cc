#include "sim/run_trajectory.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/divergence.h"

namespace ipstep {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string Printf(const char* format, int a, double b) {
  char text[120];
  std::snprintf(text, sizeof(text), format, a, b);
  return text;
}

}  // namespace

const char* RunTerminationName(RunTermination termination) {
  switch (termination) {
    case RunTermination::kCompleted:
      return "completed";
    case RunTermination::kStepFailed:
      return "step failed";
    case RunTermination::kDiverged:
      return "diverged";
    case RunTermination::kTimeout:
      return "timeout";
  }
  return "?";
}

RunSummary RunTrajectory(Simulation& sim, const RunOptions& options) {
  const int remaining = std::max(0, sim.steps() - sim.steps_taken());
  if (options.steps < -1 || options.steps > limits::kMaxSteps) {
    throw InputError("options", "RunOptions.steps",
                     "must be -1 (the simulation's steps) or in [0, " +
                         std::to_string(limits::kMaxSteps) + "], got " +
                         std::to_string(options.steps));
  }
  if (!(options.max_wall_seconds >= 0.0 && options.max_wall_seconds <= limits::kMaxTimeLimit)) {
    throw InputError("options", "RunOptions.max_wall_seconds",
                     "must be in " + limits::RangeText(0.0, limits::kMaxTimeLimit, "s"));
  }
  RunSummary run;
  run.steps_planned = options.steps >= 0 ? options.steps : remaining;
  const DivergenceRule rule(sim, run.steps_planned * sim.time_step());
  run.initial_energies = sim.Energies();
  run.final_energies = run.initial_energies;
  run.energy_scale = rule.EnergyScale(0.0);
  const auto start = Clock::now();
  for (int step = 1; step <= run.steps_planned; ++step) {
    if (options.before_step) options.before_step(step);
    StepReport report = sim.Step();
    ++run.steps_done;
    run.iterations += report.iterations;
    run.evaluations += report.evaluations;
    run.max_step_iterations = std::max(run.max_step_iterations, report.iterations);
    run.worst_residual = std::max(run.worst_residual, report.residual);
    run.step_seconds += report.wall_seconds;
    run.final_energies = report.energies;
    std::string divergence = rule.Check(sim, report);
    if (divergence.empty() && run.diverged()) {
      divergence = "after the divergence at step " + std::to_string(run.diverged_at);
    }
    if (!divergence.empty()) {
      report.converged = false;
      report.status = "diverged: " + divergence;
      if (!run.diverged()) {
        run.diverged_at = step;
        run.divergence = divergence;
      }
    } else {
      run.max_energy_drift =
          std::max(run.max_energy_drift, rule.Drift(report.time, report.energies.total()));
    }
    if (report.converged && report.substeps > 1) ++run.substepped;
    if (!report.converged) {
      ++run.failed;
      if (run.first_failed_step == 0) {
        run.first_failed_step = step;
        run.first_failure = report.status;
      }
    }
    if (options.after_step) options.after_step(report);
    if (run.diverged_at == step && options.stop_on_divergence) {
      run.termination = RunTermination::kDiverged;
      break;
    }
    if (!report.converged && options.stop_on_failure) {
      run.termination = run.diverged() ? RunTermination::kDiverged : RunTermination::kStepFailed;
      break;
    }
    if (options.max_wall_seconds > 0.0 && step < run.steps_planned &&
        Since(start) > options.max_wall_seconds) {
      run.termination = RunTermination::kTimeout;
      break;
    }
  }
  run.wall_seconds = Since(start);
  run.energy_scale = rule.EnergyScale(sim.state().time - rule.start_time());
  switch (run.termination) {
    case RunTermination::kCompleted:
      run.message = "completed " + std::to_string(run.steps_done) + " steps";
      break;
    case RunTermination::kStepFailed:
      run.message =
          "step " + std::to_string(run.first_failed_step) + " failed: " + run.first_failure;
      break;
    case RunTermination::kDiverged:
      run.message = "diverged at step " + std::to_string(run.diverged_at) + ": " + run.divergence;
      break;
    case RunTermination::kTimeout:
      run.message = Printf("timeout after %d steps (%.3g s)", run.steps_done, run.wall_seconds);
      break;
  }
  return run;
}

}  // namespace ipstep
