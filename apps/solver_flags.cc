#include "apps/solver_flags.h"

#include <cmath>
#include <stdexcept>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/default_effects.h"

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

// A flag of one optimiser family is an error with an optimiser of another.
void RequireOptimizerFamily(const char* flag, OptimizerFamily family, Optimizer optimizer) {
  if (FlagIsDefault(flag) || FamilyOf(optimizer) == family) return;
  if (FamilyOf(optimizer) == OptimizerFamily::kEigenNewton &&
      (std::string(flag) == "sparse_library" || std::string(flag) == "linear_solver_ordering" ||
       std::string(flag) == "linear_solver")) {
    return;  // the sparse Cholesky's flags apply to projected_newton too
  }
  const char* names = family == OptimizerFamily::kTrustRegion ? "newton, dogleg and gauss_newton"
                      : family == OptimizerFamily::kLineSearch
                          ? "lbfgs, bfgs, ncg and gradient_descent"
                          : "projected_newton";
  throw InputError(
      "flag", std::string("--") + flag,
      std::string("applies to ") + names + ", not to --optimizer=" + OptimizerName(optimizer));
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
  for (const char* flag : {"linear_solver", "sparse_library", "linear_solver_ordering",
                           "trust_region_radius", "backtrack_rejected_steps"}) {
    RequireOptimizerFamily(flag, OptimizerFamily::kTrustRegion, p.optimizer);
  }
  for (const char* flag :
       {"line_search", "nonlinear_cg", "lbfgs_rank", "mass_scaled_coordinates"}) {
    RequireOptimizerFamily(flag, OptimizerFamily::kLineSearch, p.optimizer);
  }
  if (!FlagIsDefault("hessian_projection") && !UsesNewtonModel(p.optimizer)) {
    throw InputError("flag", "--hessian_projection",
                     std::string("applies to newton, dogleg and projected_newton, not to "
                                 "--optimizer=") +
                         OptimizerName(p.optimizer));
  }
  // Flags whose unset value is a sentinel of the options (0 or -1: the
  // default) are used only when given, and then must be in range: an explicit
  // --dt=0 is an error, not the scene's time step.
  if (!FlagIsDefault("max_iterations")) {
    p.max_iterations =
        CheckFlagRange("max_iterations", FLAGS_max_iterations, 1, limits::kMaxIterations,
                       "the optimizer's default: newton/dogleg/gauss_newton/projected_newton "
                       "100, lbfgs/bfgs 5000, ncg 20000, gradient_descent 50000");
  }
  if (!FlagIsDefault("time_limit")) {
    p.time_limit = CheckFlagRange("time_limit", FLAGS_time_limit, 0.0, limits::kMaxTimeLimit, "s",
                                  "no limit", /*min_open=*/true);
  }
  if (!FlagIsDefault("num_threads")) {
    p.num_threads = CheckFlagRange("num_threads", FLAGS_num_threads, 1, limits::kMaxThreads,
                                   "the machine's hardware threads");
  }
  if (!FlagIsDefault("trust_region_radius")) {
    p.initial_trust_region_radius = CheckFlagRange(
        "trust_region_radius", FLAGS_trust_region_radius, limits::kMinTrustRegionRadius,
        limits::kMaxTrustRegionRadius, "", "newton and gauss_newton 1e16, dogleg 1e4");
  }
  if (!FlagIsDefault("lbfgs_rank")) {
    p.lbfgs_rank =
        CheckFlagRange("lbfgs_rank", FLAGS_lbfgs_rank, 1, limits::kMaxLbfgsRank, "the rank 20");
  }
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
