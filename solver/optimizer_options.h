// Optimiser names and the Ceres solver options each one sets. Every option can
// be overridden (the ipstep program exposes each as a gflag); the defaults are
// documented in docs/optimisers.md and were chosen by measurement
// (bench/; the tables in docs/benchmarks.md).
//
//   name              path                      Ceres options
//   newton            ceres::Problem, projected TRUST_REGION, LEVENBERG_MARQUARDT,
//                     Newton model per term     SPARSE_NORMAL_CHOLESKY, SUITE_SPARSE,
//                     (solver/newton_model_cost.h)  initial_trust_region_radius 1e16
//   dogleg            same model                TRUST_REGION, DOGLEG (TRADITIONAL),
//                                               SPARSE_NORMAL_CHOLESKY, SUITE_SPARSE
//   gauss_newton      ceres::Problem, the       as newton: Ceres's own J^T J model
//                     residual blocks as they are
//   lbfgs             ceres::GradientProblem    LINE_SEARCH, LBFGS rank 20, WOLFE,
//                                               approximate eigenvalue scaling on
//   bfgs              ceres::GradientProblem    LINE_SEARCH, BFGS, WOLFE, scaling on
//   ncg               ceres::GradientProblem    LINE_SEARCH, NONLINEAR_CONJUGATE_GRADIENT,
//                                               FLETCHER_REEVES, WOLFE
//   gradient_descent  ceres::GradientProblem    LINE_SEARCH, STEEPEST_DESCENT, WOLFE
//   projected_newton  not Ceres: CHOLMOD LL^T (solver/sparse_cholesky.h) and an
//                     Armijo line search (solver/projected_newton_solver.h), the
//                     same term models
#pragma once

#include <string>

#include <ceres/gradient_problem_solver.h>
#include <ceres/solver.h>

#include "solver/sparse_cholesky.h"

namespace ipstep {

enum class Optimizer {
  kNewton,
  kDogleg,
  kGaussNewton,
  kLbfgs,
  kBfgs,
  kNcg,
  kGradientDescent,
  kProjectedNewton,
};

// Which solver runs an optimiser: Ceres's trust region on a ceres::Problem,
// Ceres's line search on a ceres::GradientProblem, or ipstep's own projected
// Newton on Eigen.
enum class OptimizerFamily { kTrustRegion, kLineSearch, kEigenNewton };

const char* OptimizerName(Optimizer optimizer);
const char* OptimizerNames();  // comma-separated list for messages
// Throws InputError naming the option OptimizerOptions.optimizer.
Optimizer ParseOptimizer(const std::string& name);
OptimizerFamily FamilyOf(Optimizer optimizer);
bool IsTrustRegion(Optimizer optimizer);
// Optimisers that build the projected Newton model of every term (newton,
// dogleg, projected_newton): core/term_hessian.h.
bool UsesNewtonModel(Optimizer optimizer);

// How the Newton optimisers (newton, dogleg, projected_newton) make each
// iteration's model positive definite (core/term_hessian.h,
// solver/projected_newton_solver.h, solver/newton_model_cost.h):
//  * kAlways: every term's Hessian projected, negative eigenvalues clamped to
//    (almost) zero (Teran et al. 2005);
//  * kAbsolute: every term's Hessian projected, negative eigenvalues replaced
//    by their magnitude (Chen et al., SIGGRAPH 2024);
//  * kTrustRegion: per iteration, clamp or absolute from the fit of the last
//    step: absolute where the energy's actual decrease was below
//    kTrustRegionFilterSwitch of the model's prediction, clamp otherwise (the
//    idea of Chen et al., SIGGRAPH Asia 2024, "Trust-Region Eigenvalue
//    Filtering for Projected Newton");
//  * kWhenIndefinite (projected_newton only): the exact Hessian whenever the
//    assembled sum is positive definite, clamped otherwise (Longva et al.
//    2023, "Pitfalls of projection");
//  * kProgressive (projected_newton only): only the terms at a node whose
//    force imbalance is above the tolerance are projected (clamped), the set
//    growing over a step's iterations; every term when the sum is then not
//    positive definite (after Fernandez-Fernandez, Loeschner, Bender 2025,
//    "Progressively Projected Newton's Method").
//  * kInertia (newton and dogleg only): the exact Hessian wherever the nodes'
//    inertia can carry the terms' negative curvature, clamped elsewhere
//    (solver/inertia_absorption.h).
// kAlways, kAbsolute, kTrustRegion and kInertia give one positive
// semi-definite model per term, so Ceres's newton and dogleg can take them
// (Ceres's model must be a sum of squares); kWhenIndefinite and kProgressive
// need the assembled matrix; kInertia needs Ceres's residual blocks to carry
// the inertia too (projected_newton's when_indefinite does more).
// kDefault: the optimiser's own, chosen by measurement (docs/benchmarks.md,
// "Hessian projection"): projected_newton kWhenIndefinite, newton and dogleg
// kAlways (ResolveHessianProjection).
enum class HessianProjection {
  kDefault,
  kAlways,
  kAbsolute,
  kTrustRegion,
  kWhenIndefinite,
  kProgressive,
  kInertia
};

// The model fit (actual / predicted decrease of the last step) below which
// kTrustRegion filters with the absolute value.
constexpr double kTrustRegionFilterSwitch = 0.5;

// "default", "always", "abs", "trust_region", "when_indefinite", "progressive",
// "inertia".
const char* HessianProjectionName(HessianProjection projection);
const char* HessianProjectionNames();  // comma-separated, for messages
// Throws InputError naming the option OptimizerOptions.hessian_projection.
HessianProjection ParseHessianProjection(const std::string& name);
// True for the projections Ceres's newton and dogleg can use (always, abs,
// trust_region, inertia); projected_newton takes all but inertia.
bool IsPerTermProjection(HessianProjection projection);
struct OptimizerOptions;
// options.hessian_projection, kDefault resolved for options.optimizer.
HessianProjection ResolveHessianProjection(const OptimizerOptions& options);

struct OptimizerOptions {
  Optimizer optimizer = Optimizer::kNewton;

