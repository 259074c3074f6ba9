#include "solver/line_search_solver.h"

#include <limits>

#include "core/input_error.h"
#include "core/stopping_rule.h"
#include "solver/solve_status.h"

namespace ipstep {

// BFGS keeps a dense n x n inverse Hessian approximation.
constexpr int kMaxBfgsParameters = 20000;

LineSearchSolver::LineSearchSolver(IncrementalPotential* potential, const State* state,
                                   const OptimizerOptions& options)
    : potential_(potential),
      state_(state),
      options_(options),
      ceres_options_(MakeLineSearchOptions(options)),
      function_(new FirstOrderPotential(potential, state, options.mass_scaled_coordinates)),
      problem_(std::make_unique<ceres::GradientProblem>(function_)),
      parameters_(function_->NumParameters()),
      gradient_(state->num_dofs()) {
  if (options.optimizer == Optimizer::kBfgs && function_->NumParameters() > kMaxBfgsParameters) {
    throw InputError("flag", "--optimizer=bfgs",
                     "BFGS stores a dense matrix of " + std::to_string(function_->NumParameters()) +
                         "^2 doubles; use lbfgs above " + std::to_string(kMaxBfgsParameters) +
                         " free degrees of freedom");
  }
  callback_ = std::make_unique<StoppingCallback>(
      options.tolerance, [this] { return MeasureAt(parameters_.data()); }, &sink_,
      function_->energy_scale());
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
  function_->SetFullPositions(*x);
  function_->ToParameters(*x, parameters_.data());
  callback_->Reset();
  if (parameters_.empty()) {
    result.converged = true;
    result.status = "converged";
    return result;
  }
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(ceres_options_, *problem_, parameters_.data(), &summary);
  *x = function_->FromParameters(parameters_.data());
  result.iterations =
      summary.iterations.empty() ? 0 : static_cast<int>(summary.iterations.size()) - 1;
  result.evaluations = summary.num_gradient_evaluations;
  result.ceres_report = summary.BriefReport();
  result.residual = MeasureAt(parameters_.data());
  ClassifySolve(summary.termination_type, summary.message, result.iterations,
                ceres_options_.max_num_iterations, options_.tolerance, &result);
  return result;
}

}  // namespace ipstep
