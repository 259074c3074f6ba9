// RunBench (bench/bench_program.h), the ipstep_bench program: sweeps scene x grid size x integrator
// x optimiser x dt x tolerance and writes one CSV row per run (docs/benchmarks.md).
//
//   ipstep_bench --scenes=oscillator,cloth --integrators=backward_euler,newmark
//       --optimizers=newton,lbfgs,projected_newton --dt_factors=1,0.5,0.25
//       --tolerances=1e-6 --output=results/sweep.csv
//   ipstep_bench ... --shard=3/8 --output=results/shard3.csv      (one shard)
//   ipstep_bench --merge='results/shard*.csv' --output=results/sweep.csv
//
// Exit codes: 0 success (failed runs are rows, not errors), 2 bad input (also an
// --output that cannot be written), 3 a failed write of --output (a full disk).
//
// The shards: --shard and --output (apps/shard_files.h), --merge of the shard
// files (bench/bench_shards.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/command_line.h"
#include "apps/program_main.h"
#include "apps/shard_files.h"
#include "bench/bench_program.h"
#include "bench/bench_runner.h"
#include "bench/bench_shards.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/parse_number.h"
#include "energies/effect_registry.h"
#include "io/output_file.h"
#include "problems/scene_loader.h"

DEFINE_string(scenes, "oscillator", "Comma-separated scene names or JSON paths");
DEFINE_string(grid_sizes, "scene",
              "Comma-separated grid sizes (nodes per side, 2 to 1000) for scenes with a grid; "
              "'scene': the scene's own. Ignored for scenes without a grid");
DEFINE_string(integrators, "backward_euler,newmark",
              "Comma-separated: backward_euler, newmark, quasi_static, symplectic_euler");
DEFINE_string(optimizers, "newton,lbfgs,projected_newton",
              "Comma-separated optimiser specs: a Ceres optimiser (newton, dogleg, lbfgs, bfgs, "
              "ncg, gradient_descent) with options as +key=value (e.g. "
              "newton+sparse=SUITE_SPARSE+radius=1e8, newton+backtrack=false, lbfgs+rank=5), or "
              "projected_newton (the "
              "Eigen reference, not Ceres). symplectic_euler always runs once with 'none'");
DEFINE_string(dts, "",
              "Comma-separated time steps [s], each in [1e-12, 1e3]; default: the scene's "
              "time_step x --dt_factors");
DEFINE_string(dt_factors, "1", "Comma-separated factors of the scene's time_step (without --dts)");
DEFINE_string(tolerances, "1e-6", "Comma-separated stopping tolerances [m/s] (keep >= 1e-8)");
DEFINE_double(t_end, 0.0,
              "Simulated time [s], > 0; default: the scene's time_step x steps. Each dt is "
              "adjusted to t_end / round(t_end / dt) so that all runs end at the same time "
              "(at most 10000000 steps per run)");
DEFINE_int32(steps, 0,
             "Simulate this many steps of the largest dt (sets t_end), in [1, 10000000]; "
             "default: see --t_end");
DEFINE_int32(repeats, 3, "Timed runs per configuration (the median is reported), in [1, 1000]");
DEFINE_int32(warmup, 1, "Untimed runs before the timed ones, in [0, 1000]");
DEFINE_double(max_run_seconds, 120.0,
              "A run longer than this [s] stops (status timeout) and is not repeated, in [0, "
              "1e9]; 0: no limit");
DEFINE_bool(errors, true,
            "Compute errors against the exact solution (oscillator) or a reference run");
DEFINE_string(reference_optimizer, "projected_newton", "Optimiser spec of the reference runs");
DEFINE_double(reference_tolerance, 1e-8, "Stopping tolerance of the reference runs [m/s], > 0");
DEFINE_string(reference_cache, "",
              "Folder the reference runs are kept in and read from, shared by the shards of a "
              "sweep (one file per reference, keyed by scene, grid, method, dt, t_end, optimiser, "
              "tolerance and commit); default: 'references' beside --output; 'none': no files");
DEFINE_string(shard, "0/1", "i/N: run only configurations with index % N == i");
DEFINE_string(output, "bench.csv", "CSV output (with --merge: the merged file)");
DEFINE_string(merge, "",
              "Comma-separated CSV files or glob patterns from sharded runs: merge them into "
              "--output (sorted by id) and exit");
DEFINE_bool(dry_run, false, "List the configurations of this shard and exit");
DEFINE_bool(interleave, false,
            "Run the warm-up and timed runs of all configurations round-robin (run r of "
            "every configuration before run r + 1 of any) instead of one configuration "
            "after another; rows are written at the end");

