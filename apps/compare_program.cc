// RunCompare (apps/programs.h), the ipstep_compare program: the default comparison. Runs a scene
// with every integrator x optimiser and prints a markdown table: failed steps, iterations per step,
// time per step, final-time position error and energy drift.
//   ipstep_compare --scene=spring_pendulum
// The error is measured against the exact solution for the oscillator and
// otherwise against Newmark(1/4, 1/2) with newton at dt/16 and a tight tolerance,
// whose own error is estimated from a dt/8 run (second order: e ~ |x8 - x16| / 3).
// The reference tolerance is 1e-7 m/s: near the precision floor of cost-based
// acceptance (docs/optimisers.md "Precision floor"); its failed steps are reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
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
#include "core/near_miss.h"
#include "io/comparison_csv.h"
#include "io/output_file.h"
#include "problems/scene_loader.h"
#include "sim/comparison.h"
#include "sim/divergence.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

DEFINE_string(integrators, ipstep::kCompareIntegrators, "Comma-separated integrators to compare");
DEFINE_string(optimizers, ipstep::kCompareOptimizers,
              "Comma-separated optimizers to compare (variational integrators); add bfgs "
              "and gradient_descent for the full set (both are slow on large scenes). "
              "projected_newton is ipstep's own Newton on Eigen (not Ceres), the yardstick");
DEFINE_string(compare_output, "",
              "CSV file: one row per configuration, the table's columns at full precision "
              "(io/comparison_csv.h)");

namespace ipstep {
namespace {

// The names of a list flag (--integrators, --optimizers), each checked by
// `check`; an InputError naming `option` (the library's name of the item,
// apps/flag_names.h) is an unknown name: an error naming `flag`, with a near
// miss among `known` suggested. Other errors (another option's value) pass.
std::vector<std::string> CheckedList(const char* flag, const char* option, const std::string& text,
                                     const char* what, const std::string& known,
                                     const std::function<void(const std::string&)>& check) {
  const std::vector<std::string> names = SplitList(text);
  if (names.empty())
    throw InputError("flag", std::string("--") + flag, std::string("lists no ") + what);
  std::vector<std::string> candidates;
  for (std::string name : SplitList(known)) {
    name.erase(0, name.find_first_not_of(' '));
    candidates.push_back(name.substr(0, name.find(' ')));
  }
  for (const std::string& name : names) {
    try {
      check(name);
    } catch (const InputError& error) {
      if (error.where() + ": " + error.key() != option) throw;
      const std::string near = NearMiss(name, candidates);
      throw InputError("flag", std::string("--") + flag,
                       "unknown " + std::string(what) + " '" + ClipInput(name) + "'" +
                           (near.empty() ? "" : " (did you mean " + near + "?)") +
                           "; choose from " + known);
    }
  }
  return names;
}

int Run(const EffectRegistry& registry) {
  SimulationOptions base = SimulationOptionsFromFlags(registry);
  const Scene scene = LoadScene(FLAGS_scene, SceneLoadOptionsFromFlags(registry));
  CheckContactFlagsApply(scene);
  ComparisonOptions comparison_options;
  comparison_options.integrators =
      CheckedList("integrators", "options: IntegratorOptions.name", FLAGS_integrators, "integrator",
                  IntegratorNames(), [&base](const std::string& name) {
                    IntegratorOptions check = base.integrator;
                    check.name = name;
                    MakeIntegrator(check);  // throws InputError naming IntegratorOptions.name
                  });
  comparison_options.optimizers = CheckedList(
      "optimizers", "options: OptimizerOptions.optimizer", FLAGS_optimizers, "optimizer",
      OptimizerNames(), [](const std::string& name) { ParseOptimizer(name); });
  // Opened before the runs: a path that cannot be written is an error first.
  std::unique_ptr<OutputFile> csv;
  if (!FLAGS_compare_output.empty()) {
    csv = std::make_unique<OutputFile>(FLAGS_compare_output, "output: compare_output");
    csv->stream() << ComparisonCsvHeader() << '\n';
  }

  ComparisonCallbacks callbacks;
  callbacks.before_reference = [] {
    std::fprintf(stderr, "ipstep_compare: reference runs (Newmark at dt/16 and dt/8) ...\n");
  };
  callbacks.after_reference = [&scene](const Comparison& c) {
    std::printf("scene %s: %d nodes, dt %g s, %d steps (t = %g s), tolerance %g m/s\n",
                scene.name.c_str(), scene.num_nodes(), c.dt, c.steps, c.t_end, c.tolerance);
    std::printf("reference: %s\n\n", c.reference_note.c_str());
  };
  // Progress on stderr, one line per configuration; the table at the end, so
  // that it is not interleaved with them on a terminal.
  callbacks.after_row = [](const ComparisonRow& row, int done, int total) {
    const RunSummary& r = row.run;
    std::fprintf(
        stderr, "ipstep_compare: [%d/%d] %s %s: %.2f s, %d failed steps%s\n", done, total,
        row.integrator.c_str(), row.optimizer.empty() ? "(explicit)" : row.optimizer.c_str(),
        r.wall_seconds, r.failed,
        r.diverged_at > 0 ? (", diverged at step " + std::to_string(r.diverged_at)).c_str() : "");
  };
  const Comparison c = RunComparison(scene, base, comparison_options, callbacks);
  std::string table =
      "| integrator | optimizer | dt [s] | failed steps | iterations/step | ms/step | position "
      "error [m] | max energy drift [energy scales] |\n|---|---|---|---|---|---|---|---|\n";
  int diverged = 0;
  for (const ComparisonRow& row : c.rows) {
    const RunSummary& r = row.run;
    const std::string label = row.optimizer.empty()                 ? "(explicit)"
                              : row.optimizer == "projected_newton" ? "projected_newton (not Ceres)"
                                                                    : row.optimizer;
    char line[400];
    if (r.diverged()) {
      ++diverged;
      std::snprintf(line, sizeof(line),
                    "| %s | %s | %g | %d | %.1f | %.3f | diverged (step %d) | diverged |\n",
                    row.integrator.c_str(), label.c_str(), row.dt, r.failed,
                    r.iterations_per_step(), r.ms_per_step(), r.diverged_at);
    } else {
      std::snprintf(line, sizeof(line), "| %s | %s | %g | %d | %.1f | %.3f | %.3e | %.3e |\n",
                    row.integrator.c_str(), label.c_str(), row.dt, r.failed,
                    r.iterations_per_step(), r.ms_per_step(), row.position_error,
                    r.max_energy_drift);
    }
    table += line;
    if (csv) {
      csv->stream() << ComparisonCsvRow(scene.name, c, row) << '\n';
      csv->EndRow();
    }
  }
  if (csv) csv->Close();
  std::printf("%s", table.c_str());
  if (diverged > 0) {
    std::printf("\ndiverged: %s; the run stops there.\n", DivergenceRule::Description());
  }
  CheckStdout();  // the table is the program's data: a failed write is exit code 3
  return 0;
}

}  // namespace

int RunCompare(int argc, char** argv, const EffectRegistry& registry) {
  return ProgramMain(argc, argv, ProgramName(argc, argv, "ipstep_compare").c_str(),
                     "ipstep_compare --scene=NAME|FILE [--dt --steps --tolerance ...]",
                     [&registry] { return Run(registry); });
}

int RunCompare(int argc, char** argv) { return RunCompare(argc, argv, DefaultEffects()); }

}  // namespace ipstep
