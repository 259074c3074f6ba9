// RunTune (apps/programs.h), the ipstep_tune program: "this error, at least
// cost". A small, budgeted search over integrator x optimiser x (fixed h or
// adaptive tolerance) x solver tolerance for the cheapest run of a scene whose
// measured error at the end time is within --target_error, against one
// reference (sim/reference.h); the winner is validated against a reference
// twice as fine; the Pareto front (cost against error) is printed with the
// recommended configuration as an ipstep command line.
//   ipstep_tune --scene=cloth --target_error=1e-3
//   ipstep_tune --scene=cloth --match_default   (target: the default's own error)
// Search, per integrator x optimiser, coarse to fine, stopping at the first
// run that meets the target (finer ones only cost more):
//   fixed h = dt * {2, 1, 1/2, 1/4, 1/8}, with the default solver tolerance and
//     with one tied to the target (0.1 E / T, as --adaptive sets it);
//   --adaptive with E = target * {1, 1/3, 1/10}.
// Cost: the run's wall time (sim/run_trajectory.h), on this machine.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "apps/program_main.h"
#include "apps/programs.h"
#include "apps/solver_flags.h"
#include "core/input_error.h"
#include "io/output_file.h"
#include "problems/scene_loader.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "sim/step_size_controller.h"

DEFINE_double(target_error, 0.0,
              "The error to reach at the end time, > 0: [m] for "
              "--measure=position, in energy scales for --measure=energy");
DEFINE_bool(match_default, false,
            "Instead of --target_error: the measured error of the default configuration "
            "(backward_euler + newton at the scene's step and the default tolerance), to find "
            "what reaches it at least cost");
DEFINE_string(measure, "position",
              "position: the largest distance of a free node from the reference at the end "
              "time [m]; energy: the largest energy drift over the run [energy scales, "
              "sim/divergence.h], no reference needed");
DEFINE_double(at, 0.0, "End time [s], > 0; default: the scene's time_step x steps");
DEFINE_string(tune_integrators, "newmark,backward_euler", "Integrators to search");
DEFINE_string(tune_optimizers, "newton,projected_newton", "Optimisers to search");
DEFINE_double(budget_seconds, 240.0,
              "Stop searching after this much wall time [s] (the reference included), in (0, "
              "1e6]; the best found so far is reported");
DEFINE_string(tune_output, "", "CSV file: one row per run of the search");

