#include "apps/solver_flags.h"

#include <cmath>
#include <stdexcept>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/default_effects.h"
#include "solver/optimizer_option_table.h"

DEFINE_string(scene, "oscillator",
              "Built-in scene name (listed in --help) or path to a JSON scene file");
DEFINE_string(integrator, "backward_euler",
              "backward_euler | newmark | quasi_static | symplectic_euler");
DEFINE_string(optimizer, "newton",
              "newton | dogleg | gauss_newton | lbfgs | bfgs | ncg | gradient_descent | "
              "projected_newton (not Ceres)");
DEFINE_double(dt, 0.0, "Time step [s], in [1e-12, 1e3]; default: the scene's time_step");
DEFINE_int32(steps, -1, "Number of steps, in [0, 10000000]; default: the scene's steps");
DEFINE_double(t_end, 0.0,
              "End time [s], > 0: run t_end / dt steps (a whole number, or an error names a dt "
              "that fits); not with --steps; default: the scene's steps");
DEFINE_double(tolerance, 1e-5,
              "Stopping rule: h * max_i |f_i| / m_i [m/s], f = force imbalance of the step");
DEFINE_int32(max_iterations, 0,
             "Optimizer iteration limit per step, in [1, 1000000]; default: "
             "newton/dogleg/gauss_newton/projected_newton 100, lbfgs/bfgs 5000, ncg 20000, "
             "gradient_descent 50000");
DEFINE_double(time_limit, 0.0, "Wall-time limit per step [s], in (0, 1e9]; default: none");
DEFINE_int32(num_threads, 0,
             "Threads for the terms' energies, gradients and Newton models (every optimizer; "
             "the same iterates for any count) and Ceres's own evaluation (gauss_newton), in "
             "[1, 256]; default: the machine's hardware threads");
DEFINE_string(linear_solver, "",
              "newton/dogleg/gauss_newton: Ceres linear solver (default SPARSE_NORMAL_CHOLESKY; "
              "e.g. CGNR); projected_newton: SPARSE_CHOLESKY (default) | CG (conjugate gradients "
              "with incomplete Cholesky, inexact Newton)");
DEFINE_string(sparse_library, "",
              "Sparse Cholesky library: newton/dogleg/gauss_newton: SUITE_SPARSE | CX_SPARSE | "
              "EIGEN_SPARSE; projected_newton: SUITE_SPARSE (CHOLMOD) | EIGEN_SPARSE "
              "(SimplicialLDLT); default SUITE_SPARSE");
DEFINE_string(linear_solver_ordering, "",
              "newton/dogleg/gauss_newton/projected_newton: fill-reducing ordering of the sparse "
              "Cholesky, AMD | NESDIS (nested dissection, METIS); default: NESDIS for 3D solids "
              "of 20000 free DOFs or more, AMD otherwise");
DEFINE_double(trust_region_radius, 0.0,
              "newton/dogleg/gauss_newton: initial trust-region radius, in [1e-12, 1e20]; "
              "default: newton and gauss_newton 1e16, dogleg 1e4");
DEFINE_bool(backtrack_rejected_steps, true,
            "newton/dogleg/gauss_newton: when Ceres rejects a trial step (refused by contact, or "
            "the energy "
            "rose), backtrack along it and restart Ceres from there (false: Ceres only shrinks "
            "its trust region)");
DEFINE_string(line_search, "", "line-search optimizers: WOLFE | ARMIJO (default WOLFE)");
DEFINE_string(nonlinear_cg, "",
              "ncg: FLETCHER_REEVES | POLAK_RIBIERE | HESTENES_STIEFEL (default FLETCHER_REEVES)");
DEFINE_int32(lbfgs_rank, 0, "lbfgs: number of correction pairs, in [1, 1000]; default: 20");
DEFINE_bool(mass_scaled_coordinates, true,
            "line-search optimizers: work in z = sqrt(m) x / h (kinetic-energy metric)");
DEFINE_bool(precise_energy, true,
            "line-search optimizers: sum energies in extended precision (resolves smaller "
            "force imbalances; costs one extra energy pass per evaluation)");
DEFINE_string(hessian_projection, "default",
              "newton/dogleg/projected_newton: how each iteration's model is made positive "
              "definite: default (projected_newton: when_indefinite; newton, dogleg: always) | "
              "always (every term's Hessian, negative eigenvalues clamped) | abs "
              "(every term's, negative eigenvalues by their magnitude) | trust_region (clamp or "
              "abs per iteration from the last step's model fit); projected_newton also: "
              "when_indefinite (the exact Hessian when the assembled sum is positive definite) | "
              "progressive (only terms at nodes whose force imbalance is above the tolerance); "
              "newton/dogleg also: inertia (the exact Hessian where the nodes' inertia carries "
              "the terms' negative curvature, clamped elsewhere)");
