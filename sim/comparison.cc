#include "sim/comparison.h"

#include <cmath>
#include <cstdio>

#include "core/input_error.h"

namespace ipstep {
namespace {

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> items;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    if (!item.empty()) items.push_back(item);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return items;
}

}  // namespace

ComparisonOptions DefaultComparisonOptions() {
  ComparisonOptions options;
  options.integrators = Split(kCompareIntegrators);
  options.optimizers = Split(kCompareOptimizers);
  return options;
}

Comparison RunComparison(const Scene& scene, const SimulationOptions& base,
                         const ComparisonOptions& options, const ComparisonCallbacks& callbacks) {
  if (options.integrators.empty()) {
    throw InputError("options", "ComparisonOptions.integrators", "lists no integrator");
  }
  if (options.optimizers.empty()) {
    throw InputError("options", "ComparisonOptions.optimizers", "lists no optimizer");
  }
  for (const std::string& name : options.integrators) {
    IntegratorOptions check = base.integrator;
    check.name = name;
    MakeIntegrator(check);  // throws InputError naming IntegratorOptions.name
  }
  for (const std::string& name : options.optimizers) ParseOptimizer(name);

  Comparison c;
  c.dt = base.time_step > 0.0 ? base.time_step : scene.time_step;
  // t_end: its steps (Simulation checks that they are whole).
  c.steps = base.t_end > 0.0  ? static_cast<int>(std::llround(base.t_end / c.dt))
            : base.steps >= 0 ? base.steps
                              : scene.steps;
  c.t_end = c.dt * c.steps;
  c.tolerance = base.optimizer.tolerance;

  ReferenceOptions reference_options;
  reference_options.optimizer.tolerance = options.reference_tolerance;
  if (!ExactPositions(scene, c.t_end, nullptr) && callbacks.before_reference) {
    callbacks.before_reference();
  }
  c.reference = ComputeReference(scene, base, reference_options, c.dt, c.t_end);
  c.reference_note = c.reference.description;
  if (!c.reference.exact) {
    char note[160];
    std::snprintf(note, sizeof(note), " (%d of %d steps not converged); its estimated error %.2e m",
                  c.reference.failed_steps, c.reference.steps, c.reference.error);
    c.reference_note += note;
  }
  if (callbacks.after_reference) callbacks.after_reference(c);

  int total = 0;
  for (const std::string& integrator : options.integrators) {
    total += integrator == "symplectic_euler" ? 1 : static_cast<int>(options.optimizers.size());
  }
  for (const std::string& integrator : options.integrators) {
    const bool explicit_method = integrator == "symplectic_euler";
    for (const std::string& optimizer : options.optimizers) {
      if (options.interrupt != nullptr && *options.interrupt != 0) {
        c.interrupted = true;
        return c;
      }
      SimulationOptions run_options = base;
      run_options.integrator.name = integrator;
      run_options.optimizer.optimizer = ParseOptimizer(optimizer);
      Simulation sim(scene, run_options);
      RunOptions loop;
      loop.interrupt = options.interrupt;
      loop.after_step = options.after_step;
      ComparisonRow row;
      row.integrator = integrator;
      row.optimizer = explicit_method ? "" : optimizer;
      row.dt = c.dt;
      row.run = RunTrajectory(sim, loop);
      row.position_error = row.run.diverged()
                               ? std::nan("")
                               : MaxNodeDistance(sim.state().x, c.reference.x,
                                                 FreeNodes(sim.state()), sim.state().dimension);
      if (row.run.termination == RunTermination::kInterrupted) c.interrupted = true;
      c.rows.push_back(row);
      if (callbacks.after_row)
        callbacks.after_row(c.rows.back(), static_cast<int>(c.rows.size()), total);
      if (c.interrupted) return c;
      if (explicit_method) break;  // no optimiser involved
    }
  }
  return c;
}

}  // namespace ipstep
