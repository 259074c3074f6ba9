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
#include "apps/divergence.h"
#include "apps/near_miss.h"
#include "apps/program_main.h"
#include "apps/programs.h"
#include "apps/solver_flags.h"
#include "core/input_error.h"
#include "problems/scene_loader.h"
#include "sim/simulation.h"

DEFINE_string(integrators, "backward_euler,newmark,symplectic_euler",
              "Comma-separated integrators to compare");
DEFINE_string(optimizers, "newton,dogleg,gauss_newton,projected_newton,lbfgs,ncg",
              "Comma-separated optimizers to compare (variational integrators); add bfgs "
              "and gradient_descent for the full set (both are slow on large scenes). "
              "projected_newton is ipstep's own Newton on Eigen (not Ceres), the yardstick");

namespace ipstep {
namespace {

struct RunResult {
  int failed = 0;
  int steps_done = 0;
  double iterations_per_step = 0.0;
  double ms_per_step = 0.0;
  double energy_drift = 0.0;  // max |E - E0| / |E0|
  Eigen::VectorXd x;
  double initial_energy = 0.0;
  int diverged_at = 0;  // the step at which the run diverged (apps/divergence.h); 0: it did not
  double seconds = 0.0;
};

RunResult RunOnce(const Scene& scene, SimulationOptions options) {
  Simulation sim(scene, options);
  RunResult result;
  const double e0 = sim.Energies().total();
  result.initial_energy = e0;
  long iterations = 0;
  for (int step = 1; step <= sim.steps(); ++step) {
    const StepReport r = sim.Step();
    ++result.steps_done;
    iterations += r.iterations;
    result.seconds += r.wall_seconds;
    if (!r.converged) ++result.failed;
    const double drift = std::abs(r.energies.total() - e0) / std::max(std::abs(e0), 1e-300);
    result.energy_drift = std::max(result.energy_drift, drift);
    if (RunDiverged(e0, r.energies.total(),
                    sim.state().x.allFinite() && sim.state().v.allFinite())) {
      result.diverged_at = step;
      break;
    }
  }
  const int n = std::max(1, result.steps_done);
  result.iterations_per_step = static_cast<double>(iterations) / n;
  result.ms_per_step = 1e3 * result.seconds / n;
  result.x = sim.state().x;
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

// Exact final positions for the built-in oscillator (omega = 1, u0 = 0.1, at rest).
bool ExactOscillator(const Scene& scene, double t, Eigen::VectorXd* x) {
  if (scene.name != "oscillator") return false;
  *x = Eigen::Map<const Eigen::VectorXd>(scene.positions.data(), scene.positions.size());
  (*x)[2] = 1.0 + 0.1 * std::cos(t);
  return true;
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
  const int steps = base.steps >= 0 ? base.steps : scene.steps;
  const double t_end = dt * steps;

  Eigen::VectorXd reference;
  std::string reference_note;
  if (ExactOscillator(scene, t_end, &reference)) {
    reference_note = "exact solution";
  } else {
    SimulationOptions fine = base;
    fine.integrator = IntegratorOptions{"newmark", 0.25, 0.5};
    fine.optimizer = OptimizerOptions{};
    fine.optimizer.tolerance = 1e-7;
    fine.time_step = dt / 16;
    fine.steps = steps * 16;
    std::fprintf(stderr, "ipstep_compare: reference runs (Newmark at dt/16 and dt/8) ...\n");
    const RunResult r16 = RunOnce(scene, fine);
    fine.time_step = dt / 8;
    fine.steps = steps * 8;
    const RunResult r8 = RunOnce(scene, fine);
    reference = r16.x;
    char note[200];
    std::snprintf(note, sizeof(note),
                  "Newmark(1/4,1/2) + newton at dt/16, tolerance 1e-7 (%d of %d steps not "
                  "converged); its estimated error %.2e m",
                  r16.failed, steps * 16, (r8.x - r16.x).lpNorm<Eigen::Infinity>() / 3.0);
    reference_note = note;
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
      "| integrator | optimizer | failed steps | iterations/step | ms/step | position error [m] "
      "| max energy drift |\n|---|---|---|---|---|---|---|\n";
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
      const RunResult r = RunOnce(scene, options);
      char row[400];
      if (r.diverged_at > 0) {
        ++diverged;
        std::snprintf(row, sizeof(row),
                      "| %s | %s | %d | %.1f | %.3f | diverged (step %d) | diverged |\n",
                      integrator.c_str(), label.c_str(), r.failed, r.iterations_per_step,
                      r.ms_per_step, r.diverged_at);
      } else {
        const double error = (r.x - reference).lpNorm<Eigen::Infinity>();
        char drift[32] = "n/a (E0 = 0)";  // a drift relative to E0 = 0 means nothing
        if (r.initial_energy != 0.0) std::snprintf(drift, sizeof(drift), "%.3e", r.energy_drift);
        std::snprintf(row, sizeof(row), "| %s | %s | %d | %.1f | %.3f | %.3e | %s |\n",
                      integrator.c_str(), label.c_str(), r.failed, r.iterations_per_step,
                      r.ms_per_step, error, drift);
      }
      table += row;
      std::fprintf(
          stderr, "ipstep_compare: [%d/%d] %s %s: %.2f s, %d failed steps%s\n", ++done, total,
          integrator.c_str(), explicit_method ? "(explicit)" : optimizer.c_str(), r.seconds,
          r.failed,
          r.diverged_at > 0 ? (", diverged at step " + std::to_string(r.diverged_at)).c_str() : "");
      if (explicit_method) break;  // no optimiser involved
    }
  }
  std::printf("%s", table.c_str());
  if (diverged > 0) {
    std::printf("\ndiverged: %s (apps/divergence.h); the run stops there.\n", kDivergedRule);
  }
  std::fflush(stdout);
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
