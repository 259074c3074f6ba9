#include "apps/solver_flags.h"

#include <cmath>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "energies/effect_registry.h"

DEFINE_string(scene, "oscillator",
              "Built-in scene name (oscillator, spring_pendulum, cloth, fpu) or path to a JSON "
              "scene file");
DEFINE_string(integrator, "backward_euler",
              "backward_euler | newmark | quasi_static | symplectic_euler");
DEFINE_string(optimizer, "newton",
              "newton | dogleg | gauss_newton | lbfgs | bfgs | ncg | gradient_descent | "
              "projected_newton (Eigen, not Ceres)");
DEFINE_double(dt, 0.0, "Time step [s]; 0 uses the scene's time_step");
DEFINE_int32(steps, -1, "Number of steps; -1 uses the scene's steps");
DEFINE_double(tolerance, 1e-5,
              "Stopping rule: h * max_i |f_i| / m_i [m/s], f = force imbalance of the step");
DEFINE_int32(max_iterations, 0,
             "Optimizer iteration limit per step; 0: newton/dogleg/gauss_newton/projected_newton "
             "100, lbfgs/bfgs 5000, ncg 20000, gradient_descent 50000");
DEFINE_double(time_limit, 0.0, "Wall-time limit per step [s]; 0: none");
DEFINE_int32(num_threads, 1, "Ceres threads (newton, dogleg, gauss_newton)");
DEFINE_string(linear_solver, "",
              "newton/dogleg/gauss_newton: Ceres linear solver (default SPARSE_NORMAL_CHOLESKY)");
DEFINE_string(
    sparse_library, "",
    "newton/dogleg/gauss_newton: SUITE_SPARSE | CX_SPARSE | EIGEN_SPARSE (default CX_SPARSE)");
DEFINE_double(trust_region_radius, 0.0,
              "newton/dogleg/gauss_newton: initial trust-region radius; 0: newton and gauss_newton "
              "1e16, dogleg 1e4");
DEFINE_bool(backtrack_rejected_steps, true,
            "newton/dogleg/gauss_newton: when Ceres rejects a trial step (refused by contact, or "
            "the energy "
            "rose), backtrack along it and restart Ceres from there (false: Ceres only shrinks "
            "its trust region)");
DEFINE_string(line_search, "", "line-search optimizers: WOLFE | ARMIJO (default WOLFE)");
DEFINE_string(nonlinear_cg, "",
              "ncg: FLETCHER_REEVES | POLAK_RIBIERE | HESTENES_STIEFEL (default FLETCHER_REEVES)");
DEFINE_int32(lbfgs_rank, 0, "lbfgs: number of correction pairs; 0: 20");
DEFINE_bool(mass_scaled_coordinates, true,
            "line-search optimizers: work in z = sqrt(m) x / h (kinetic-energy metric)");
DEFINE_bool(precise_energy, true,
            "line-search optimizers: sum energies in extended precision (resolves smaller "
            "force imbalances; costs one extra energy pass per evaluation)");
DEFINE_double(newmark_beta, 0.25, "Newmark beta, in [1e-3, 1] (integrators/newmark.h)");
DEFINE_double(newmark_gamma, 0.5, "Newmark gamma, in [0.5, 1] (integrators/newmark.h)");
DEFINE_int32(grid_size, 0, "Override the node count per side of a scene's grid; 0: the scene's");

namespace ipstep {
namespace {

// A flag of one optimiser family is an error with an optimiser of another.
void RequireOptimizerFamily(const char* flag, OptimizerFamily family, Optimizer optimizer) {
  if (FlagIsDefault(flag) || FamilyOf(optimizer) == family) return;
  const char* names = family == OptimizerFamily::kTrustRegion
                          ? "newton, dogleg and gauss_newton"
                          : "lbfgs, bfgs, ncg and gradient_descent";
  throw InputError(
      "flag", std::string("--") + flag,
      std::string("applies to ") + names + ", not to --optimizer=" + OptimizerName(optimizer));
}

}  // namespace

SimulationOptions SimulationOptionsFromFlags() {
  SimulationOptions o;
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
  p.max_iterations = FLAGS_max_iterations;
  p.time_limit = FLAGS_time_limit;
  p.num_threads = FLAGS_num_threads;
  p.linear_solver = FLAGS_linear_solver;
  p.sparse_library = FLAGS_sparse_library;
  p.initial_trust_region_radius = FLAGS_trust_region_radius;
  p.backtrack_rejected_steps = FLAGS_backtrack_rejected_steps;
  p.line_search = FLAGS_line_search;
  p.nonlinear_cg = FLAGS_nonlinear_cg;
  p.lbfgs_rank = FLAGS_lbfgs_rank;
  p.mass_scaled_coordinates = FLAGS_mass_scaled_coordinates;
  p.precise_line_search_energy = FLAGS_precise_energy;
  for (const char* flag : {"linear_solver", "sparse_library", "trust_region_radius", "num_threads",
                           "backtrack_rejected_steps"}) {
    RequireOptimizerFamily(flag, OptimizerFamily::kTrustRegion, p.optimizer);
  }
  for (const char* flag :
       {"line_search", "nonlinear_cg", "lbfgs_rank", "mass_scaled_coordinates"}) {
    RequireOptimizerFamily(flag, OptimizerFamily::kLineSearch, p.optimizer);
  }
  ValidateOptimizerOptions(p);
  if (!std::isfinite(FLAGS_dt) || FLAGS_dt < 0.0) {
    throw InputError("flag", "--dt", "must be a finite number > 0 (0: the scene's time_step)");
  }
  if (FLAGS_steps < -1) throw InputError("flag", "--steps", "must be >= 0 (-1: the scene's steps)");
  o.time_step = FLAGS_dt;
  o.steps = FLAGS_steps;
  return o;
}

SceneLoadOptions SceneLoadOptionsFromFlags() {
  SceneLoadOptions o;
  if (FLAGS_grid_size < 0 || FLAGS_grid_size == 1) {
    throw InputError("flag", "--grid_size", "must be >= 2 (0: the scene's size)");
  }
  o.grid_size = FLAGS_grid_size;
  o.extra_effects = EffectRegistry::Global().UserNames();
  return o;
}

}  // namespace ipstep