  // Stopping rule (core/stopping_rule.h): velocity error [m/s].
  double tolerance = 1e-5;

  // Overrides. Empty string / 0 / negative: the optimiser's default.
  int max_iterations = 0;   // default: newton, dogleg, gauss_newton, projected_newton 100;
                            // lbfgs, bfgs 5000; ncg 20000; gradient_descent 50000
  double time_limit = 0.0;  // seconds per step; default 1e9 (none)
  // Threads for the terms' energies, gradients and Newton models (every
  // optimiser; the same iterates for any count: core/thread_pool.h) and for
  // Ceres's own evaluation (gauss_newton). 0: the machine's hardware threads.
  int num_threads = 0;
  // newton, dogleg, gauss_newton: Ceres's linear solver (e.g.
  // SPARSE_NORMAL_CHOLESKY, the default; DENSE_QR, CGNR); projected_newton:
  // SPARSE_CHOLESKY (the default) or CG (preconditioned conjugate gradients,
  // inexact Newton: solver/conjugate_gradient.h).
  std::string linear_solver;
  // Sparse Cholesky library: SUITE_SPARSE (the default), CX_SPARSE or
  // EIGEN_SPARSE; projected_newton: SUITE_SPARSE (CHOLMOD supernodal) or
  // EIGEN_SPARSE (SimplicialLDLT), solver/sparse_cholesky.h.
  std::string sparse_library;
  // Fill-reducing ordering of the sparse Cholesky: AMD or NESDIS (nested
  // dissection); empty: chosen by the matrix's dimension and size
  // (ChooseOrdering, solver/sparse_cholesky.h). newton, dogleg,
  // gauss_newton: Ceres's linear_solver_ordering_type.
  std::string linear_solver_ordering;
  double initial_trust_region_radius = 0.0;
  // newton, dogleg: when Ceres rejects a trial step (a step filter refused it,
  // or the energy rose), backtrack along it as a line search would and
  // restart Ceres from there with a fresh trust region
  // (solver/trust_region_solver.h). false: Ceres only shrinks its radius.
  bool backtrack_rejected_steps = true;
  std::string line_search;   // WOLFE or ARMIJO
  std::string nonlinear_cg;  // FLETCHER_REEVES, POLAK_RIBIERE, HESTENES_STIEFEL
  int lbfgs_rank = 0;
  // Line-search optimisers work in mass-weighted coordinates z_i = sqrt(m_i) x_i / h
  // (the kinetic-energy metric; solver/first_order_potential.h) unless false.
  bool mass_scaled_coordinates = true;
  // Line-search optimisers compare energies summed in extended precision
  // (solver/first_order_potential.h) unless false.
  bool precise_line_search_energy = true;
  // newton, dogleg, projected_newton: how each iteration's model is made
  // positive definite (see HessianProjection).
  HessianProjection hessian_projection = HessianProjection::kDefault;
};

// The Ceres options for the trust-region optimisers (newton, dogleg), validated
// with Solver::Options::IsValid. Throws InputError naming the offending option
// ("options: OptimizerOptions.<field>: ...", docs/architecture.md "Using ipstep as a library").
ceres::Solver::Options MakeTrustRegionOptions(const OptimizerOptions& options);
// The same for the line-search optimisers.
ceres::GradientProblemSolver::Options MakeLineSearchOptions(const OptimizerOptions& options);
// projected_newton's library from options.sparse_library; throws InputError
// naming OptimizerOptions.sparse_library for a library it cannot use.
SparseLibrary ProjectedNewtonSparseLibrary(const OptimizerOptions& options);
// projected_newton's linear solver: true for CG; throws InputError naming
// OptimizerOptions.linear_solver for one it does not have.
bool ProjectedNewtonUsesCg(const OptimizerOptions& options);
// "" (automatic), "AMD" or "NESDIS"; throws InputError naming
// OptimizerOptions.linear_solver_ordering otherwise.
FillOrdering ParseFillOrdering(const std::string& name);
// options.num_threads, 0 resolved to the machine's hardware threads.
int ThreadCount(const OptimizerOptions& options);
// Validates the numeric fields (tolerance, limits): throws InputError naming the
// field.
void ValidateOptimizerOptions(const OptimizerOptions& options);

}  // namespace ipstep
