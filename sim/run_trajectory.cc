#include "sim/run_trajectory.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include <glog/logging.h>

#include "contact/contact_effect.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/scoped_timer.h"
#include "sim/divergence.h"
#include "sim/simulation_option_table.h"
#include "sim/step_size_controller.h"

namespace ipstep {
namespace {

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
    case RunTermination::kStepLimit:
      return "step limit";
    case RunTermination::kInterrupted:
      return "interrupted";
  }
  return "?";
}

namespace {

// The bookkeeping of the steps a run takes, fixed or adaptive: counts, the
// divergence rule, the callbacks and whether to stop.
class StepRecorder {
 public:
  StepRecorder(Simulation* sim, const RunOptions& options, double t_end, RunSummary* run)
      : sim_(sim), options_(options), rule_(*sim, t_end), run_(run), start_(WallClock::now()) {
    run_->initial_energies = rule_.initial_energies();
    run_->final_energies = run_->initial_energies;
    run_->energy_scale = rule_.EnergyScale(0.0);
  }

  // Called before the step's first attempt.
  void Begin(int step) {
    if (options_.before_step) options_.before_step(step);
  }

  // Records an accepted step (the k-th of this run); true if the run stops.
  bool Record(int step, StepReport report, bool more_to_come) {
    RunSummary& run = *run_;
    ++run.steps_done;
    run.iterations += report.iterations;
    run.evaluations += report.evaluations;
    run.max_step_iterations = std::max(run.max_step_iterations, report.iterations);
    run.worst_residual = std::max(run.worst_residual, report.residual);
    run.step_seconds += report.wall_seconds;
    run.final_energies = report.energies;
    run.min_time_step =
        run.steps_done == 1 ? report.time_step : std::min(run.min_time_step, report.time_step);
    run.max_time_step = std::max(run.max_time_step, report.time_step);
    if (std::isfinite(report.prescribed_work)) work_ += std::abs(report.prescribed_work);
    std::string divergence = rule_.Check(*sim_, report, work_);
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
          std::max(run.max_energy_drift, rule_.Drift(report.time, report.energies.total(), work_));
    }
    if (report.converged && report.substeps > 1) ++run.substepped;
    if (!report.converged) {
      ++run.failed;
      if (run.first_failed_step == 0) {
        run.first_failed_step = step;
        run.first_failure = report.status;
      }
    }
    if (options_.after_step) options_.after_step(report);
    if (run.diverged_at == step && options_.stop_on_divergence) {
      run.termination = RunTermination::kDiverged;
      return true;
    }
    if (!report.converged && options_.stop_on_failure) {
      run.termination = run.diverged() ? RunTermination::kDiverged : RunTermination::kStepFailed;
      return true;
    }
    if (options_.interrupt != nullptr && *options_.interrupt != 0 && more_to_come) {
      run.termination = RunTermination::kInterrupted;
      return true;
    }
    if (options_.max_wall_seconds > 0.0 && more_to_come &&
        SecondsSince(start_) > options_.max_wall_seconds) {
      run.termination = RunTermination::kTimeout;
      return true;
    }
    return false;
  }

  void Finish() {
    RunSummary& run = *run_;
    run.wall_seconds = SecondsSince(start_);
    run.energy_scale = rule_.EnergyScale(sim_->state().time - rule_.start_time(), work_);
    if (const ContactEffect* contact = sim_->FindEffect<ContactEffect>()) {
      run.contact_kappa = contact->state().kappa();
      run.contact_kappa_adaptive = contact->state().adaptive_kappa();
    }
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
      case RunTermination::kStepLimit:
        run.message = "stopped after " + std::to_string(run.steps_done) +
                      " steps, the most a run takes, before the end time";
        break;
      case RunTermination::kInterrupted:
        run.message = "interrupted at step " + std::to_string(run.steps_done);
        break;
    }
  }

 private:
  Simulation* sim_;
  const RunOptions& options_;
  const DivergenceRule rule_;
  RunSummary* run_;
  WallClock::time_point start_;
  double work_ = 0.0;  // prescribed work so far, summed in magnitude [J]
};

void RunFixed(Simulation& sim, RunSummary* run, StepRecorder* recorder) {
  for (int step = 1; step <= run->steps_planned; ++step) {
    recorder->Begin(step);
    if (recorder->Record(step, sim.Step(), step < run->steps_planned)) return;
  }
}