namespace ipstep {
namespace {

// The fixed steps of the search, coarse to fine, in units of the scene's step.
constexpr double kStepFactors[] = {2.0, 1.0, 0.5, 0.25, 0.125};
// With --match_default, "equal error" is equal to about three digits: the
// target is itself a measurement, and runs that differ from the default only
// in h or the tolerance often end within round-off of its error (backward
// Euler on the cloth, whose error is its damped vibration).
constexpr double kMatchSlack = 1e-3;

struct Candidate {
  std::string integrator, optimizer;
  bool adaptive = false;
  double dt = 0.0;               // fixed runs, and the first step of adaptive ones
  double tolerance = 0.0;        // solver [m/s]
  double error_tolerance = 0.0;  // adaptive [m]
  // results
  double error = NAN, seconds = NAN;
  int steps = 0, failed = 0;
  long iterations = 0;  // solver iterations, rejected attempts included
  std::string status;
  // --tune_output: search (a run of the search), pick (the recommended one),
  // default (backward_euler + newton at the scene's step), validation (the
  // pick against the finer reference).
  std::string role = "search";
};

Candidate Fixed(const std::string& integrator, const std::string& optimizer, double dt,
                double tolerance) {
  Candidate c;
  c.integrator = integrator;
  c.optimizer = optimizer;
  c.dt = dt;
  c.tolerance = tolerance;
  return c;
}

std::string CommandLine(const std::string& scene, const Candidate& c, double t_end) {
  char text[400];
  if (c.adaptive) {
    std::snprintf(text, sizeof(text),
                  "ipstep --scene=%s --integrator=%s --optimizer=%s --adaptive "
                  "--error_tolerance=%.3g --dt=%.6g --t_end=%.6g",
                  scene.c_str(), c.integrator.c_str(), c.optimizer.c_str(), c.error_tolerance, c.dt,
                  t_end);
  } else {
    std::snprintf(text, sizeof(text),
                  "ipstep --scene=%s --integrator=%s --optimizer=%s --dt=%.10g --t_end=%.6g "
                  "--tolerance=%.3g",
                  scene.c_str(), c.integrator.c_str(), c.optimizer.c_str(), c.dt, t_end,
                  c.tolerance);
  }
  return text;
}

std::string Label(const Candidate& c) {
  char text[200];
  if (c.adaptive) {
    std::snprintf(text, sizeof(text), "%s + %s, adaptive E = %.3g m", c.integrator.c_str(),
                  c.optimizer.c_str(), c.error_tolerance);
  } else {
    std::snprintf(text, sizeof(text), "%s + %s, h = %.4g s, tolerance %.3g m/s",
                  c.integrator.c_str(), c.optimizer.c_str(), c.dt, c.tolerance);
  }
  return text;
}

int Run(const EffectRegistry& registry) {
  if (FLAGS_match_default && !FlagIsDefault("target_error")) {
    throw InputError("flag", "--match_default", "give --target_error or --match_default, not both");
  }
  if (!FLAGS_match_default && (!(FLAGS_target_error > 0.0) || !std::isfinite(FLAGS_target_error))) {
    throw InputError("flag", "--target_error", "give the error to reach, a finite number > 0");
  }
  if (FLAGS_measure != "position" && FLAGS_measure != "energy") {
    throw InputError("flag", "--measure",
                     "must be 'position' or 'energy', got '" + ClipInput(FLAGS_measure) + "'");
  }
  CheckFlagRange("budget_seconds", FLAGS_budget_seconds, 0.0, 1e6, "s", "", /*min_open=*/true);
  SimulationOptions base = SimulationOptionsFromFlags(registry);
  base.max_substeps = kProgramMaxSubsteps;
  const Scene scene = LoadScene(FLAGS_scene, SceneLoadOptionsFromFlags(registry));
  CheckContactFlagsApply(scene);
  const double dt = base.time_step > 0.0 ? base.time_step : scene.time_step;
  double t_end = base.t_end > 0.0 ? base.t_end : dt * scene.steps;  // --t_end, as --at
  base.t_end = 0.0;                                                 // each run sets its own steps
  if (!FlagIsDefault("at")) {
    t_end = CheckFlagRange("at", FLAGS_at, 0.0, 1e7, "s", "", /*min_open=*/true);
  }
  if (!(t_end > 0.0)) throw InputError("flag", "--at", "the scene has no steps: give --at");
  const std::vector<std::string> integrators = SplitList(FLAGS_tune_integrators);
  const std::vector<std::string> optimizers = SplitList(FLAGS_tune_optimizers);
  for (const std::string& name : integrators) {
    IntegratorOptions check = base.integrator;
    check.name = name;
    const MadeIntegrator integrator = MakeIntegrator(check);
    if (!integrator.variational || integrator.common().order() < 1) {
      throw InputError("flag", "--tune_integrators",
                       "'" + ClipInput(name) + "': only dynamic variational integrators");
    }
  }
  for (const std::string& name : optimizers) ParseOptimizer(name);
  const bool position = FLAGS_measure == "position";
  // Opened before the search, so that a path that cannot be written is an
  // error now, not after it (io/output_file.h).
  std::unique_ptr<OutputFile> tune_output;
  if (!FLAGS_tune_output.empty()) {
    tune_output = std::make_unique<OutputFile>(FLAGS_tune_output, "flag: --tune_output");
  }
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };

  // The reference: Newmark at dt / 64 (its own error from dt / 32).
  ReferenceOptions reference_options;
  reference_options.optimizer.optimizer = Optimizer::kProjectedNewton;
  reference_options.optimizer.tolerance = 1e-8;
  reference_options.refinement = 64;
  ReferenceSolution reference;
  if (position) {
    std::fprintf(stderr, "ipstep_tune: reference run ...\n");
    reference = ComputeReference(scene, base, reference_options, dt, t_end);
  }
  // Runs `c` and measures its error (against `against` for --measure=position).
  auto measure_against = [&](Candidate* c, const ReferenceSolution& against) {
    SimulationOptions options = base;
    options.integrator.name = c->integrator;
    options.optimizer.optimizer = ParseOptimizer(c->optimizer);
    options.optimizer.tolerance = c->tolerance;
    RunOptions run_options;
    if (c->adaptive) {
      run_options.adaptive = true;
      run_options.adaptive_options.error_tolerance = c->error_tolerance;
      run_options.adaptive_options.t_end = t_end;
      run_options.adaptive_options.initial_time_step = c->dt;
      options.accept_residual = AdaptiveStallResidual(run_options.adaptive_options);
      options.max_substeps = 1;
      options.time_step = c->dt;
    } else {
      options.time_step = c->dt;
      options.steps = static_cast<int>(std::llround(t_end / c->dt));
    }
    run_options.max_wall_seconds = std::max(1.0, FLAGS_budget_seconds - elapsed());
    Simulation sim(scene, options);
    const RunSummary run = RunTrajectory(sim, run_options);
    c->seconds = run.wall_seconds;
    c->steps = run.steps_done;
    c->failed = run.failed;
    c->iterations = run.iterations;
    c->status = run.message;
    if (run.termination != RunTermination::kCompleted || run.diverged()) return;
    c->error = position ? MaxNodeDistance(sim.state().x, against.x, FreeNodes(sim.state()),
                                          sim.state().dimension)
                        : run.max_energy_drift;
  };