namespace ipstep {
namespace bench {
namespace {

// An item of a list flag (--integrators, --optimizers) that the library
// rejects: the library names its option ("options: OptimizerOptions.
// sparse_library: ...", apps/flag_names.h), which ipstep_bench has no flag
// for, so the error names the list flag and the item.
template <class Check>
auto CheckedItem(const char* flag, const std::string& item, const Check& check) {
  try {
    return check();
  } catch (const InputError& error) {
    const std::string message = error.what();
    const std::string prefix = "options: ";
    const size_t name_end = message.find(": ", prefix.size());
    if (message.rfind(prefix, 0) != 0 || name_end == std::string::npos) throw;
    throw InputError("flag", std::string("--") + flag,
                     "'" + ClipInput(item) + "': " + message.substr(name_end + 2));
  }
}

// Runs and warm-up runs per configuration: each is a whole trajectory.
constexpr int kMaxRepeats = 1000;

// A list of numbers > 0 (and <= max).
std::vector<double> NumberList(const std::string& flag, const std::string& text,
                               double max = std::numeric_limits<double>::max()) {
  std::vector<double> numbers;
  for (const std::string& item : SplitList(text)) {
    double value = 0.0;
    if (!ParseFiniteNumber(item, &value) || value <= 0.0 || value > max) {
      throw InputError("flag", "--" + flag,
                       "'" + ClipInput(item) + "' is not a number in " +
                           limits::RangeText(0.0, max, "", /*min_open=*/true));
    }
    numbers.push_back(value);
  }
  return numbers;
}

// A time step of the sweep: in the range of --dt (core/input_limits.h).
void CheckTimeStep(const std::string& flags, double dt) {
  if (!(dt >= limits::kMinTimeStep && dt <= limits::kMaxTimeStep)) {
    throw InputError("flag", flags,
                     "give a time step of " + limits::FormatLimit(dt) + " s; it must be in " +
                         limits::RangeText(limits::kMinTimeStep, limits::kMaxTimeStep, "s"));
  }
}

struct SceneSetup {
  std::string scene;
  int grid_size;
  double t_end;
  std::vector<double> dts;
};

int Run(const EffectRegistry& registry) {
  if (!FLAGS_merge.empty()) return Merge();
  int shard = 0, shards = 1;
  ParseShard(FLAGS_shard, &shard, &shards);
  CheckFlagRange("repeats", FLAGS_repeats, 1, kMaxRepeats, "");
  CheckFlagRange("warmup", FLAGS_warmup, 0, kMaxRepeats, "");
  // --steps and --t_end: 0 is their unset value, not an explicit choice.
  if (!FlagIsDefault("steps")) {
    CheckFlagRange("steps", FLAGS_steps, 1, limits::kMaxSteps, "the scene's time_step x steps");
  }
  if (!FlagIsDefault("t_end")) {
    CheckFlagRange("t_end", FLAGS_t_end, 0.0, limits::kMaxSteps * limits::kMaxTimeStep, "s",
                   "the scene's time_step x steps", /*min_open=*/true);
  }
  CheckFlagRange("max_run_seconds", FLAGS_max_run_seconds, 0.0, limits::kMaxTimeLimit, "s", "");
  if (!(FLAGS_reference_tolerance > 0.0) || !std::isfinite(FLAGS_reference_tolerance)) {
    throw InputError("flag", "--reference_tolerance", "must be a finite number > 0");
  }
  const std::vector<std::string> scenes = SplitList(FLAGS_scenes);
  const std::vector<std::string> integrators = SplitList(FLAGS_integrators);
  const std::vector<std::string> optimizers = SplitList(FLAGS_optimizers);
  const std::vector<double> tolerances = NumberList("tolerances", FLAGS_tolerances);
  std::vector<int> grid_sizes;
  for (const std::string& item : SplitList(FLAGS_grid_sizes)) {
    if (item == "scene") {
      grid_sizes.push_back(0);  // RunConfig::grid_size 0: the scene's
      continue;
    }
    const int size = std::atoi(item.c_str());
    if (std::to_string(size) != item || size < 2 || size > limits::kMaxGridSize) {
      throw InputError("flag", "--grid_sizes",
                       "'" + ClipInput(item) + "' is not an integer in [2, " +
                           std::to_string(limits::kMaxGridSize) +
                           "] or 'scene' (the scene's own size)");
    }
    grid_sizes.push_back(size);
  }
  if (scenes.empty() || integrators.empty() || optimizers.empty() || tolerances.empty() ||
      grid_sizes.empty()) {
    throw InputError("flag", "--scenes/--integrators/--optimizers/--tolerances/--grid_sizes",
                     "lists must not be empty");
  }
  for (const std::string& integrator : integrators) {
    CheckedItem("integrators", integrator, [&integrator] {
      MakeIntegrator({integrator, 0.25, 0.5});
    });
  }
  std::map<std::string, OptimizerSpec> specs;
  for (const std::string& text : optimizers) {
    specs.emplace(
        text, CheckedItem("optimizers", text, [&text] { return ParseOptimizerSpec(text, 1e-6); }));
  }
  specs.emplace("none", ParseOptimizerSpec("none", 1e-6));

  // Scenes, their grid sizes, end time and time steps.
  std::vector<SceneSetup> setups;
  for (const std::string& name : scenes) {
    SceneLoadOptions defaults;
    defaults.extra_effects = registry.UserNames();
    const Scene scene = LoadScene(name, defaults);
    std::set<int> sizes;
    for (int size : grid_sizes) {
      SceneLoadOptions load = defaults;
      load.grid_size = size;
      try {
        LoadScene(name, load);
        sizes.insert(size);
      } catch (const InputError&) {
        sizes.insert(0);  // no grid: the size does not apply
      }
    }
    std::vector<double> dts = NumberList("dts", FLAGS_dts, limits::kMaxTimeStep);
    for (double dt : dts) CheckTimeStep("--dts", dt);
    if (dts.empty()) {
      for (double f : NumberList("dt_factors", FLAGS_dt_factors)) {
        dts.push_back(scene.time_step * f);
        CheckTimeStep("--dt_factors", dts.back());
      }
    }
    if (dts.empty()) throw InputError("flag", "--dts/--dt_factors", "no time step");
    const double dt_max = *std::max_element(dts.begin(), dts.end());
    double t_end = FLAGS_t_end > 0.0 ? FLAGS_t_end : scene.time_step * scene.steps;
    if (FLAGS_steps > 0) t_end = FLAGS_steps * dt_max;
    for (double& dt : dts) {
      const double steps = std::max(1.0, std::round(t_end / dt));
      if (!(steps <= limits::kMaxSteps)) {
        throw InputError("flag", "--t_end/--steps/--dts/--dt_factors",
                         "scene " + ClipInput(name) + ": t_end " + limits::FormatLimit(t_end) +
                             " s at dt " + limits::FormatLimit(dt) + " s is " +
                             limits::FormatLimit(steps) + " steps, more than " +
                             std::to_string(limits::kMaxSteps));
      }
      dt = t_end / steps;
      CheckTimeStep("--t_end/--steps/--dts/--dt_factors", dt);
    }
    for (int size : sizes) setups.push_back({name, size, t_end, dts});
  }

  std::vector<RunConfig> configs;
  for (const SceneSetup& s : setups) {
    for (const std::string& integrator : integrators) {
      const bool explicit_method =
          MakeIntegrator({integrator, 0.25, 0.5}).explicit_integrator != nullptr;
      const std::vector<std::string> methods =
          explicit_method ? std::vector<std::string>{"none"} : optimizers;
      for (const std::string& optimizer : methods) {
        if (!explicit_method && optimizer == "none") continue;
        for (double dt : s.dts) {
          for (size_t t = 0; t < (explicit_method ? 1 : tolerances.size()); ++t) {
            RunConfig c;
            c.effects = &registry;
            c.id = static_cast<int>(configs.size());
            c.scene = s.scene;
            c.grid_size = s.grid_size;
            c.integrator = integrator;
            c.optimizer = optimizer;
            c.steps = static_cast<int>(std::llround(s.t_end / dt));
            c.dt = dt;
            c.tolerance = tolerances[t];
            c.repeats = FLAGS_repeats;
            c.warmup = FLAGS_warmup;
            c.max_run_seconds = FLAGS_max_run_seconds;
            configs.push_back(c);
          }
        }
      }
    }
  }
  std::vector<RunConfig> mine;
  for (const RunConfig& c : configs) {
    if (c.id % shards == shard) mine.push_back(c);
  }
  std::fprintf(stderr, "ipstep_bench: %zu configurations, %zu in shard %d/%d\n", configs.size(),
               mine.size(), shard, shards);
  if (FLAGS_dry_run) {
    for (const RunConfig& c : mine) {
      std::printf("%d %s grid=%d %s %s dt=%g steps=%d tol=%g\n", c.id, c.scene.c_str(), c.grid_size,
                  c.integrator.c_str(), c.optimizer.c_str(), c.dt, c.steps, c.tolerance);
    }
    return 0;
  }
  const std::unique_ptr<OutputFile> output = OpenOutputCreatingFolder(FLAGS_output, "output");
  output->stream() << CsvHeader() << '\n';
  output->Flush();

  ReferenceCache references(FLAGS_reference_optimizer, FLAGS_reference_tolerance, &registry);
  if (FLAGS_reference_cache != "none") {
    references.set_directory(
        FLAGS_reference_cache.empty()
            ? (std::filesystem::path(FLAGS_output).parent_path() / "references").string()
            : FLAGS_reference_cache);
  }
  std::map<std::pair<std::string, int>, double> dt_min;
  for (const SceneSetup& s : setups) {
    dt_min[{s.scene, s.grid_size}] = *std::min_element(s.dts.begin(), s.dts.end());
  }
  // One run of a configuration; false once it needs no more (an incomplete run
  // is not repeated).
  auto run_once = [&](const RunConfig& config, int run, RunRow* row) {
    OptimizerSpec spec = specs.at(config.optimizer);
    spec.options.tolerance = config.tolerance;
    row->result = RunConfiguration(config, spec);
    const bool complete = row->result.steps_done == config.steps;
    if (run >= config.warmup || !complete) row->wall.push_back(row->result.loop_seconds);
    return complete && run + 1 < config.warmup + config.repeats;
  };
  auto finish = [&](RunRow* row) {
    const RunConfig& config = row->config;
    row->position_error = std::nan("");
    row->reference_error = std::nan("");
    row->reference_dt = std::nan("");
    const double t_end = config.dt * config.steps;
    if (FLAGS_errors && row->result.steps_done == config.steps) {
      const ReferenceSolution& ref =
          references.Get(config.scene, config.grid_size, config.integrator,
                         dt_min.at({config.scene, config.grid_size}), t_end);
      row->reference = ref.exact ? "exact" : ref.description;
      row->reference_dt = ref.exact ? std::nan("") : ref.dt;
      row->reference_error = ref.error;
      row->position_error = MaxNodeDistance(row->result.final_x, ref.x, row->result.free_nodes,
                                            row->result.dimension);
    }
    output->stream() << CsvRow(*row) << '\n';
    output->Flush();  // a stopped sweep keeps its rows; a failed write stops it (exit code 3)
    std::fprintf(stderr,
                 "[%d] %s grid=%d %s %s dt=%.4g tol=%g: %.3f ms/step, %.2f it/step, "
                 "%d failed, error %.3g, %s\n",
                 config.id, config.scene.c_str(), config.grid_size, config.integrator.c_str(),
                 config.optimizer.c_str(), config.dt, config.tolerance,
                 row->wall.empty() ? 0.0 : 1e3 * row->wall.back() / std::max(1, config.steps),
                 static_cast<double>(row->result.iterations) / std::max(1, row->result.steps_done),
                 row->result.failed_steps, row->position_error, row->result.status.c_str());
  };
  std::vector<RunRow> rows(mine.size());
  for (size_t i = 0; i < mine.size(); ++i) {
    rows[i].config = mine[i];
    rows[i].shard = FLAGS_shard;
    rows[i].configurations = static_cast<int>(configs.size());
  }
  if (FLAGS_interleave) {
    // Round-robin: run r of every configuration before run r + 1 of any, so
    // that a slow period of a shared machine hits all of them alike.
    std::vector<bool> more(mine.size(), true);
    for (int run = 0; std::find(more.begin(), more.end(), true) != more.end(); ++run) {
      for (size_t i = 0; i < mine.size(); ++i) {
        if (more[i]) more[i] = run_once(mine[i], run, &rows[i]);
      }
    }
    for (RunRow& row : rows) finish(&row);
  } else {
    for (size_t i = 0; i < mine.size(); ++i) {
      for (int run = 0; run_once(mine[i], run, &rows[i]); ++run) {
      }
      finish(&rows[i]);
    }
  }
  output->Close();
  if (FLAGS_errors) {
    std::fprintf(stderr, "ipstep_bench: %d reference runs computed, the others read from %s\n",
                 references.computed(),
                 FLAGS_reference_cache == "none" ? "memory" : "the reference cache");
  }
  return 0;
}

}  // namespace
}  // namespace bench

int RunBench(int argc, char** argv, const EffectRegistry& registry) {
  return ProgramMain(argc, argv, ProgramName(argc, argv, "ipstep_bench").c_str(),
                     "ipstep_bench --scenes=... --integrators=... --optimizers=... "
                     "[--dts|--dt_factors] [--tolerances] [--shard=i/N] --output=FILE.csv",
                     [&registry] { return bench::Run(registry); });
}

int RunBench(int argc, char** argv) { return RunBench(argc, argv, DefaultEffects()); }

}  // namespace ipstep