// Error-controlled steps (sim/step_size_controller.h) to t_end.
void RunAdaptive(Simulation& sim, const AdaptiveOptions& adaptive, RunSummary* run,
                 StepRecorder* recorder) {
  const int order = sim.integrator().order();
  StepSizeController controller(adaptive, order);
  const double t_start = sim.state().time;
  const double t_stop = t_start + adaptive.t_end;
  double h = adaptive.initial_time_step > 0.0 ? adaptive.initial_time_step : sim.time_step();
  h = std::clamp(h, controller.min_time_step(), controller.max_time_step());
  for (int step = 1;; ++step) {
    const double left = t_stop - sim.state().time;
    // Done, up to round-off of the summed steps (and never a step below the
    // smallest a Simulation takes).
    if (left <= std::max(1e-12 * adaptive.t_end, limits::kMinTimeStep)) return;
    if (step > limits::kMaxSteps) {
      run->termination = RunTermination::kStepLimit;
      return;
    }
    recorder->Begin(step);
    const Simulation::Checkpoint start = sim.Save();
    Eigen::VectorXd start_forces;
    const bool impulsive = sim.ImpulsiveForces(start.state.x, &start_forces);
    int rejected = 0;
    double rejected_seconds = 0.0;
    long rejected_iterations = 0, rejected_evaluations = 0;
    for (;;) {
      // The last step lands on t_stop (a sliver under a tenth of h is merged in).
      double h_try = std::min(h, left);
      if (left - h_try < 0.1 * h_try) h_try = left;
      StepReport report = sim.Step(h_try, /*retry_as_substeps=*/false);
      StepSizeController::Decision decision;
      if (report.converged) {
        // The contact forces' change over the step and the forces themselves,
        // as the position errors h/2 |h M^-1 df_c| and h^2/2 |M^-1 f_c|.
        Eigen::VectorXd end_forces;
        double impact_error = 0.0, contact_error = 0.0;
        if (impulsive && sim.ImpulsiveForces(sim.state().x, &end_forces)) {
          const State& s = sim.state();
          const int dim = s.dimension;
          for (int i = 0; i < s.num_nodes(); ++i) {
            if (!s.is_free(i)) continue;
            const double share = 0.5 * h_try * h_try / s.mass[i];
            impact_error = std::max(
                impact_error,
                share *
                    (end_forces.segment(dim * i, dim) - start_forces.segment(dim * i, dim)).norm());
            contact_error =
                std::max(contact_error, share * end_forces.segment(dim * i, dim).norm());
          }
        }
        // Filtered through the step's matrix (sim/stiff_mode_filter.h: one
        // assembly and factorisation per attempt, part of the step's time)
        // unless the options say raw.
        const auto estimate_start = WallClock::now();
        const double error = sim.LocalError(start.state, h_try, adaptive.filter_stiff_modes);
        report.wall_seconds += SecondsSince(estimate_start);
        decision = controller.Judge(h_try, error, impact_error, contact_error);
        report.error_estimate = std::max(error, impact_error);
        VLOG(1) << "adaptive: t=" << start.state.time << " h=" << h_try << " error=" << error
                << " impact=" << impact_error << " contact=" << contact_error
                << (decision.accept ? " accepted" : " rejected")
                << ", next h=" << decision.next_time_step;
        if (decision.accept && decision.over_budget) ++run->over_budget;  // at the smallest step
      } else {
        decision = controller.Failed(h_try);
      }
      if (decision.accept) {
        report.rejected = rejected;
        report.iterations += static_cast<int>(rejected_iterations);
        report.evaluations += static_cast<int>(rejected_evaluations);
        report.wall_seconds += rejected_seconds;
        run->rejected += rejected;
        h = decision.next_time_step;
        if (recorder->Record(step, report, sim.state().time < t_stop - 1e-12 * adaptive.t_end)) {
          return;
        }
        break;
      }
      ++rejected;
      rejected_seconds += report.wall_seconds;
      rejected_iterations += report.iterations;
      rejected_evaluations += report.evaluations;
      sim.Restore(start);
      h = decision.next_time_step;
    }
  }
}

}  // namespace

void ConfigureAdaptiveSimulation(const AdaptiveOptions& adaptive, bool keep_tolerance,
                                 SimulationOptions* options) {
  ValidateAdaptiveOptions(adaptive);
  if (!keep_tolerance) options->optimizer.tolerance = AdaptiveSolverTolerance(adaptive);
  options->accept_residual = AdaptiveStallResidual(adaptive);
  options->max_substeps = 1;
}

void ValidateRunOptions(const Simulation& sim, const RunOptions& options) {
  if (options.steps < -1 || options.steps > limits::kMaxSteps) {
    throw InputError("options", "RunOptions.steps",
                     "must be -1 (the simulation's steps) or in [0, " +
                         std::to_string(limits::kMaxSteps) + "], got " +
                         std::to_string(options.steps));
  }
  CheckOptionRanges(RunOptionTable(), options);  // max_wall_seconds
  if (!options.adaptive) return;
  ValidateAdaptiveOptions(options.adaptive_options);
  if (options.steps != -1) {
    throw InputError("options", "RunOptions.steps",
                     "an adaptive run's steps follow from its error tolerance: leave it -1");
  }
  if (sim.integrator().order() < 1) {
    throw InputError("options", "RunOptions.adaptive",
                     sim.integrator().name() +
                         " has no time-discretisation error to control; adaptive steps need "
                         "a dynamic integrator");
  }
}

RunSummary RunTrajectory(Simulation& sim, const RunOptions& options) {
  ValidateRunOptions(sim, options);
  const int remaining = std::max(0, sim.steps() - sim.steps_taken());
  RunSummary run;
  if (options.adaptive) {
    run.adaptive = true;
    StepRecorder recorder(&sim, options, options.adaptive_options.t_end, &run);
    RunAdaptive(sim, options.adaptive_options, &run, &recorder);
    recorder.Finish();
    return run;
  }
  run.steps_planned = options.steps >= 0 ? options.steps : remaining;
  StepRecorder recorder(&sim, options, run.steps_planned * sim.time_step(), &run);
  RunFixed(sim, &run, &recorder);
  recorder.Finish();
  return run;
}

}  // namespace ipstep
