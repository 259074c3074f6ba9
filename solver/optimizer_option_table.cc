#include "solver/optimizer_option_table.h"

#include "core/input_limits.h"

namespace ipstep {
namespace {

using Row = OptionRow<OptimizerOptions>;

Row Make(const char* name, const char* flag, OptionType type, OptionValue value, const char* doc) {
  return MakeOptionRow<OptimizerOptions>(name, std::string("OptimizerOptions.") + name, flag, type,
                                         std::move(value), doc);
}

// "" when `options.optimizer` is of `family` (projected_newton also takes the
// sparse Cholesky's options), else why not.
std::function<std::string(const OptimizerOptions&, const std::string&)> Family(
    OptimizerFamily family, bool sparse_cholesky = false) {
  return [family, sparse_cholesky](const OptimizerOptions& o,
                                   const std::string& prefix) -> std::string {
    const OptimizerFamily given = FamilyOf(o.optimizer);
    if (given == family || (sparse_cholesky && given == OptimizerFamily::kEigenNewton)) return "";
    const char* names = family == OptimizerFamily::kTrustRegion
                            ? (sparse_cholesky ? "newton, dogleg, gauss_newton and projected_newton"
                                               : "newton, dogleg and gauss_newton")
                        : family == OptimizerFamily::kLineSearch
                            ? "lbfgs, bfgs, ncg and gradient_descent"
                            : "projected_newton";
    return std::string("applies to ") + names + ", not to " + prefix +
           "optimizer=" + OptimizerName(o.optimizer);
  };
}

OptionTable<OptimizerOptions> Build() {
  OptionTable<OptimizerOptions> t;
  Row optimizer = Make("optimizer", "optimizer", OptionType::kString, std::string("newton"),
                       "newton | dogleg | gauss_newton | lbfgs | bfgs | ncg | gradient_descent | "
                       "projected_newton (not Ceres)");
  optimizer.field = "OptimizerOptions.optimizer";
  optimizer.set = [](const OptionValue& v, OptimizerOptions* o) {
    o->optimizer = ParseOptimizer(std::get<std::string>(v));
  };
  t.push_back(optimizer);
  Row tolerance =
      Make("tolerance", "tolerance", OptionType::kDouble, 1e-5,
           "Stopping rule: h * max_i |f_i| / m_i [m/s], f = force imbalance of the step, > 0");
  tolerance.unit = "m/s";
  BindField(&OptimizerOptions::tolerance, &tolerance);
  t.push_back(tolerance);
  Row max_iterations = WithRange(
      Make("max_iterations", "max_iterations", OptionType::kInt, 0LL,
           "Optimizer iteration limit per step"),
      1, limits::kMaxIterations, "",
      "the optimizer's: newton/dogleg/gauss_newton/projected_newton 100, lbfgs/bfgs 5000, "
      "ncg 20000, gradient_descent 50000");
  BindField(&OptimizerOptions::max_iterations, &max_iterations);
  t.push_back(max_iterations);
  Row time_limit = WithRange(
      Make("time_limit", "time_limit", OptionType::kDouble, 0.0, "Wall-time limit per step"), 0.0,
      limits::kMaxTimeLimit, "s", "no limit", /*min_open=*/true);
  BindField(&OptimizerOptions::time_limit, &time_limit);
  t.push_back(time_limit);
  Row threads = WithRange(
      Make("num_threads", "num_threads", OptionType::kInt, 0LL,
           "Threads for the terms' energies, gradients and Newton models (every optimizer; the "
           "same iterates for any count) and Ceres's own evaluation (gauss_newton)"),
      1, limits::kMaxThreads, "", "the machine's hardware threads");
  BindField(&OptimizerOptions::num_threads, &threads);
  t.push_back(threads);
  Row linear_solver =
      Make("linear_solver", "linear_solver", OptionType::kString, std::string(),
           "newton/dogleg/gauss_newton: Ceres linear solver (default SPARSE_NORMAL_CHOLESKY; "
           "e.g. CGNR); projected_newton: SPARSE_CHOLESKY (default) | CG (conjugate gradients "
           "with incomplete Cholesky, inexact Newton)");
  BindField(&OptimizerOptions::linear_solver, &linear_solver);
  linear_solver.applies = Family(OptimizerFamily::kTrustRegion, true);
  t.push_back(linear_solver);
  Row sparse =
      Make("sparse_library", "sparse_library", OptionType::kString, std::string(),
           "Sparse Cholesky library: newton/dogleg/gauss_newton: SUITE_SPARSE | CX_SPARSE | "
           "EIGEN_SPARSE; projected_newton: SUITE_SPARSE (CHOLMOD) | EIGEN_SPARSE "
           "(SimplicialLDLT); default SUITE_SPARSE");
  BindField(&OptimizerOptions::sparse_library, &sparse);
  sparse.applies = Family(OptimizerFamily::kTrustRegion, true);
  t.push_back(sparse);
  Row ordering =
      Make("linear_solver_ordering", "linear_solver_ordering", OptionType::kString, std::string(),
           "newton/dogleg/gauss_newton/projected_newton: fill-reducing ordering of the sparse "
           "Cholesky, AMD | NESDIS (nested dissection, METIS); default: NESDIS for 3D solids "
           "of 20000 free DOFs or more, AMD otherwise");
  BindField(&OptimizerOptions::linear_solver_ordering, &ordering);
  ordering.applies = Family(OptimizerFamily::kTrustRegion, true);
  t.push_back(ordering);
  Row radius =
      WithRange(Make("initial_trust_region_radius", "trust_region_radius", OptionType::kDouble, 0.0,
                     "newton/dogleg/gauss_newton: initial trust-region radius"),
                limits::kMinTrustRegionRadius, limits::kMaxTrustRegionRadius, "",
                "newton and gauss_newton 1e16, dogleg 1e4");
  BindField(&OptimizerOptions::initial_trust_region_radius, &radius);
  radius.applies = Family(OptimizerFamily::kTrustRegion);
  t.push_back(radius);
  Row backtrack =
      Make("backtrack_rejected_steps", "backtrack_rejected_steps", OptionType::kBool, true,
           "newton/dogleg/gauss_newton: when Ceres rejects a trial step (refused by contact, or "
           "the energy rose), backtrack along it and restart Ceres from there (false: Ceres "
           "only shrinks its trust region)");
  BindField(&OptimizerOptions::backtrack_rejected_steps, &backtrack);
  backtrack.applies = Family(OptimizerFamily::kTrustRegion);
  t.push_back(backtrack);
  Row line_search = Make("line_search", "line_search", OptionType::kString, std::string(),
                         "line-search optimizers: WOLFE | ARMIJO (default WOLFE)");
  BindField(&OptimizerOptions::line_search, &line_search);
  line_search.applies = Family(OptimizerFamily::kLineSearch);
  t.push_back(line_search);
  Row ncg = Make("nonlinear_cg", "nonlinear_cg", OptionType::kString, std::string(),
                 "ncg: FLETCHER_REEVES | POLAK_RIBIERE | HESTENES_STIEFEL (default "
                 "FLETCHER_REEVES)");
  BindField(&OptimizerOptions::nonlinear_cg, &ncg);
  ncg.applies = Family(OptimizerFamily::kLineSearch);
  t.push_back(ncg);
  Row rank = WithRange(
      Make("lbfgs_rank", "lbfgs_rank", OptionType::kInt, 0LL, "lbfgs: number of correction pairs"),
      1, limits::kMaxLbfgsRank, "", "the rank 20");
  BindField(&OptimizerOptions::lbfgs_rank, &rank);
  rank.applies = Family(OptimizerFamily::kLineSearch);
  t.push_back(rank);
  Row scaled = Make("mass_scaled_coordinates", "mass_scaled_coordinates", OptionType::kBool, true,
                    "line-search optimizers: work in z = sqrt(m) x / h (kinetic-energy metric)");
  BindField(&OptimizerOptions::mass_scaled_coordinates, &scaled);
  scaled.applies = Family(OptimizerFamily::kLineSearch);
  t.push_back(scaled);
  Row precise = Make("precise_line_search_energy", "precise_energy", OptionType::kBool, true,
                     "line-search optimizers: sum energies in extended precision (resolves smaller "
                     "force imbalances; costs one extra energy pass per evaluation)");
  BindField(&OptimizerOptions::precise_line_search_energy, &precise);
  t.push_back(precise);
  Row projection =
      Make("hessian_projection", "hessian_projection", OptionType::kString, std::string("default"),
           "newton/dogleg/projected_newton: how each iteration's model is made positive "
           "definite: default (projected_newton: when_indefinite; newton, dogleg: always) | "
           "always (every term's Hessian, negative eigenvalues clamped) | abs "
           "(every term's, negative eigenvalues by their magnitude) | trust_region (clamp or "
           "abs per iteration from the last step's model fit); projected_newton also: "
           "when_indefinite (the exact Hessian when the assembled sum is positive definite) | "
           "progressive (only terms at nodes whose force imbalance is above the tolerance); "
           "newton/dogleg also: inertia (the exact Hessian where the nodes' inertia carries "
           "the terms' negative curvature, clamped elsewhere)");
  projection.set = [](const OptionValue& v, OptimizerOptions* o) {
    o->hessian_projection = ParseHessianProjection(std::get<std::string>(v));
  };
  projection.applies = [](const OptimizerOptions& o, const std::string& prefix) -> std::string {
    if (UsesNewtonModel(o.optimizer)) return "";
    return "applies to newton, dogleg and projected_newton, not to " + prefix +
           "optimizer=" + OptimizerName(o.optimizer);
  };
  t.push_back(projection);
  return t;
}

}  // namespace

const OptionTable<OptimizerOptions>& OptimizerOptionTable() {
  static const OptionTable<OptimizerOptions> table = Build();
  return table;
}

}  // namespace ipstep
