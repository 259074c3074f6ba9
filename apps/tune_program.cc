// RunTune (apps/programs.h), the ipstep_tune program: "this error, at least
// cost". A small, budgeted search over integrator x optimiser x (fixed h or
// adaptive tolerance) x solver tolerance for the cheapest run of a scene whose
// measured error (sim/error_measure.h: at the end time, the largest over the
// run, or the energy drift) is within --target_error, against one reference
// (sim/reference.h); the winner is validated against a reference twice as
// fine; the Pareto front (cost against error) is printed with the recommended
// configuration as an ipstep command line.
//   ipstep_tune --scene=cloth --target_error=1e-3
//   ipstep_tune --scene=cloth --match_default   (target: the default's own error)
// Sharded like ipstep_bench (apps/tune_shards.h): each shard runs its share of
// the integrator x optimiser families and writes it to --tune_output; --merge
// reads the shards back and chooses, times and validates as one search does.
//   ipstep_tune --scene=cloth --target_error=1e-3 --shard=0/2 --tune_output=out/shard0.csv
//   ipstep_tune --scene=cloth --target_error=1e-3 --merge='out/shard*.csv'
// The search (apps/tune_search.h), per integrator x optimiser, coarse to fine,
// stopping at the first run that meets the target (finer ones only cost more):
//   fixed h = dt * {2, 1, 1/2, 1/4, 1/8}, with the default solver tolerance and
//     with one tied to the target (0.1 E / T, as --adaptive sets it);
//   --adaptive with E = target * {1, 1/3, 1/10}.
// Cost (--tune_cost): the run's wall time (sim/run_trajectory.h), on this
// machine, or its solver iterations.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "apps/program_main.h"
#include "apps/programs.h"
#include "apps/shard_files.h"
#include "apps/solver_flags.h"
#include "apps/tune_search.h"
#include "apps/tune_shards.h"
#include "core/input_error.h"
#include "io/output_file.h"
#include "problems/scene_loader.h"
#include "sim/contact_kappa_pin.h"
#include "sim/error_measure.h"
#include "sim/reference.h"

DEFINE_double(target_error, 0.0,
              "The error to reach, > 0: [m] for --measure=position and max_position, in energy "
              "scales for --measure=energy");
DEFINE_bool(match_default, false,
            "Instead of --target_error: the measured error of the default configuration "
            "(backward_euler + newton at the scene's step and the default tolerance), to find "
            "what reaches it at least cost");
DEFINE_string(measure, "position",
              "position: the largest distance of a free node from the reference at the end "
              "time [m]; max_position: the largest such distance over the run, at 20 times "
              "T j / 20 [m]; energy: the largest energy drift over the run [energy scales, "
              "sim/divergence.h], no reference needed");
DEFINE_double(at, 0.0, "End time [s], > 0; default: the scene's time_step x steps");
DEFINE_string(tune_integrators, "newmark,backward_euler", "Integrators to search");
DEFINE_string(tune_optimizers, "newton,projected_newton", "Optimisers to search");
DEFINE_double(budget_seconds, 240.0,
              "Stop searching after this much wall time [s] (the reference included), in (0, "
              "1e6]; the best found so far is reported. Each shard has its own");
DEFINE_string(tune_cost, "seconds",
              "The cost of a run for the Pareto front and the pick: seconds (its wall time) or "
              "iterations (its solver iterations: the same on every machine and run)");
DEFINE_string(tune_output, "",
              "CSV file: one row per run of the search (with --shard: the shard's runs, for "
              "--merge)");
DEFINE_string(shard, "",
              "i/N: run only the integrator x optimiser families f with f % N == i and write "
              "them to --tune_output (no pick); --merge chooses");
DEFINE_string(merge, "",
              "Comma-separated CSV files or glob patterns of a sharded search (every shard "
              "once; the same scene and target flags): choose, time and validate as the "
              "unsharded search does");
DEFINE_string(reference_cache, "",
              "Folder the references are kept in and read from, shared by the shards (one file "
              "per reference, keyed by the flags, the end time and the commit); default: "
              "'references' beside --tune_output with --shard, beside the shard files with "
              "--merge, none otherwise; 'none': no files");

