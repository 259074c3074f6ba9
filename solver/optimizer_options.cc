#include "solver/optimizer_options.h"

#include <algorithm>
#include <cmath>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/thread_pool.h"
#include "solver/optimizer_option_table.h"

namespace ipstep {
namespace {

constexpr struct {
  Optimizer optimizer;
  const char* name;
} kNames[] = {
    {Optimizer::kNewton, "newton"},
    {Optimizer::kDogleg, "dogleg"},
    {Optimizer::kGaussNewton, "gauss_newton"},
    {Optimizer::kLbfgs, "lbfgs"},
    {Optimizer::kBfgs, "bfgs"},
    {Optimizer::kNcg, "ncg"},
    {Optimizer::kGradientDescent, "gradient_descent"},
    {Optimizer::kProjectedNewton, "projected_newton"},
};

int DefaultMaxIterations(Optimizer o) {
  switch (o) {
    case Optimizer::kNewton:
    case Optimizer::kDogleg:
    case Optimizer::kGaussNewton:
    case Optimizer::kProjectedNewton:
      return 100;
    case Optimizer::kLbfgs:
    case Optimizer::kBfgs:
      return 5000;
    case Optimizer::kNcg:
      return 20000;
    case Optimizer::kGradientDescent:
      return 50000;
  }
  return 100;
}

// Ceres's own convergence tests are off or at round-off: only genuine stalls
// (a step of relative size 1e-16) end a solve early; convergence is decided by
// the stopping rule (callback). Ceres's function tolerance in particular would
// stop Newton early: the cost decrease is quadratic in the gradient.
template <class CeresOptions>
void SetCommonOptions(const OptimizerOptions& o, CeresOptions* c) {
  c->max_num_iterations =
      o.max_iterations > 0 ? o.max_iterations : DefaultMaxIterations(o.optimizer);
  c->max_solver_time_in_seconds = o.time_limit > 0.0 ? o.time_limit : 1e9;
  c->function_tolerance = 0.0;
  c->gradient_tolerance = 0.0;
  c->parameter_tolerance = 1e-16;
  c->logging_type = ceres::SILENT;
  c->minimizer_progress_to_stdout = false;
  c->update_state_every_iteration = true;
}

template <class CeresOptions>
void SetLineSearchOptions(const OptimizerOptions& o, CeresOptions* c) {
  c->line_search_type = ceres::WOLFE;
  c->use_approximate_eigenvalue_bfgs_scaling = true;
  switch (o.optimizer) {
    case Optimizer::kLbfgs:
      c->line_search_direction_type = ceres::LBFGS;
      break;
    case Optimizer::kBfgs:
      c->line_search_direction_type = ceres::BFGS;
      break;
    case Optimizer::kNcg:
      c->line_search_direction_type = ceres::NONLINEAR_CONJUGATE_GRADIENT;
      // Measured: Polak-Ribiere stalled on cloth steps that Fletcher-Reeves finished.
      c->nonlinear_conjugate_gradient_type = ceres::FLETCHER_REEVES;
      break;
    default:
      c->line_search_direction_type = ceres::STEEPEST_DESCENT;
      break;
  }
  if (!o.line_search.empty() &&
      !ceres::StringToLineSearchType(o.line_search, &c->line_search_type)) {
    throw InputError("options", "OptimizerOptions.line_search",
                     "unknown line search '" + o.line_search + "' (WOLFE or ARMIJO)");
  }
  if (!o.nonlinear_cg.empty() && !ceres::StringToNonlinearConjugateGradientType(
                                     o.nonlinear_cg, &c->nonlinear_conjugate_gradient_type)) {
    throw InputError("options", "OptimizerOptions.nonlinear_cg",
                     "unknown type '" + o.nonlinear_cg +
                         "' (FLETCHER_REEVES, POLAK_RIBIERE or HESTENES_STIEFEL)");
  }
  if (o.lbfgs_rank > 0) c->max_lbfgs_rank = o.lbfgs_rank;
}

}  // namespace

const char* OptimizerName(Optimizer optimizer) {
  for (const auto& entry : kNames) {
    if (entry.optimizer == optimizer) return entry.name;
  }
  return "unknown";
}

const char* OptimizerNames() {
  return "newton, dogleg, gauss_newton, lbfgs, bfgs, ncg, gradient_descent, projected_newton";
}

Optimizer ParseOptimizer(const std::string& name) {
  for (const auto& entry : kNames) {
    if (name == entry.name) return entry.optimizer;
  }
  throw InputError("options", "OptimizerOptions.optimizer",
                   "unknown optimizer '" + name + "' (choose one of " + OptimizerNames() + ")");
}

constexpr struct {
  HessianProjection projection;
  const char* name;
} kProjections[] = {
    {HessianProjection::kDefault, "default"},
    {HessianProjection::kAlways, "always"},
    {HessianProjection::kAbsolute, "abs"},
    {HessianProjection::kTrustRegion, "trust_region"},
    {HessianProjection::kWhenIndefinite, "when_indefinite"},
    {HessianProjection::kProgressive, "progressive"},
    {HessianProjection::kInertia, "inertia"},
};

const char* HessianProjectionName(HessianProjection projection) {
  for (const auto& entry : kProjections) {
    if (entry.projection == projection) return entry.name;
  }
  return "always";
}

const char* HessianProjectionNames() {
  return "default, always, abs, trust_region, when_indefinite, progressive, inertia";
}

HessianProjection ParseHessianProjection(const std::string& name) {
  for (const auto& entry : kProjections) {
    if (name == entry.name) return entry.projection;
  }
  throw InputError(
      "options", "OptimizerOptions.hessian_projection",
      "unknown projection '" + ClipInput(name) + "' (" + HessianProjectionNames() + ")");
}

HessianProjection ResolveHessianProjection(const OptimizerOptions& o) {
  if (o.hessian_projection != HessianProjection::kDefault) return o.hessian_projection;
  // Measured over the built-in scenes, grids 40 and 80, the self-contact
  // twist and the hard-case suite (docs/benchmarks.md, "Hessian
  // projection"): when_indefinite never took more iterations or failed more
  // steps than the other four (hanging_square grid 80: 11.3 iterations per
  // step against 109 with always); for Ceres's per-term models always and
  // trust_region tied and abs took more iterations everywhere.
  return o.optimizer == Optimizer::kProjectedNewton ? HessianProjection::kWhenIndefinite
                                                    : HessianProjection::kAlways;
}

bool IsPerTermProjection(HessianProjection projection) {
  return projection == HessianProjection::kAlways || projection == HessianProjection::kAbsolute ||
         projection == HessianProjection::kTrustRegion || projection == HessianProjection::kInertia;
}

OptimizerFamily FamilyOf(Optimizer optimizer) {
  switch (optimizer) {
    case Optimizer::kNewton:
    case Optimizer::kDogleg:
    case Optimizer::kGaussNewton:
      return OptimizerFamily::kTrustRegion;
    case Optimizer::kProjectedNewton:
      return OptimizerFamily::kEigenNewton;
    default:
      return OptimizerFamily::kLineSearch;
  }
}

bool IsTrustRegion(Optimizer optimizer) {
  return FamilyOf(optimizer) == OptimizerFamily::kTrustRegion;
}

bool UsesNewtonModel(Optimizer optimizer) {
  return optimizer == Optimizer::kNewton || optimizer == Optimizer::kDogleg ||
         optimizer == Optimizer::kProjectedNewton;
}

int ThreadCount(const OptimizerOptions& o) {
  return o.num_threads > 0 ? std::min(o.num_threads, limits::kMaxThreads) : DefaultThreadCount();
}

SparseLibrary ProjectedNewtonSparseLibrary(const OptimizerOptions& o) {
  if (o.sparse_library.empty() || o.sparse_library == "SUITE_SPARSE") {
    return SparseLibrary::kSuiteSparse;
  }
  if (o.sparse_library == "EIGEN_SPARSE") return SparseLibrary::kEigen;
  throw InputError("options", "OptimizerOptions.sparse_library",
                   "projected_newton uses SUITE_SPARSE (CHOLMOD) or EIGEN_SPARSE, not '" +
                       o.sparse_library + "'");
}

bool ProjectedNewtonUsesCg(const OptimizerOptions& o) {
  if (o.linear_solver.empty() || o.linear_solver == "SPARSE_CHOLESKY") return false;
  if (o.linear_solver == "CG") return true;
  throw InputError(
      "options", "OptimizerOptions.linear_solver",
      "projected_newton uses SPARSE_CHOLESKY or CG, not '" + ClipInput(o.linear_solver) + "'");
}

FillOrdering ParseFillOrdering(const std::string& name) {
  if (name.empty()) return FillOrdering::kAutomatic;
  if (name == "AMD") return FillOrdering::kAmd;
  if (name == "NESDIS") return FillOrdering::kNestedDissection;
  throw InputError("options", "OptimizerOptions.linear_solver_ordering",
                   "unknown ordering '" + name + "' (AMD or NESDIS)");
}

// The ranges of max_iterations, time_limit, num_threads,
// initial_trust_region_radius and lbfgs_rank, and what their 0 stands for,
// are their rows' in the option table (solver/optimizer_option_table.cc); the
// programs reject an explicit 0 at the flags layer (apps/solver_flags.cc).
void ValidateOptimizerOptions(const OptimizerOptions& o) {
  if (!std::isfinite(o.tolerance) || o.tolerance <= 0.0) {
    throw InputError("options", "OptimizerOptions.tolerance",
                     "must be a finite number > 0, got " + std::to_string(o.tolerance));
  }
  CheckOptionRanges(OptimizerOptionTable(), o);
  ParseFillOrdering(o.linear_solver_ordering);
  if (o.optimizer == Optimizer::kProjectedNewton) {
    if (ResolveHessianProjection(o) == HessianProjection::kInertia) {
      throw InputError("options", "OptimizerOptions.hessian_projection",
                       "inertia is for newton and dogleg (projected_newton's when_indefinite takes "
                       "the exact Hessian wherever the assembled sum is positive definite)");
    }
    ProjectedNewtonSparseLibrary(o);
    if (ProjectedNewtonUsesCg(o) && !IsPerTermProjection(ResolveHessianProjection(o))) {
      throw InputError("options", "OptimizerOptions.hessian_projection",
                       std::string(HessianProjectionName(ResolveHessianProjection(o))) +
                           " needs a definiteness test, which CG does not give: with "
                           "linear_solver CG use always, abs or trust_region");
    }
  }
  if (!IsPerTermProjection(ResolveHessianProjection(o)) && IsTrustRegion(o.optimizer)) {
    throw InputError("options", "OptimizerOptions.hessian_projection",
                     std::string(HessianProjectionName(ResolveHessianProjection(o))) +
                         " needs the assembled Hessian: projected_newton only (" +
                         OptimizerName(o.optimizer) +
                         " takes always, abs, trust_region or inertia)");
  }
}

ceres::Solver::Options MakeTrustRegionOptions(const OptimizerOptions& o) {
  ValidateOptimizerOptions(o);
  if (!IsTrustRegion(o.optimizer)) {
    throw InputError("options", "OptimizerOptions.optimizer",
                     std::string(OptimizerName(o.optimizer)) + " is not a trust-region optimizer");
  }
  ceres::Solver::Options c;
  SetCommonOptions(o, &c);
  c.minimizer_type = ceres::TRUST_REGION;
  c.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // SUITE_SPARSE (CHOLMOD): measured against CX_SPARSE with newton, 20
  // steps: equal on the small scenes (cloth 6.4 against 6.5 ms/step,
  // cantilever_2d 3.0 against 2.8), faster from about 10^4 unknowns (cloth
  // grid 40: 30 against 36, hanging_square grid 81: 615 against 1,099).
  c.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  c.num_threads = ThreadCount(o);
  if (o.optimizer != Optimizer::kDogleg) {
    c.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    c.initial_trust_region_radius = 1e16;  // full model steps, damped only after a rejection
  } else {
    c.trust_region_strategy_type = ceres::DOGLEG;
    c.dogleg_type = ceres::TRADITIONAL_DOGLEG;
  }
  if (o.initial_trust_region_radius > 0.0) {
    c.initial_trust_region_radius = o.initial_trust_region_radius;
    c.max_trust_region_radius = std::max(c.max_trust_region_radius, o.initial_trust_region_radius);
  }
  if (!o.linear_solver.empty() &&
      !ceres::StringToLinearSolverType(o.linear_solver, &c.linear_solver_type)) {
    throw InputError("options", "OptimizerOptions.linear_solver",
                     "unknown linear solver '" + o.linear_solver +
                         "' (e.g. SPARSE_NORMAL_CHOLESKY, DENSE_QR, DENSE_NORMAL_CHOLESKY, CGNR)");
  }
  if (!o.sparse_library.empty() && !ceres::StringToSparseLinearAlgebraLibraryType(
                                       o.sparse_library, &c.sparse_linear_algebra_library_type)) {
    throw InputError("options", "OptimizerOptions.sparse_library",
                     "unknown sparse library '" + o.sparse_library +
                         "' (SUITE_SPARSE, CX_SPARSE or EIGEN_SPARSE)");
  }
  std::string error;
  if (!c.IsValid(&error)) {
    throw InputError("options",
                     "OptimizerOptions.optimizer=" + std::string(OptimizerName(o.optimizer)),
                     "invalid Ceres options: " + error);
  }
  return c;
}

ceres::GradientProblemSolver::Options MakeLineSearchOptions(const OptimizerOptions& o) {
  ValidateOptimizerOptions(o);
  if (FamilyOf(o.optimizer) != OptimizerFamily::kLineSearch) {
    throw InputError("options", "OptimizerOptions.optimizer",
                     std::string(OptimizerName(o.optimizer)) + " is not a line-search optimizer");
  }
  ceres::GradientProblemSolver::Options c;
  SetCommonOptions(o, &c);
  SetLineSearchOptions(o, &c);
  std::string error;
  if (!c.IsValid(&error)) {
    throw InputError(
        "options", "OptimizerOptions.line_search",
        "invalid Ceres options for " + std::string(OptimizerName(o.optimizer)) + ": " + error);
  }
  return c;
}

}  // namespace ipstep
