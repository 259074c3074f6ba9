#include "apps/solver_flags.h"

#include <cmath>
#include <stdexcept>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "apps/option_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/default_effects.h"
#include "solver/optimizer_option_table.h"

DEFINE_string(scene, "oscillator",
              "Built-in scene name (listed in --help) or path to a JSON scene file");
// Help text, default and range of each flag: its option row (apps/option_flags.h).
DEFINE_string(integrator, ipstep::FlagDefault<const char*>("integrator"),
              ipstep::FlagHelp("integrator"));
DEFINE_string(optimizer, ipstep::FlagDefault<const char*>("optimizer"),
              ipstep::FlagHelp("optimizer"));
DEFINE_double(dt, ipstep::FlagDefault<double>("dt"), ipstep::FlagHelp("dt"));
DEFINE_int32(steps, ipstep::FlagDefault<int>("steps"), ipstep::FlagHelp("steps"));
DEFINE_double(t_end, ipstep::FlagDefault<double>("t_end"), ipstep::FlagHelp("t_end"));
DEFINE_double(tolerance, ipstep::FlagDefault<double>("tolerance"), ipstep::FlagHelp("tolerance"));
DEFINE_int32(max_iterations, ipstep::FlagDefault<int>("max_iterations"),
             ipstep::FlagHelp("max_iterations"));
DEFINE_double(time_limit, ipstep::FlagDefault<double>("time_limit"),
              ipstep::FlagHelp("time_limit"));
DEFINE_int32(num_threads, ipstep::FlagDefault<int>("num_threads"), ipstep::FlagHelp("num_threads"));
DEFINE_string(linear_solver, ipstep::FlagDefault<const char*>("linear_solver"),
              ipstep::FlagHelp("linear_solver"));
DEFINE_string(sparse_library, ipstep::FlagDefault<const char*>("sparse_library"),
              ipstep::FlagHelp("sparse_library"));
DEFINE_string(linear_solver_ordering, ipstep::FlagDefault<const char*>("linear_solver_ordering"),
              ipstep::FlagHelp("linear_solver_ordering"));
DEFINE_double(trust_region_radius, ipstep::FlagDefault<double>("trust_region_radius"),
              ipstep::FlagHelp("trust_region_radius"));
DEFINE_bool(backtrack_rejected_steps, ipstep::FlagDefault<bool>("backtrack_rejected_steps"),
            ipstep::FlagHelp("backtrack_rejected_steps"));
DEFINE_string(line_search, ipstep::FlagDefault<const char*>("line_search"),
              ipstep::FlagHelp("line_search"));
DEFINE_string(nonlinear_cg, ipstep::FlagDefault<const char*>("nonlinear_cg"),
              ipstep::FlagHelp("nonlinear_cg"));
DEFINE_int32(lbfgs_rank, ipstep::FlagDefault<int>("lbfgs_rank"), ipstep::FlagHelp("lbfgs_rank"));
DEFINE_bool(mass_scaled_coordinates, ipstep::FlagDefault<bool>("mass_scaled_coordinates"),
            ipstep::FlagHelp("mass_scaled_coordinates"));
DEFINE_bool(precise_energy, ipstep::FlagDefault<bool>("precise_energy"),
            ipstep::FlagHelp("precise_energy"));
DEFINE_string(hessian_projection, ipstep::FlagDefault<const char*>("hessian_projection"),
              ipstep::FlagHelp("hessian_projection"));
DEFINE_double(newmark_beta, ipstep::FlagDefault<double>("newmark_beta"),
              ipstep::FlagHelp("newmark_beta"));
DEFINE_double(newmark_gamma, ipstep::FlagDefault<double>("newmark_gamma"),
              ipstep::FlagHelp("newmark_gamma"));
DEFINE_double(energy_tolerance, ipstep::FlagDefault<double>("energy_tolerance"),
              ipstep::FlagHelp("energy_tolerance"));
DEFINE_int32(grid_size, ipstep::FlagDefault<int>("grid_size"), ipstep::FlagHelp("grid_size"));

