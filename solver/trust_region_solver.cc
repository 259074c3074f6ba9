#include "solver/trust_region_solver.h"

#include <algorithm>
#include <limits>

#include <glog/logging.h>

#include "core/stopping_rule.h"
#include "solver/newton_model_cache.h"
#include "solver/newton_model_cost.h"
#include "solver/node_ordering.h"
#include "solver/serial_openmp.h"
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
  potential_->SetNumThreads(ThreadCount(options));
  if (UsesNewtonModel(options.optimizer)) {
    // The models are computed on the potential's threads (the cache); Ceres
    // evaluates on one, summing costs in block order (deterministic).
    ceres_options_.num_threads = 1;
  }
  const HessianProjection projection = ResolveHessianProjection(options);
  filter_ = projection == HessianProjection::kAbsolute ? EigenvalueFilter::kAbsolute
                                                       : EigenvalueFilter::kClamp;
  if (projection == HessianProjection::kTrustRegion) {
    ceres_options_.callbacks.push_back(&fit_callback_);
  }
  callback_ = std::make_unique<StoppingCallback>(
      options.tolerance,
      [this] {
        potential_->NotifyAccepted(positions_.data());
        return MeasureAt(positions_.data());
      },
      &sink_);
  ceres_options_.callbacks.push_back(callback_.get());
  if (options.backtrack_rejected_steps) {
    ceres_options_.callbacks.push_back(&backtrack_callback_);
  }
  BuildProblem();
}

