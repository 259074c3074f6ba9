#include "bench/bench_runner.h"
#include "apps/commit.h"
#include "sim/default_effects.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/parse_number.h"
#include "core/scoped_timer.h"
#include "energies/effect_registry.h"
#include "io/csv_fields.h"
#include "io/reference_file.h"
#include "problems/scene_loader.h"
#include "sim/run_trajectory.h"

namespace ipstep {
namespace bench {
namespace {

std::string Number(double value) {
  if (std::isnan(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

double Median(std::vector<double> values) {
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

Trajectory RunConfiguration(const RunConfig& config, const OptimizerSpec& spec) {
  Trajectory out;
  const auto setup_start = WallClock::now();
  SceneLoadOptions load;
  load.grid_size = config.grid_size;
  const EffectRegistry& effects = config.effects ? *config.effects : DefaultEffects();
  load.extra_effects = effects.UserNames();
  const Scene scene = LoadScene(config.scene, load);
  SimulationOptions options;
  options.effects = &effects;
  options.integrator.name = config.integrator;
  options.optimizer = spec.options;
  options.time_step = config.dt;
  options.steps = config.steps;
  std::unique_ptr<Simulation> sim;
  try {
    sim = std::make_unique<Simulation>(scene, options);
  } catch (const std::exception& e) {
    out.status = std::string("error: ") + e.what();
    out.final_x.resize(0);
    return out;
  }
  const bool variational = sim->variational_integrator() != nullptr;
  if (spec.none != !variational) {
    out.status = "error: optimizer '" + spec.text + "' does not fit integrator " +
                 config.integrator + (variational ? "" : " (use none)");
    return out;
  }
  out.setup_seconds = SecondsSince(setup_start);
  const State& state = sim->state();
  out.nodes = state.num_nodes();
  out.dimension = state.dimension;
  out.free_dofs = state.num_free_nodes() * state.dimension;
  out.free_nodes = FreeNodes(state);
  RunOptions run_options;
  run_options.steps = config.steps;
  run_options.max_wall_seconds = config.max_run_seconds;
  const RunSummary run = ipstep::RunTrajectory(*sim, run_options);
  out.initial_energy = run.initial_energies.total();
  out.max_energy_drift = run.max_energy_drift;
  out.steps_done = run.steps_done;
  out.failed_steps = run.failed;
  out.worst_residual = variational ? run.worst_residual : 0.0;
  out.iterations = run.iterations;
  out.max_step_iterations = run.max_step_iterations;
  out.evaluations = run.evaluations;
  out.loop_seconds = run.wall_seconds;
  switch (run.termination) {
    case RunTermination::kDiverged:
      out.status = "diverged at step " + std::to_string(run.diverged_at);
      break;
    case RunTermination::kTimeout:
      out.status = "timeout after " + std::to_string(run.steps_done) + " steps";
      break;
    default:
      out.status = run.failed > 0 ? "failed steps (first: " + run.first_failure + ")" : "ok";
  }
  out.final_x = state.x;
  if (spec.projected_newton()) {
    out.phases = static_cast<const ProjectedNewtonSolver&>(sim->step_solver()).timings();
  }
  return out;
}

const ReferenceSolution& ReferenceCache::Get(const std::string& scene, int grid_size,
                                             const std::string& integrator, double dt_min,
                                             double t_end) {
  const std::string method = ReferenceIntegratorFor(integrator);
  const auto key = std::make_tuple(scene, grid_size, method, dt_min, t_end);
  auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;
  char key_text[400];
  std::snprintf(key_text, sizeof(key_text), "%s|%d|%s|%.17g|%.17g|%s|%.17g|%s", scene.c_str(),
                grid_size, method.c_str(), dt_min, t_end, optimizer_.c_str(), tolerance_,
                IPSTEP_COMMIT);
  // Computed once by the shards that ask at once (io/reference_file.h).
  ReferenceSolution reference = CachedReference(directory_, key_text, [&] {
    ++computed_;
    const OptimizerSpec spec = ParseOptimizerSpec(optimizer_, tolerance_);
    SceneLoadOptions load;
    load.grid_size = grid_size;
    const EffectRegistry& effects = effects_ ? *effects_ : DefaultEffects();
    load.extra_effects = effects.UserNames();
    SimulationOptions base;
    base.effects = &effects;
    ReferenceOptions options;
    options.integrator = method;
    options.optimizer = spec.options;
    ReferenceSolution computed;
    try {
      computed = ComputeReference(LoadScene(scene, load), base, options, dt_min, t_end);
    } catch (const std::exception& e) {
      computed.ok = false;
      computed.description = std::string("FAILED: ") + e.what();
    }
    if (optimizer_.find('+') != std::string::npos) {
      computed.description += " (" + optimizer_ + ")";
    }
    return computed;
  });
  return cache_.emplace(key, std::move(reference)).first->second;
}

std::string CsvHeader() {
  return "id,scene,grid_size,nodes,free_dofs,integrator,optimizer,dt,steps,t_end,tolerance,"
         "repeats,warmup,wall_s_median,wall_s_min,wall_per_sim_s,ms_per_step,setup_s,"
         "iterations_per_step,max_step_iterations,evaluations_per_step,failed_steps,"
         "worst_residual,steps_done,status,position_error,energy_drift,reference,reference_dt,"
         "reference_error,pn_hessian_s,pn_factorize_s,pn_line_search_s,pn_gradient_s,shard,"
         "configurations,commit";
}

std::string CsvRow(const RunRow& row) {
  const RunConfig& c = row.config;
  const Trajectory& t = row.result;
  const double median = Median(row.wall);
  const double min =
      row.wall.empty() ? std::nan("") : *std::min_element(row.wall.begin(), row.wall.end());
  const int steps = std::max(1, t.steps_done);
  const bool ran = t.steps_done > 0;
  // A diverged run's drift is meaningless.
  const bool diverged = t.status.rfind("diverged", 0) == 0;
  const bool pn = c.optimizer.rfind("projected_newton", 0) == 0;
  std::ostringstream out;
  out << c.id << ',' << CsvField(c.scene) << ',' << c.grid_size << ',' << t.nodes << ','
      << t.free_dofs << ',' << c.integrator << ',' << CsvField(c.optimizer) << ',' << Number(c.dt)
      << ',' << c.steps << ',' << Number(c.dt * c.steps) << ',' << Number(c.tolerance) << ','
      << c.repeats << ',' << c.warmup << ',' << Number(median) << ',' << Number(min) << ','
      << Number(ran ? median / (c.dt * steps) : std::nan("")) << ','
      << Number(ran ? 1e3 * median / steps : std::nan("")) << ',' << Number(t.setup_seconds) << ','
      << Number(static_cast<double>(t.iterations) / steps) << ',' << t.max_step_iterations << ','
      << Number(static_cast<double>(t.evaluations) / steps) << ',' << t.failed_steps << ','
      << Number(t.worst_residual) << ',' << t.steps_done << ',' << CsvField(t.status) << ','
      << Number(row.position_error) << ','
      << Number(ran && !diverged ? t.max_energy_drift : std::nan("")) << ','
      << CsvField(row.reference) << ',' << Number(row.reference_dt) << ','
      << Number(row.reference_error) << ',' << Number(pn ? t.phases.hessian : std::nan("")) << ','
      << Number(pn ? t.phases.factorize : std::nan("")) << ','
      << Number(pn ? t.phases.line_search : std::nan("")) << ','
      << Number(pn ? t.phases.gradient : std::nan("")) << ',' << row.shard << ','
      << row.configurations << ',' << IPSTEP_COMMIT;
  return out.str();
}

}  // namespace bench
}  // namespace ipstep