namespace ipstep {
namespace {

// A given flag that its row says does not apply to the optimiser is an error
// (the rows' order: the trust-region flags, the line-search flags, then
// --hessian_projection).
void RequireApplicableFlags(const OptimizerOptions& p) {
  for (const OptionRow<OptimizerOptions>& row : OptimizerOptionTable()) {
    if (!row.applies || row.flag.empty() || FlagIsDefault(row.flag.c_str())) continue;
    const std::string why = row.applies(p, "--");
    if (!why.empty()) throw InputError("flag", "--" + row.flag, why);
  }
}

}  // namespace

SimulationOptions SimulationOptionsFromFlags(const EffectRegistry& registry) {
  SimulationOptions o;
  o.effects = &registry;
  o.integrator.name = FLAGS_integrator;
  o.integrator.newmark_beta = FLAGS_newmark_beta;
  o.integrator.newmark_gamma = FLAGS_newmark_gamma;
  if (!FlagIsDefault("newmark_beta") || !FlagIsDefault("newmark_gamma")) {
    if (FLAGS_integrator != "newmark") {
      throw InputError("flag", FlagIsDefault("newmark_beta") ? "--newmark_gamma" : "--newmark_beta",
                       "applies to --integrator=newmark only");
    }
  }
  OptimizerOptions& p = o.optimizer;
  p.optimizer = ParseOptimizer(FLAGS_optimizer);
  p.tolerance = FLAGS_tolerance;
  p.linear_solver = FLAGS_linear_solver;
  p.sparse_library = FLAGS_sparse_library;
  p.linear_solver_ordering = FLAGS_linear_solver_ordering;
  p.backtrack_rejected_steps = FLAGS_backtrack_rejected_steps;
  p.line_search = FLAGS_line_search;
  p.nonlinear_cg = FLAGS_nonlinear_cg;
  p.mass_scaled_coordinates = FLAGS_mass_scaled_coordinates;
  p.precise_line_search_energy = FLAGS_precise_energy;
  p.hessian_projection = ParseHessianProjection(FLAGS_hessian_projection);
  RequireApplicableFlags(p);
  // Flags whose unset value is a sentinel of the options (0 or -1: the
  // default) are used only when given, and then must be in range: an explicit
  // --dt=0 is an error, not the scene's time step.
  // Ranges and what omitting the flag means: the option table's rows.
  if (!FlagIsDefault("max_iterations")) {
    p.max_iterations = FlagInRowRange("max_iterations", FLAGS_max_iterations);
  }
  if (!FlagIsDefault("time_limit")) p.time_limit = FlagInRowRange("time_limit", FLAGS_time_limit);
  if (!FlagIsDefault("num_threads")) {
    p.num_threads = FlagInRowRange("num_threads", FLAGS_num_threads);
  }
  if (!FlagIsDefault("trust_region_radius")) {
    p.initial_trust_region_radius =
        FlagInRowRange("trust_region_radius", FLAGS_trust_region_radius);
  }
  if (!FlagIsDefault("lbfgs_rank")) p.lbfgs_rank = FlagInRowRange("lbfgs_rank", FLAGS_lbfgs_rank);
  ValidateOptimizerOptions(p);
  if (!FlagIsDefault("dt")) {
    o.time_step = FlagInRowRange("dt", FLAGS_dt);
  }
  if (!FlagIsDefault("steps")) {
    o.steps = FlagInRowRange("steps", FLAGS_steps);
  }
  if (!FlagIsDefault("t_end")) {
    if (!FlagIsDefault("steps")) {
      throw InputError("flag", "--t_end", "give --steps or --t_end, not both");
    }
    o.t_end = FlagInRowRange("t_end", FLAGS_t_end);
  }
  o.energy_tolerance = FlagInRowRange("energy_tolerance", FLAGS_energy_tolerance);
  AddContactFlagOverrides(&o.effect_overrides);
  return o;
}

SceneLoadOptions SceneLoadOptionsFromFlags(const EffectRegistry& registry) {
  SceneLoadOptions o;
  if (!FlagIsDefault("grid_size")) {
    o.grid_size = FlagInRowRange("grid_size", FLAGS_grid_size);
  }
  o.extra_effects = registry.UserNames();
  return o;
}

}  // namespace ipstep