void TrustRegionSolver::BuildProblem() {
  static const double kUnitWeight = 1.0;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  if (potential_->has_step_filters() || options_.backtrack_rejected_steps ||
      UsesNewtonModel(options_.optimizer)) {
    problem_options.evaluation_callback = &filter_callback_;
  }
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  weighted_costs_.clear();
  weighted_losses_.clear();
  const int dim = state_->dimension;
  const StepContext& context = potential_->context();
  const bool newton_model = UsesNewtonModel(options_.optimizer);
  auto weight_of = [&context](const Term& term) {
    return term.kind == TermKind::kInertia     ? &context.inertia_weight
           : term.kind == TermKind::kPotential ? &context.potential_weight
                                               : &context.dissipation_weight;
  };
  // The terms whose Newton models the cache computes (in parallel, before
  // Ceres evaluates: solver/newton_model_cache.h).
  // With the inertia projection (solver/inertia_absorption.h) the inertia
  // terms' models change too: they are cached as well.
  const bool absorb = ResolveHessianProjection(options_) == HessianProjection::kInertia;
  auto cached_term = [&](const Term& term) {
    return newton_model &&
           (!term.gauss_newton_model || (absorb && term.kind == TermKind::kInertia));
  };
  cache_.reset();
  if (newton_model) {
    std::vector<int> cached;
    std::vector<const double*> weights;
    for (size_t t = 0; t < potential_->terms().size(); ++t) {
      const Term& term = potential_->terms()[t];
      if (!cached_term(term)) continue;
      cached.push_back(static_cast<int>(t));
      weights.push_back(weight_of(term));
    }
    cache_ = std::make_unique<NewtonModelCache>(potential_, std::move(cached), std::move(weights),
                                                absorb, state_);
  }
  int cache_index = 0;
  std::vector<double*> blocks;
  for (const Term& term : potential_->terms()) {
    const double* weight = weight_of(term);
    blocks.clear();
    for (int node : term.nodes) blocks.push_back(positions_.data() + dim * node);
    if (cached_term(term)) {
      // The projected Newton model (solver/newton_model_cost.h).
      auto cost = std::make_unique<NewtonModelCost>(&term, dim, weight, &veto_, &filter_,
                                                    cache_.get(), cache_index++);
      weighted_losses_.push_back(std::make_unique<NewtonModelLoss>(cost.get()));
      problem_->AddResidualBlock(cost.get(), weighted_losses_.back().get(), blocks);
      weighted_costs_.push_back(std::move(cost));
      continue;
    }
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
  ChooseOrdering();
  built_version_ = potential_->structure_version();
}

std::string TrustRegionSolver::LinearSolverDescription() const {
  std::string text =
      std::string("Ceres ") + ceres::LinearSolverTypeToString(ceres_options_.linear_solver_type);
  if (ceres_options_.linear_solver_type == ceres::SPARSE_NORMAL_CHOLESKY ||
      ceres_options_.linear_solver_type == ceres::SPARSE_SCHUR) {
    text += std::string(" with ") + ceres::SparseLinearAlgebraLibraryTypeToString(
                                        ceres_options_.sparse_linear_algebra_library_type);
    if (ceres_options_.sparse_linear_algebra_library_type == ceres::SUITE_SPARSE) {
      text += node_order_.empty() ? ", AMD ordering" : ", nested dissection (METIS) of the nodes";
    }
  }
  return text;
}

void TrustRegionSolver::ChooseOrdering() {
  node_order_.clear();
  if (ceres_options_.linear_solver_type != ceres::SPARSE_NORMAL_CHOLESKY ||
      ceres_options_.sparse_linear_algebra_library_type != ceres::SUITE_SPARSE) {
    return;
  }
  FillOrdering ordering = ParseFillOrdering(options_.linear_solver_ordering);
  if (ordering == FillOrdering::kAutomatic) {
    int free_dofs = 0;
    for (int i = 0; i < state_->num_nodes(); ++i) free_dofs += state_->is_free(i);
    ordering = ::ipstep::ChooseOrdering(state_->dimension, free_dofs * state_->dimension);
  }
  if (ordering == FillOrdering::kNestedDissection) {
    node_order_ = NestedDissectionNodeOrder(*potential_, *state_);
  }
}

std::shared_ptr<ceres::ParameterBlockOrdering> TrustRegionSolver::MakeOrdering() {
  if (node_order_.empty()) return nullptr;
  // One elimination group per node, in node_order_, and every other block
  // (constant ones: Ceres wants all blocks) in a last group. A fresh object
  // per solve: Ceres removes the constant blocks from the ordering it is
  // given.
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  const int dim = state_->dimension;
  for (size_t k = 0; k < node_order_.size(); ++k) {
    ordering->AddElementToGroup(positions_.data() + dim * node_order_[k], static_cast<int>(k));
  }
  std::vector<double*> blocks;
  problem_->GetParameterBlocks(&blocks);
  const int last = static_cast<int>(node_order_.size());
  for (double* block : blocks) {
    if (!ordering->IsMember(block)) ordering->AddElementToGroup(block, last);
  }
  return ordering;
}

void TrustRegionSolver::FilterCallback::PrepareForEvaluation(bool evaluate_jacobians,
                                                             bool new_evaluation_point) {
  TrustRegionSolver& s = *solver_;
  if (new_evaluation_point) {
    // The user memory holds the trial point.
    s.veto_ = s.potential_->has_step_filters() && !s.potential_->IsStepValid(s.positions_.data());
    if (s.options_.backtrack_rejected_steps) {
      s.rejected_ = s.positions_;
      s.rejected_vetoed_ = s.veto_;
      s.trial_since_callback_ = true;
    }
    if (s.cache_) s.cache_->Invalidate();
  }
  // The terms' Newton models at this point, on the thread pool.
  if (s.cache_ && !s.veto_ && !s.cache_->Has(evaluate_jacobians)) {
    s.cache_->Prepare(s.positions_.data(), evaluate_jacobians, s.filter_);
  }
}

ceres::CallbackReturnType TrustRegionSolver::FitCallback::operator()(
    const ceres::IterationSummary& summary) {
  // kTrustRegion: the filter of the next models from this step's fit
  // (Ceres's relative decrease: actual over the model's predicted decrease).
  if (summary.iteration > 0) {
    solver_->filter_ = summary.relative_decrease < kTrustRegionFilterSwitch
                           ? EigenvalueFilter::kAbsolute
                           : EigenvalueFilter::kClamp;
  }
  return ceres::SOLVER_CONTINUE;
}

ceres::CallbackReturnType TrustRegionSolver::BacktrackCallback::operator()(
    const ceres::IterationSummary& summary) {
  // Without a new trial point (e.g. the linear solver failed) there is
  // nothing to backtrack along.
  const bool trial = solver_->trial_since_callback_;
  solver_->trial_since_callback_ = false;
  if (summary.step_is_successful && summary.iteration > 0) solver_->short_backtracks_ = 0;
  if (summary.step_is_successful || summary.iteration == 0 || !trial) {
    return ceres::SOLVER_CONTINUE;
  }
  return solver_->BacktrackRejectedStep() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
}

namespace {

// Armijo's rule, and a strict decrease: a step below the positions' round-off
// leaves E unchanged and would satisfy Armijo's rule with a vanishing slope.
bool SufficientDecrease(long double e0, long double e, double alpha, double slope) {
  constexpr double kArmijo = 1e-4;
  return e < e0 && e <= e0 + static_cast<long double>(kArmijo * alpha * slope);
}

}  // namespace

bool TrustRegionSolver::BacktrackRejectedStep() {
  // The callback runs with update_state_every_iteration: positions_ is the
  // accepted iterate, which is also the filters' last accepted point.
  constexpr double kFilterFraction = 0.9;
  // A refused step is cut to the contact-safe fraction, which may be small
  // for a long model step; a step that raised the energy is searched
  // down to about 1e-3 of its length only (10 halvings from <= 0.5): shorter
  // steps are left to Ceres's shrinking trust region, and near the precision
  // floor a longer search only finds round-off "decreases" (measured: before
  // this limit and the strict decrease below, a 100x100 cloth step restarted
  // Ceres at the same point until the iteration limit).
  const int max_halvings = rejected_vetoed_ ? 30 : 10;
  const Eigen::VectorXd& x = positions_;
  // Without inertia (quasi-static) the model can be nearly singular (a body
  // free to slide, gravity's tiny curvature): its steps are then poor
  // directions, and the trust region's memory of a small radius is the better
  // globalisation (solver/trust_region_solver.h). Only a full step that Ceres
  // refused for its cost's round-off is taken.
  const bool quasi_static = !(potential_->context().inertia_weight > 0.0);
  if (quasi_static && rejected_vetoed_) return false;
  // Model steps that keep raising the energy (every restart's first step
  // rejected again) are poor directions: after kMaxShortBacktracks such
  // restarts in a row, leave them to the trust region, whose radius
  // remembers. Measured with Gauss-Newton on cloth_sphere --grid_size=40,
  // first 80 steps:
  // without this limit the restarts crawled at about 1 % per iteration (57
  // iterations per step, 14 failed); with 20: 25.8, 6 failed (the trust
  // region alone: 31.2, 6); 3 and 10 cost slope's stick-slip steps (1.53x and
  // 1.11x the reference's iterations instead of 1.06x).
  if (short_backtracks_ >= kMaxShortBacktracks && !rejected_vetoed_) return false;
  const Eigen::VectorXd direction = rejected_ - x;
  double energy = 0.0;
  ++backtrack_evaluations_;
  if (!potential_->Evaluate(x.data(), &energy, gradient_.data())) return false;
  const double slope = gradient_.dot(direction);
  long double e0 = 0.0L;
  if (!(slope < 0.0) || !potential_->EvaluatePreciseEnergy(x.data(), &e0)) return false;
  double alpha = 0.5;
  if (rejected_vetoed_) {
    alpha = kFilterFraction * potential_->MaxStepSize(x.data(), rejected_.data());
  } else {
    long double e1 = 0.0L;
    ++backtrack_evaluations_;
    if (potential_->EvaluatePreciseEnergy(rejected_.data(), &e1)) {
      // Ceres compares costs in double precision: near convergence it rejects
      // steps whose decrease is below the round-off of its cost sum (the
      // precision floor). The extended-precision energy can still see it.
      if (SufficientDecrease(e0, e1, 1.0, slope)) {
        restart_point_ = rejected_;
        short_backtracks_ = 0;  // the full step: rejected only by round-off
        return true;
      }
      if (quasi_static) return false;
      const double curvature = static_cast<double>(e1 - e0) - slope;  // of the quadratic
      if (curvature > 0.0) alpha = std::clamp(-slope / (2.0 * curvature), 0.1, 0.5);
    }
  }
  for (int k = 0; k < max_halvings && alpha > 0.0; ++k, alpha *= 0.5) {
    trial_ = x + alpha * direction;
    long double e = 0.0L;
    ++backtrack_evaluations_;
    if (potential_->EvaluatePreciseEnergy(trial_.data(), &e) &&
        SufficientDecrease(e0, e, alpha, slope)) {
      restart_point_ = trial_;
      short_backtracks_ += !rejected_vetoed_;
      return true;
    }
  }
  return false;
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
  ceres::Solver::Options options = ceres_options_;
  int iterations = 0, evaluations = 0;
  backtrack_evaluations_ = 0;
  short_backtracks_ = 0;
  while (true) {
    restart_point_.resize(0);
    trial_since_callback_ = false;
    options.linear_solver_ordering = MakeOrdering();
    {
      const SerialOpenMp serial;  // Ceres's SUITE_SPARSE: CHOLMOD (solver/serial_openmp.h)
      ceres::Solve(options, problem_.get(), &summary);
    }
    VLOG(3) << summary.FullReport();
    iterations += summary.iterations.empty() ? 0 : static_cast<int>(summary.iterations.size()) - 1;
    evaluations += summary.num_residual_evaluations;
    bool backtracked = summary.termination_type == ceres::USER_FAILURE && restart_point_.size() > 0;
    // Ceres also ends a solve when a trial point's cost equals the current one
    // in double precision ("function tolerance", at the precision floor),
    // before any callback sees the rejection: backtrack along that trial too.
    if (!backtracked && summary.termination_type == ceres::CONVERGENCE &&
        options_.backtrack_rejected_steps && trial_since_callback_ &&
        !(MeasureAt(positions_.data()) <= options_.tolerance)) {
      backtracked = BacktrackRejectedStep();
      iterations += backtracked;  // the trial's iteration, not in Ceres's summary
    }
    if (!backtracked) break;
    // Restart from the backtracked point with a fresh trust region and what is left
    // of the iteration and time budgets.
    positions_ = restart_point_;
    potential_->NotifyAccepted(positions_.data());
    callback_->Reset(iterations);
    options.max_num_iterations = ceres_options_.max_num_iterations - iterations;
    options.max_solver_time_in_seconds -= summary.total_time_in_seconds;
    if (options.max_num_iterations <= 0 || options.max_solver_time_in_seconds <= 0.0) {
      summary.termination_type = ceres::NO_CONVERGENCE;
      summary.message = options.max_num_iterations <= 0 ? "Maximum number of iterations reached."
                                                        : "Maximum solver time reached.";
      break;
    }
  }
  *x = positions_;
  result.iterations = iterations;
  result.evaluations = evaluations + backtrack_evaluations_;
  result.ceres_report = summary.BriefReport();
  result.residual = MeasureAt(positions_.data());
  ClassifySolve(summary.termination_type, summary.message, result.iterations,
                ceres_options_.max_num_iterations, options_.tolerance, &result);
  return result;
}

}  // namespace ipstep