DEFINE_double(newmark_beta, 0.25, "Newmark beta, in [1e-3, 1] (integrators/newmark.h)");
DEFINE_double(newmark_gamma, 0.5, "Newmark gamma, in [0.5, 1] (integrators/newmark.h)");
DEFINE_double(energy_tolerance, 0.1,
              "A step whose energy grows by more than this fraction of the energy in motion "
              "fails with status 'energy growth' (variational integrators), in [0, 100]; 0: no "
              "check");
DEFINE_int32(grid_size, 0,
             "Override the node count per side of a scene's grid, in [2, 1000]; default: the "
             "scene's");

namespace ipstep {
namespace {

// The row of OptimizerOptions' table named `name` (solver/optimizer_option_table.h).
const OptionRow<OptimizerOptions>& OptimizerRow(const char* name) {
  const OptionRow<OptimizerOptions>* row = FindOption(OptimizerOptionTable(), name);
  if (row == nullptr) throw std::logic_error(std::string("no option row ") + name);
  return *row;
}

// A given flag whose unset value is a sentinel of the options, checked
// against its row's range (and told what omitting it means).
double FlagInRange(const char* name, double value) {
  const OptionRow<OptimizerOptions>& row = OptimizerRow(name);
  return CheckFlagRange(row.flag.c_str(), value, row.min, row.max, row.unit, row.default_meaning,
                        row.min_open);
}
int FlagInRange(const char* name, int value) {
  const OptionRow<OptimizerOptions>& row = OptimizerRow(name);
  return CheckFlagRange(row.flag.c_str(), value, static_cast<int>(row.min),
                        static_cast<int>(row.max), row.default_meaning);
}

// A given flag that its row says does not apply to the optimiser is an error
// (the rows' order: the trust-region flags, the line-search flags, then
// --hessian_projection).
void RequireApplicableFlags(const OptimizerOptions& p) {
  for (const OptionRow<OptimizerOptions>& row : OptimizerOptionTable()) {
    if (!row.applies || row.flag.empty() || FlagIsDefault(row.flag.c_str())) continue;
    std::string why = row.applies(p);
    if (why.empty()) continue;
    const size_t at = why.rfind("optimizer=");
    if (at != std::string::npos) why.insert(at, "--");
    throw InputError("flag", "--" + row.flag, why);
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
    p.max_iterations = FlagInRange("max_iterations", FLAGS_max_iterations);
  }
  if (!FlagIsDefault("time_limit")) p.time_limit = FlagInRange("time_limit", FLAGS_time_limit);
  if (!FlagIsDefault("num_threads")) p.num_threads = FlagInRange("num_threads", FLAGS_num_threads);
  if (!FlagIsDefault("trust_region_radius")) {
    p.initial_trust_region_radius =
        FlagInRange("initial_trust_region_radius", FLAGS_trust_region_radius);
  }
  if (!FlagIsDefault("lbfgs_rank")) p.lbfgs_rank = FlagInRange("lbfgs_rank", FLAGS_lbfgs_rank);
  ValidateOptimizerOptions(p);
  if (!FlagIsDefault("dt")) {
    o.time_step = CheckFlagRange("dt", FLAGS_dt, limits::kMinTimeStep, limits::kMaxTimeStep, "s",
                                 "the scene's time_step");
  }
  if (!FlagIsDefault("steps")) {
    o.steps = CheckFlagRange("steps", FLAGS_steps, 0, limits::kMaxSteps, "the scene's steps");
  }
  if (!FlagIsDefault("t_end")) {
    if (!FlagIsDefault("steps")) {
      throw InputError("flag", "--t_end", "give --steps or --t_end, not both");
    }
    o.t_end = CheckFlagRange("t_end", FLAGS_t_end, 0.0, limits::kMaxSteps * limits::kMaxTimeStep,
                             "s", "the scene's steps", /*min_open=*/true);
  }
  o.energy_tolerance = CheckFlagRange("energy_tolerance", FLAGS_energy_tolerance, 0.0, 100.0, "",
                                      "the tolerance 0.1; 0 is no check");
  AddContactFlagOverrides(&o.effect_overrides);
  return o;
}

SceneLoadOptions SceneLoadOptionsFromFlags(const EffectRegistry& registry) {
  SceneLoadOptions o;
  if (!FlagIsDefault("grid_size")) {
    o.grid_size =
        CheckFlagRange("grid_size", FLAGS_grid_size, 2, limits::kMaxGridSize, "the scene's size");
  }
  o.extra_effects = registry.UserNames();
  return o;
}

}  // namespace ipstep
