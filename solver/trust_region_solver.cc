#include "solver/trust_region_solver.h"

#include <limits>

#include "core/stopping_rule.h"
#include "solver/solve_status.h"

namespace ipstep {

TrustRegionSolver::TrustRegionSolver(IncrementalPotential* potential, const State* state,
                                     const OptimizerOptions& options)
    : potential_(potential),
      state_(state),
      options_(options),
      ceres_options_(MakeTrustRegionOptions(options)),
      positions_(Eigen::VectorXd::Zero(state->num_dofs())),
      gradient_(state->num_dofs()) {
  callback_ = std::make_unique<StoppingCallback>(
      options.tolerance,
      [this] {
        potential_->NotifyAccepted(positions_.data());
        return MeasureAt(positions_.data());
      },
      &sink_);
  ceres_options_.callbacks.push_back(callback_.get());
  BuildProblem();
}

void TrustRegionSolver::BuildProblem() {
  static const double kUnitWeight = 1.0;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  if (potential_->has_step_filters()) problem_options.evaluation_callback = &filter_callback_;
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  weighted_costs_.clear();
  weighted_losses_.clear();
  const int dim = state_->dimension;
  const StepContext& context = potential_->context();
  std::vector<double*> blocks;
  for (const Term& term : potential_->terms()) {
    const double* weight = term.kind == TermKind::kInertia     ? &context.inertia_weight
                           : term.kind == TermKind::kPotential ? &context.potential_weight
                                                               : &context.dissipation_weight;
    blocks.clear();
    for (int node : term.nodes) blocks.push_back(positions_.data() + dim * node);
    ceres::LossFunction* loss = nullptr;
    if (term.loss) {
      // rho_w = w rho: the weight goes into the loss, not the residual.
      weighted_losses_.push_back(std::make_unique<WeightedLoss>(term.loss.get(), weight));
      loss = weighted_losses_.back().get();
      weight = &kUnitWeight;
    }
    weighted_costs_.push_back(
        std::make_unique<WeightedCostFunction>(term.cost.get(), weight, &veto_));
    problem_->AddResidualBlock(weighted_costs_.back().get(), loss, blocks);
  }
  for (int i = 0; i < state_->num_nodes(); ++i) {
    double* block = positions_.data() + dim * i;
    if (!state_->is_free(i) && problem_->HasParameterBlock(block)) {
      problem_->SetParameterBlockConstant(block);
    }
  }
  built_version_ = potential_->structure_version();
}

void TrustRegionSolver::FilterCallback::PrepareForEvaluation(bool, bool new_evaluation_point) {
  if (new_evaluation_point) {
    solver_->veto_ = !solver_->potential_->IsStepValid(solver_->positions_.data());
  }
}

double TrustRegionSolver::MeasureAt(const double* x) {
  double energy = 0.0;
  if (!potential_->Evaluate(x, &energy, gradient_.data())) {
    return std::numeric_limits<double>::infinity();
  }
  return StoppingMeasure(gradient_, *state_, potential_->context());
}

StepSolveResult TrustRegionSolver::Solve(Eigen::VectorXd* x) {
  if (built_version_ != potential_->structure_version()) BuildProblem();
  positions_ = *x;  // same size: no reallocation
  potential_->NotifyAccepted(positions_.data());
  veto_ = false;
  StepSolveResult result;
  callback_->Reset();
  if (problem_->NumResidualBlocks() == 0) {
    result.residual = MeasureAt(positions_.data());
    result.converged = result.residual <= options_.tolerance;
    result.status = result.converged ? "converged" : "no energy terms";
    return result;
  }
  ceres::Solver::Summary summary;
  ceres::Solve(ceres_options_, problem_.get(), &summary);
  *x = positions_;
  result.iterations =
      summary.iterations.empty() ? 0 : static_cast<int>(summary.iterations.size()) - 1;
  result.evaluations = summary.num_residual_evaluations;
  result.ceres_report = summary.BriefReport();
  result.residual = MeasureAt(positions_.data());
  ClassifySolve(summary.termination_type, summary.message, result.iterations,
                ceres_options_.max_num_iterations, options_.tolerance, &result);
  return result;
}

}  // namespace ipstep