  // The default configuration at the scene's step, for comparison (and the
  // target, with --match_default).
  Candidate fallback =
      Fixed("backward_euler", "newton", t_end / std::max(1.0, std::round(t_end / dt)),
            OptimizerOptions{}.tolerance);
  fallback.role = "default";
  measure_against(&fallback, reference);
  double target = FLAGS_target_error;
  if (FLAGS_match_default) {
    if (!(fallback.error > 0.0)) {
      std::printf("the default (backward_euler + newton at h = %g s) has no error to match (%s)\n",
                  fallback.dt, fallback.status.c_str());
      return 1;
    }
    target = fallback.error;
  }
  // What counts as within the target.
  const double within = FLAGS_match_default ? target * (1.0 + kMatchSlack) : target;
  std::printf(
      "scene %s: error target %.3g %s%s at t = %g s (%s)\n", scene.name.c_str(), target,
      position ? "m" : "energy scales", FLAGS_match_default ? " (the default's error)" : "", t_end,
      position ? ("reference: " + reference.description).c_str() : "energy drift, no reference");
  if (position && !reference.exact && reference.error > target / 3) {
    std::printf(
        "warning: the reference's own estimated error %.3g m is not far below the "
        "target\n",
        reference.error);
  }

  std::vector<Candidate> runs;
  const double tied_tolerance = 0.1 * target / t_end;
  bool out_of_time = false;
  for (const std::string& integrator : integrators) {
    for (const std::string& optimizer : optimizers) {
      std::vector<Candidate> family;
      for (double tolerance : {base.optimizer.tolerance, tied_tolerance}) {
        // A tied tolerance equal to the default would repeat the same runs.
        if (tolerance == tied_tolerance && tied_tolerance == base.optimizer.tolerance &&
            !family.empty()) {
          break;
        }
        for (double factor : kStepFactors) {
          Candidate c = Fixed(integrator, optimizer,
                              t_end / std::max(1.0, std::round(t_end / (dt * factor))), tolerance);
          family.push_back(c);
        }
      }
      for (double share : {1.0, 1.0 / 3.0, 0.1}) {
        Candidate c = Fixed(integrator, optimizer, dt, 0.0);
        c.adaptive = true;
        c.error_tolerance = target * share;
        c.tolerance = 0.1 * c.error_tolerance / t_end;
        family.push_back(c);
      }
      // Coarse to fine within each sequence (5 fixed h per solver tolerance,
      // then 3 adaptive); stop a sequence at its first run within the target.
      std::vector<size_t> starts;
      for (size_t begin = 0; begin + 3 < family.size(); begin += std::size(kStepFactors)) {
        starts.push_back(begin);
      }
      starts.push_back(family.size() - 3);
      for (size_t s = 0; s < starts.size(); ++s) {
        const size_t end = s + 1 < starts.size() ? starts[s + 1] : family.size();
        for (size_t k = starts[s]; k < end; ++k) {
          if (elapsed() > FLAGS_budget_seconds) {
            out_of_time = true;
            break;
          }
          Candidate c = family[k];
          measure_against(&c, reference);
          std::fprintf(stderr, "ipstep_tune: %s: error %.3g, %.3f s, %d steps%s\n",
                       Label(c).c_str(), c.error, c.seconds, c.steps,
                       std::isnan(c.error) ? (" (" + c.status + ")").c_str() : "");
          runs.push_back(c);
          if (c.error <= within) break;
        }
      }
    }
  }
  // Every run of the search, the default and the validation (when there is a pick).
  auto write_runs = [&](const std::vector<Candidate>& rows) {
    if (!tune_output) return;
    std::ostream& out = tune_output->stream();
    out.precision(10);
    out << "integrator,optimizer,adaptive,dt,tolerance,error_tolerance,steps,failed,iterations,"
           "seconds,error,role\n";
    for (const Candidate& c : rows) {
      out << c.integrator << ',' << c.optimizer << ',' << (c.adaptive ? 1 : 0) << ',' << c.dt << ','
          << c.tolerance << ',' << c.error_tolerance << ',' << c.steps << ',' << c.failed << ','
          << c.iterations << ',' << c.seconds << ',' << c.error << ',' << c.role << '\n';
      tune_output->EndRow();
    }
    tune_output->Close();
  };
  // The Pareto front: runs with an error, by cost, each more accurate than every cheaper one.
  std::vector<size_t> measured;  // indices into runs
  for (size_t k = 0; k < runs.size(); ++k) {
    if (!std::isnan(runs[k].error) && runs[k].failed == 0) measured.push_back(k);
  }
  std::stable_sort(measured.begin(), measured.end(),
                   [&runs](size_t a, size_t b) { return runs[a].seconds < runs[b].seconds; });
  std::printf(
      "\nPareto front (%zu runs measured%s):\n\n| configuration | steps | time [s] | "
      "error |\n|---|---|---|---|\n",
      runs.size(), out_of_time ? ", the budget ran out" : "");
  double best_error = HUGE_VAL;
  Candidate* winner = nullptr;
  for (size_t k : measured) {
    Candidate& c = runs[k];
    if (c.error >= best_error) continue;
    best_error = c.error;
    std::printf("| %s | %d | %.3g | %.3g%s |\n", Label(c).c_str(), c.steps, c.seconds, c.error,
                c.error <= within ? " (within target)" : "");
    if (winner == nullptr && c.error <= within) winner = &c;
  }
  if (winner == nullptr) {
    std::printf("\nno run reached the target %g; the most accurate: %.3g\n", target, best_error);
    write_runs(runs);
    return 0;
  }
  winner->role = "pick";
  const size_t winner_index = static_cast<size_t>(winner - runs.data());
  std::printf("\nrecommended (%.3g s, error %.3g):\n  %s\n", winner->seconds, winner->error,
              CommandLine(FLAGS_scene, *winner, t_end).c_str());
  // The comparison with the default from a second, back-to-back run of each
  // (the fastest of each one's two runs: a shared machine slows runs at random).
  Candidate pick_again = *winner, default_again = fallback;
  pick_again.role = default_again.role = "timing";
  measure_against(&pick_again, reference);
  measure_against(&default_again, reference);
  const double pick_seconds = std::min(winner->seconds, pick_again.seconds);
  const double default_seconds = std::min(fallback.seconds, default_again.seconds);
  if (fallback.error <= within) {
    std::printf(
        "the default (backward_euler + newton at h = %g s): error %.3g, %.3f s: %.1fx "
        "the recommended time (fastest of two runs each: %.3g s against %.3g s; iterations "
        "%ld against %ld)\n",
        fallback.dt, fallback.error, default_seconds, default_seconds / pick_seconds,
        default_seconds, pick_seconds, fallback.iterations, winner->iterations);
  } else {
    std::printf(
        "the default (backward_euler + newton at h = %g s) does not reach it: error "
        "%.3g in %.3f s\n",
        fallback.dt, fallback.error, default_seconds);
  }
  runs.push_back(pick_again);
  runs.push_back(default_again);
  if (position && !reference.exact) {
    ReferenceOptions finer = reference_options;
    finer.refinement = 128;
    const ReferenceSolution tight = ComputeReference(scene, base, finer, dt, t_end);
    Candidate again = runs[winner_index];
    again.role = "validation";
    measure_against(&again, tight);
    std::printf("validated against %s: error %.3g (%s the target)\n", tight.description.c_str(),
                again.error, again.error <= within ? "within" : "NOT within");
    runs.push_back(again);
  }
  runs.push_back(fallback);
  write_runs(runs);
  return 0;
}

}  // namespace

int RunTune(int argc, char** argv, const EffectRegistry& registry) {
  return ProgramMain(argc, argv, ProgramName(argc, argv, "ipstep_tune").c_str(),
                     "ipstep_tune --scene=NAME|FILE --target_error=E [--at=T --measure=...]",
                     [&registry] { return Run(registry); });
}

int RunTune(int argc, char** argv) { return RunTune(argc, argv, DefaultEffects()); }

}  // namespace ipstep