namespace ipstep {
namespace {

using tune::Candidate;

// With --match_default, "equal error" is equal to about three digits: the
// target is itself a measurement, and runs that differ from the default only
// in h or the tolerance often end within round-off of its error (backward
// Euler on the cloth, whose error is its damped vibration).
constexpr double kMatchSlack = 1e-3;

// --reference_cache's folder ("" for none); `beside`: a file the default is beside.
std::string CacheFolder(bool sharded, const std::string& beside) {
  if (FLAGS_reference_cache == "none") return "";
  if (!FLAGS_reference_cache.empty()) return FLAGS_reference_cache;
  if (!sharded) return "";
  return (std::filesystem::path(beside).parent_path() / "references").string();
}

// The flags the recommended command line carries beside the pick's own: the
// scene's and the runs' flags given here, and a pinned contact stiffness.
std::vector<std::pair<std::string, std::string>> RecommendedFlags(double pinned_kappa) {
  std::vector<std::pair<std::string, std::string>> flags = GivenFlags(__FILE__);
  if (pinned_kappa > 0.0) {
    char value[40];
    std::snprintf(value, sizeof(value), "%.17g", pinned_kappa);
    flags.emplace_back("contact_kappa", value);
  }
  return flags;
}

int Run(const EffectRegistry& registry) {
  if (FLAGS_match_default && !FlagIsDefault("target_error")) {
    throw InputError("flag", "--match_default", "give --target_error or --match_default, not both");
  }
  if (!FLAGS_match_default && (!(FLAGS_target_error > 0.0) || !std::isfinite(FLAGS_target_error))) {
    throw InputError("flag", "--target_error", "give the error to reach, a finite number > 0");
  }
  ErrorMeasure measure = ErrorMeasure::kPosition;
  if (!ParseErrorMeasure(FLAGS_measure, &measure)) {
    throw InputError(
        "flag", "--measure",
        "must be 'position', 'max_position' or 'energy', got '" + ClipInput(FLAGS_measure) + "'");
  }
  if (FLAGS_tune_cost != "seconds" && FLAGS_tune_cost != "iterations") {
    throw InputError("flag", "--tune_cost",
                     "must be 'seconds' or 'iterations', got '" + ClipInput(FLAGS_tune_cost) + "'");
  }
  const tune::Cost cost =
      FLAGS_tune_cost == "iterations" ? tune::Cost::kIterations : tune::Cost::kSeconds;
  const bool sharded = !FlagIsDefault("shard"), merging = !FlagIsDefault("merge");
  if (sharded && merging) {
    throw InputError("flag", "--merge",
                     "give --shard (run one shard) or --merge (choose from the shards), not both");
  }
  int shard = 0, shards = 1;
  if (sharded) {
    ParseShard(FLAGS_shard, &shard, &shards);
    if (FLAGS_tune_output.empty()) {
      throw InputError("flag", "--shard",
                       "a shard writes its runs to --tune_output=FILE for --merge: give it");
    }
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
  tune::SearchSpace space;
  space.integrators = SplitList(FLAGS_tune_integrators);
  space.optimizers = SplitList(FLAGS_tune_optimizers);
  if (space.families() == 0) {
    throw InputError("flag", space.integrators.empty() ? "--tune_integrators" : "--tune_optimizers",
                     "give at least one");
  }
  for (const std::string& name : space.integrators) {
    IntegratorOptions check = base.integrator;
    check.name = name;
    const MadeIntegrator integrator = MakeIntegrator(check);
    if (!integrator.variational || integrator.common().order() < 1) {
      throw InputError("flag", "--tune_integrators",
                       "'" + ClipInput(name) + "': only dynamic variational integrators");
    }
  }
  for (const std::string& name : space.optimizers) ParseOptimizer(name);
  space.dt = dt;
  space.t_end = t_end;
  space.target = FLAGS_target_error;
  space.default_tolerance = base.optimizer.tolerance;
  // A contact scene whose kappa adapts to the step would compare barriers,
  // not configurations: every run and the reference get one kappa, the one
  // the default configuration ends with (sim/contact_kappa_pin.h).
  double pinned_kappa = 0.0;
  {
    RunOptions unused;
    SimulationOptions pin =
        tune::CandidateOptions(base, tune::DefaultCandidate(dt, t_end), t_end, &unused);
    pinned_kappa = PinAdaptiveContactKappa(scene, &pin);
    if (pinned_kappa > 0.0) base.effect_overrides = pin.effect_overrides;
  }
  const std::string search =
      tune::SearchKey(FLAGS_scene, FLAGS_measure, FLAGS_match_default, space);
  // Opened before the search, so that a path that cannot be written is an
  // error now, not after it (io/output_file.h).
  std::unique_ptr<OutputFile> tune_output;
  if (!FLAGS_tune_output.empty()) {
    tune_output = std::make_unique<OutputFile>(FLAGS_tune_output, "flag: --tune_output");
  }
  // The shards first: their errors before any run.
  tune::MergedSearch merged;
  if (merging) merged = tune::ReadShards(FLAGS_merge, search, &space);
  const tune::Runner runner(scene, base, measure, t_end, FLAGS_budget_seconds);

  // The reference: Newmark at dt / 64 (its own error from dt / 32), with the
  // positions at kErrorCheckpoints times for max_position.
  ReferenceOptions reference_options;
  reference_options.optimizer.optimizer = Optimizer::kProjectedNewton;
  reference_options.optimizer.tolerance = 1e-8;
  reference_options.refinement = 64;
  reference_options.checkpoints = kErrorCheckpoints;
  const std::string cache =
      CacheFolder(sharded || merging, merging ? merged.first_file : FLAGS_tune_output);
  auto get_reference = [&](const ReferenceOptions& options) {
    std::fprintf(stderr, "ipstep_tune: reference (%s dt / %d) ...\n", options.integrator.c_str(),
                 options.refinement);
    bool computed = false;
    ReferenceSolution r =
        tune::SearchReference(scene, base, options, dt, t_end, cache, __FILE__, &computed);
    if (!computed) std::fprintf(stderr, "ipstep_tune: reference read from %s\n", cache.c_str());
    return r;
  };
  const bool needs_reference = MeasureNeedsReference(measure);
  ReferenceSolution reference;
  if (needs_reference) reference = get_reference(reference_options);
  const ReferenceSolution* against = needs_reference ? &reference : nullptr;
  const double reference_error =
      measure == ErrorMeasure::kMaxPosition ? reference.checkpoint_error : reference.error;

  // The default configuration at the scene's step, for comparison (and the
  // target, with --match_default).
  Candidate fallback = merged.fallback;
  if (!merging) {
    fallback = tune::DefaultCandidate(dt, t_end);
    runner.Measure(&fallback, against);
    if (sharded) fallback.shard = FLAGS_shard;
    if (FLAGS_match_default) {
      if (!(fallback.error > 0.0)) {
        std::printf(
            "the default (backward_euler + newton at h = %g s) has no error to match (%s)\n",
            fallback.dt, fallback.status.c_str());
        return 1;
      }
      space.target = fallback.error;
    }
  }
  const double target = space.target;
  // What counts as within the target.
  space.within = FLAGS_match_default ? target * (1.0 + kMatchSlack) : target;
  const double within = space.within;
  std::printf("scene %s: error target %.3g %s%s%s at t = %g s (%s)\n", scene.name.c_str(), target,
              ErrorMeasureUnit(measure), FLAGS_match_default ? " (the default's error)" : "",
              measure == ErrorMeasure::kMaxPosition ? " over the run" : "", t_end,
              needs_reference ? ("reference: " + reference.description).c_str()
                              : "energy drift, no reference");
  if (pinned_kappa > 0.0) {
    std::printf(
        "contact: kappa adapts to the step, so every run and the reference use kappa = %.6g, "
        "the one the default configuration ends with (--contact_kappa chooses it)\n",
        pinned_kappa);
  }
  if (needs_reference && !reference.exact && reference_error > target / 3) {
    std::printf(
        "warning: the reference's own estimated error %.3g m is not far below the "
        "target\n",
        reference_error);
  }

  std::vector<Candidate> runs;
  bool out_of_time = false;
  if (merging) {
    runs = merged.runs;
    out_of_time = merged.out_of_time;
    std::printf("merged %zu runs of %d shards (%zu files)\n", runs.size(), merged.shards,
                merged.files);
  } else {
    out_of_time = !tune::Search(space, runner, against, shard, shards, &runs);
    if (sharded) {
      for (Candidate& c : runs) c.shard = FLAGS_shard;
    }
  }
  const tune::SearchRecord record{search, target, out_of_time};
  if (sharded) {
    std::vector<Candidate> rows = runs;
    rows.push_back(fallback);
    tune::WriteRows(rows, record, tune_output.get());
    std::printf("shard %s: %zu runs of families", FLAGS_shard.c_str(), runs.size());
    for (int f = shard; f < space.families(); f += shards) std::printf(" %d", f);
    std::printf(" of %d%s, written to %s\n", space.families(),
                out_of_time ? " (the budget ran out)" : "", FLAGS_tune_output.c_str());
    return 0;
  }
  // Every run of the search, the default and the validation (when there is a pick).
  auto write_runs = [&](const std::vector<Candidate>& rows) {
    if (tune_output) tune::WriteRows(rows, record, tune_output.get());
  };
  const std::vector<size_t> front = tune::ParetoFront(runs, cost);
  std::printf(
      "\nPareto front (%zu runs measured%s, cost: %s):\n\n| configuration | steps | iterations | "
      "time [s] | error |\n|---|---|---|---|---|\n",
      runs.size(), out_of_time ? ", the budget ran out" : "", FLAGS_tune_cost.c_str());
  Candidate* winner = nullptr;
  for (size_t k : front) {
    Candidate& c = runs[k];
    std::printf("| %s | %d | %ld | %.3g | %.3g%s |\n", tune::Label(c).c_str(), c.steps,
                c.iterations, c.seconds, c.error, c.error <= within ? " (within target)" : "");
    if (winner == nullptr && c.error <= within) winner = &c;
  }
  if (winner == nullptr) {
    std::printf("\nno run reached the target %g; the most accurate: %.3g\n", target,
                front.empty() ? HUGE_VAL : runs[front.back()].error);
    runs.push_back(fallback);
    write_runs(runs);
    return 0;
  }
  winner->role = "pick";
  const Candidate pick = *winner;
  std::printf("\nrecommended (%.3g s, %ld iterations, error %.3g):\n  %s\n", pick.seconds,
              pick.iterations, pick.error,
              tune::CommandLine(FLAGS_scene, pick, t_end, RecommendedFlags(pinned_kappa)).c_str());
  // The comparison with the default from a second, back-to-back run of each
  // (the fastest of each one's two runs: a shared machine slows runs at random).
  Candidate pick_again = pick, default_again = fallback;
  pick_again.role = default_again.role = "timing";
  runner.Measure(&pick_again, against);
  runner.Measure(&default_again, against);
  const double pick_seconds = std::min(pick.seconds, pick_again.seconds);
  const double default_seconds = std::min(fallback.seconds, default_again.seconds);
  if (fallback.error <= within) {
    std::printf(
        "the default (backward_euler + newton at h = %g s): error %.3g, %.3f s: %.1fx "
        "the recommended time (fastest of two runs each: %.3g s against %.3g s; iterations "
        "%ld against %ld)\n",
        fallback.dt, fallback.error, default_seconds, default_seconds / pick_seconds,
        default_seconds, pick_seconds, fallback.iterations, pick.iterations);
  } else {
    std::printf(
        "the default (backward_euler + newton at h = %g s) does not reach it: error "
        "%.3g in %.3f s\n",
        fallback.dt, fallback.error, default_seconds);
  }
  runs.push_back(pick_again);
  runs.push_back(default_again);
  if (needs_reference && !reference.exact) {
    ReferenceOptions finer = reference_options;
    finer.refinement = 128;
    const ReferenceSolution tight = get_reference(finer);
    Candidate again = pick;
    again.role = "validation";
    runner.Measure(&again, &tight);
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
                     "ipstep_tune --scene=NAME|FILE --target_error=E [--at=T --measure=...] "
                     "[--shard=i/N --tune_output=FILE | --merge=FILES]",
                     [&registry] { return Run(registry); });
}

int RunTune(int argc, char** argv) { return RunTune(argc, argv, DefaultEffects()); }

}  // namespace ipstep
