#include "solver/line_search_solver.h"

#include <limits>

#include "core/input_error.h"
#include "core/stopping_rule.h"
#include "solver/solve_status.h"

namespace ipstep {

// Restarts of a stalled line search (see Solve).
constexpr int kMaxRestarts = 10;

// BFGS keeps a dense n x n inverse Hessian approximation and updates all of
// it every iteration: O(n^2) per iteration, with more iterations as n grows.
// Measured on cloth (ipstep --scene=cloth --optimizer=bfgs --steps=2
// --grid_size=30 / 50): 11 s per step at 1,796 free DOFs, 239 s at 4,996
// (docs/optimisers.md), so it is refused above 3,000.
constexpr int kMaxBfgsParameters = 3000;
// The memory L-BFGS may allocate up front (2 x rank vectors), in doubles:
// 20000^2 (3.2 GB).
constexpr double kMaxLbfgsDoubles = 20000.0 * 20000.0;

LineSearchSolver::LineSearchSolver(IncrementalPotential* potential, const State* state,
                                   const OptimizerOptions& options)
    : potential_(potential),
      state_(state),
      options_(options),
      ceres_options_(MakeLineSearchOptions(options)),
      function_(new FirstOrderPotential(potential, state, options.mass_scaled_coordinates,
                                        options.precise_line_search_energy)),
      problem_(std::make_unique<ceres::GradientProblem>(function_)),
      parameters_(function_->NumParameters()),
      gradient_(state->num_dofs()) {
  potential_->SetNumThreads(ThreadCount(options));
  if (options.optimizer == Optimizer::kBfgs && function_->NumParameters() > kMaxBfgsParameters) {
    throw InputError("options", "OptimizerOptions.optimizer=bfgs",
                     "BFGS stores a dense matrix of " + std::to_string(function_->NumParameters()) +
                         "^2 doubles and updates all of it every iteration; use lbfgs above " +
                         std::to_string(kMaxBfgsParameters) + " free degrees of freedom");
  }
  // L-BFGS allocates 2 x rank vectors of the parameters up front.
  const double lbfgs_doubles = 2.0 * ceres_options_.max_lbfgs_rank * function_->NumParameters();
  if (options.optimizer == Optimizer::kLbfgs && lbfgs_doubles > kMaxLbfgsDoubles) {
    throw InputError("options", "OptimizerOptions.lbfgs_rank",
                     "rank " + std::to_string(ceres_options_.max_lbfgs_rank) + " stores " +
                         std::to_string(2 * ceres_options_.max_lbfgs_rank) + " vectors of " +
                         std::to_string(function_->NumParameters()) +
                         " free degrees of freedom, more than the limit of 20000^2 doubles; "
                         "use a smaller rank");
  }
  callback_ = std::make_unique<StoppingCallback>(
      options.tolerance,
      [this] {
        potential_->NotifyAccepted(function_->FromParameters(parameters_.data()).data());
        return MeasureAt(parameters_.data());
      },
      &sink_, function_->energy_scale());
  ceres_options_.callbacks.push_back(callback_.get());
}

double LineSearchSolver::MeasureAt(const double* parameters) {
  if (!function_->FullGradient(parameters, &gradient_)) {
    return std::numeric_limits<double>::infinity();
  }
  return StoppingMeasure(gradient_, *state_, potential_->context());
}

StepSolveResult LineSearchSolver::Solve(Eigen::VectorXd* x) {
  StepSolveResult result;
  potential_->NotifyAccepted(x->data());
  if (!function_->SetFullPositions(*x)) {
    result.status = "energy cannot be evaluated at the initial guess";
    result.residual = std::numeric_limits<double>::infinity();
    return result;
  }
  if (parameters_.empty()) {
    result.converged = true;
    result.status = "converged";
    return result;
  }
  function_->ToParameters(*x, parameters_.data());
  callback_->Reset();
  // Ceres compares energies in double: once the decrease per iteration falls
  // below round-off of the energy drop since the start, the line search stalls
  // (reported as CONVERGENCE). A restart from the last iterate re-references
  // the energy there, which restores the resolution (docs/optimisers.md "Precision floor").
  const int max_iterations = ceres_options_.max_num_iterations;
  ceres::GradientProblemSolver::Options options = ceres_options_;
  ceres::GradientProblemSolver::Summary summary;
  double previous_residual = std::numeric_limits<double>::infinity();
  for (int restart = 0;; ++restart) {
    options.max_num_iterations = max_iterations - result.iterations;
    ceres::Solve(options, *problem_, parameters_.data(), &summary);
    result.iterations +=
        summary.iterations.empty() ? 0 : static_cast<int>(summary.iterations.size()) - 1;
    result.evaluations += summary.num_gradient_evaluations;
    result.residual = MeasureAt(parameters_.data());
    const bool stalled = summary.termination_type == ceres::CONVERGENCE;
    if (result.residual <= options_.tolerance || !stalled || restart == kMaxRestarts ||
        result.residual >= previous_residual || result.iterations >= max_iterations) {
      break;
    }
    previous_residual = result.residual;
    if (!function_->SetFullPositions(function_->FromParameters(parameters_.data()))) break;
  }
  *x = function_->FromParameters(parameters_.data());
  result.ceres_report = summary.BriefReport();
  ClassifySolve(summary.termination_type, summary.message, result.iterations, max_iterations,
                options_.tolerance, &result);
  return result;
}

}  // namespace ipstep
