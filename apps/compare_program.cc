// RunCompare (apps/programs.h), the ipstep_compare program: the default comparison. Runs a scene
// with every integrator x optimiser and prints a markdown table: failed steps, iterations per step,
// time per step, final-time position error and energy drift.
//   ipstep_compare --scene=spring_pendulum
// The error is measured against the exact solution for the oscillator and
// otherwise against Newmark(1/4, 1/2) with newton at dt/16 and a tight tolerance,
// whose own error is estimated from a dt/8 run (second order: e ~ |x8 - x16| / 3).
// The reference tolerance is 1e-7 m/s: near the precision floor of cost-based
// acceptance (README "Precision floor"); its failed steps are reported.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <gflags/gflags.h>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "apps/near_miss.h"
#include "apps/program_main.h"
#include "apps/programs.h"
#include "apps/solver_flags.h"
#include "core/input_error.h"
#include "problems/scene_loader.h"
#include "sim/divergence.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

DEFINE_string(integrators, "backward_euler,newmark,symplectic_euler",
              "Comma-separated integrators to compare");
DEFINE_string(optimizers, "newton,dogleg,gauss_newton,projected_newton,lbfgs,ncg",
              "Comma-separated optimizers to compare (variational integrators); add bfgs "
              "and gradient_descent for the full set (both are slow on large scenes). "
              "projected_newton is ipstep's own Newton on Eigen (not Ceres), the yardstick");

namespace ipstep {
namespace {

// The reference's tolerance [m/s]: near the precision floor of cost-based
// acceptance (README "Precision floor").
constexpr double kReferenceTolerance = 1e-7;

struct RunResult {
  RunSummary run;
  Eigen::VectorXd x;
  std::vector<int> free_nodes;
  int dimension = 2;
};

RunResult RunOnce(const Scene& scene, const SimulationOptions& options) {
  Simulation sim(scene, options);
  RunResult result;
  result.run = RunTrajectory(sim);
  result.x = sim.state().x;
  result.free_nodes = FreeNodes(sim.state());
  result.dimension = sim.state().dimension;
  return result;
}

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
      if (std::string(error.what()).rfind(std::string(option) + ": ", 0) != 0) throw;
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
  const std::vector<std::string> integrators =
      CheckedList("integrators", "options: IntegratorOptions.name", FLAGS_integrators, "integrator",
                  IntegratorNames(), [&base](const std::string& name) {
                    IntegratorOptions check = base.integrator;
                    check.name = name;
                    if (!MakeIntegrator(check)) {
                      throw InputError("options", "IntegratorOptions.name", "no integrator");
                    }
                  });
  const std::vector<std::string> optimizers = CheckedList(
      "optimizers", "options: OptimizerOptions.optimizer", FLAGS_optimizers, "optimizer",
      OptimizerNames(), [](const std::string& name) { ParseOptimizer(name); });

  const double dt = base.time_step > 0.0 ? base.time_step : scene.time_step;
  // --t_end: its steps (Simulation checks that they are whole).
  const int steps = base.t_end > 0.0  ? static_cast<int>(std::llround(base.t_end / dt))
                    : base.steps >= 0 ? base.steps
                                      : scene.steps;
  const double t_end = dt * steps;

  ReferenceOptions reference_options;
  reference_options.optimizer.tolerance = kReferenceTolerance;
  if (!ExactPositions(scene, t_end, nullptr)) {
    std::fprintf(stderr, "ipstep_compare: reference runs (Newmark at dt/16 and dt/8) ...\n");
  }
  const ReferenceSolution reference = ComputeReference(scene, base, reference_options, dt, t_end);
  std::string reference_note = reference.description;
  if (!reference.exact) {
    char note[160];
    std::snprintf(note, sizeof(note), " (%d of %d steps not converged); its estimated error %.2e m",
                  reference.failed_steps, reference.steps, reference.error);
    reference_note += note;
  }

  std::printf("scene %s: %d nodes, dt %g s, %d steps (t = %g s), tolerance %g m/s\n",
              scene.name.c_str(), scene.num_nodes(), dt, steps, t_end, base.optimizer.tolerance);
  std::printf("reference: %s\n\n", reference_note.c_str());
  // Progress on stderr, one line per configuration; the table at the end, so
  // that it is not interleaved with them on a terminal.
  int total = 0;
  for (const std::string& integrator : integrators) {
    total += integrator == "symplectic_euler" ? 1 : static_cast<int>(optimizers.size());
  }
  std::string table =
      "| integrator | optimizer | dt [s] | failed steps | iterations/step | ms/step | position "
      "error [m] | max energy drift [energy scales] |\n|---|---|---|---|---|---|---|---|\n";
  int done = 0, diverged = 0;
  for (const std::string& integrator : integrators) {
    const bool explicit_method = integrator == "symplectic_euler";
    for (const std::string& optimizer : optimizers) {
      SimulationOptions options = base;
      options.integrator.name = integrator;
      options.optimizer.optimizer = ParseOptimizer(optimizer);
      const std::string label = explicit_method                   ? "(explicit)"
                                : optimizer == "projected_newton" ? "projected_newton (not Ceres)"
                                                                  : optimizer;
      const RunResult result = RunOnce(scene, options);
      const RunSummary& r = result.run;
      char row[400];
      if (r.diverged()) {
        ++diverged;
        std::snprintf(row, sizeof(row),
                      "| %s | %s | %g | %d | %.1f | %.3f | diverged (step %d) | diverged |\n",
                      integrator.c_str(), label.c_str(), dt, r.failed, r.iterations_per_step(),
                      r.ms_per_step(), r.diverged_at);
      } else {
        const double error =
            MaxNodeDistance(result.x, reference.x, result.free_nodes, result.dimension);
        std::snprintf(row, sizeof(row), "| %s | %s | %g | %d | %.1f | %.3f | %.3e | %.3e |\n",
                      integrator.c_str(), label.c_str(), dt, r.failed, r.iterations_per_step(),
                      r.ms_per_step(), error, r.max_energy_drift);
      }
      table += row;
      std::fprintf(
          stderr, "ipstep_compare: [%d/%d] %s %s: %.2f s, %d failed steps%s\n", ++done, total,
          integrator.c_str(), explicit_method ? "(explicit)" : optimizer.c_str(), r.wall_seconds,
          r.failed,
          r.diverged_at > 0 ? (", diverged at step " + std::to_string(r.diverged_at)).c_str() : "");
      if (explicit_method) break;  // no optimiser involved
    }
  }
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
