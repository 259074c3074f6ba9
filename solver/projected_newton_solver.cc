// ProjectedNewtonSolver (solver/projected_newton_solver.h): the options, the
// direction of each iteration (by the Hessian projection) and the solve loop
// with its Armijo line search. The Hessian's assembly is in
// projected_newton_assembly.cc, the Newton system's solution in
// projected_newton_linear_solve.cc.
#include "solver/projected_newton_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/input_error.h"
#include "core/scoped_timer.h"
#include "core/stopping_rule.h"

namespace ipstep {
namespace {

// The first trial step stops at this fraction of the collision-free distance
// (as the simulation's feasible start).
constexpr double kStepFilterFraction = 0.9;
constexpr double kArmijo = 1e-4;
constexpr int kMaxBacktracks = 60;
// kProgressive: the threshold's shrink factor and the attempts per iteration
// before every term is projected.
constexpr double kProgressiveShrink = 0.25;
constexpr int kProgressiveAttempts = 6;

}  // namespace

ProjectedNewtonSolver::ProjectedNewtonSolver(IncrementalPotential* potential, const State* state,
                                             const OptimizerOptions& options)
    : potential_(potential),
      state_(state),
      gradient_(state->num_dofs()),
      trial_(state->num_dofs()) {
  ValidateOptimizerOptions(options);
  potential_->SetNumThreads(ThreadCount(options));
  tolerance_ = options.tolerance;
  max_iterations_ = options.max_iterations > 0 ? options.max_iterations : 100;
  time_limit_ = options.time_limit > 0.0 ? options.time_limit : 1e9;
  projection_ = ResolveHessianProjection(options);
  library_ = ProjectedNewtonSparseLibrary(options);
  use_cg_ = ProjectedNewtonUsesCg(options);
  ordering_ = ParseFillOrdering(options.linear_solver_ordering);
  BuildStructure();
}

std::string ProjectedNewtonSolver::LinearSolverDescription() const {
  if (use_cg_) {
    return "conjugate gradients with incomplete Cholesky (CG), forcing term min(0.1, "
           "sqrt(r/r0))";
  }
  if (library_ == SparseLibrary::kEigen) return "Eigen SimplicialLDLT (EIGEN_SPARSE), AMD ordering";
  const FillOrdering ordering = ordering_ == FillOrdering::kAutomatic
                                    ? ChooseOrdering(state_->dimension, num_free_)
                                    : ordering_;
  return std::string("CHOLMOD LL^T (SUITE_SPARSE), ") +
         (ordering == FillOrdering::kNestedDissection ? "nested dissection (METIS) of the nodes"
                                                      : "AMD") +
         " ordering";
}

std::vector<int> ProjectedNewtonSolver::GrowProjectedSet(double threshold) {
  const int dim = state_->dimension;
  const StepContext& context = potential_->context();
  // A node's share of the stopping measure (core/stopping_rule.h).
  const double scale = context.time_step / context.potential_weight;
  std::vector<int> added;
  const auto& terms = potential_->terms();
  for (size_t t = 0; t < terms.size(); ++t) {
    if (projected_set_[t] || terms[t].gauss_newton_model) continue;
    for (int node : terms[t].nodes) {
      if (!state_->is_free(node)) continue;
      const double measure = scale * gradient_.segment(dim * node, dim).norm() / state_->mass[node];
      if (measure > threshold) {
        projected_set_[t] = 1;
        added.push_back(static_cast<int>(t));
        break;
      }
    }
  }
  return added;
}

bool ProjectedNewtonSolver::ProgressiveDirection(const Eigen::VectorXd& x,
                                                 Eigen::VectorXd* direction, bool* evaluated) {
  // Terms at nodes whose share of the stopping measure is above
  // threshold = fraction * (the largest share) are projected, the others
  // exact; while the sum is not positive definite, the fraction drops by
  // kProgressiveShrink and more terms join. The set only grows within a step.
  const StepContext& context = potential_->context();
  const double residual = StoppingMeasure(gradient_, *state_, context);
  double fraction = 1.0;
  for (int attempt = 0; attempt < kProgressiveAttempts; ++attempt, fraction *= kProgressiveShrink) {
    const std::vector<int> added = GrowProjectedSet(fraction * residual);
    bool ok;
    if (attempt == 0) {
      ok = AssembleHessian(x, TermHessian::kExact, &projected_set_);
    } else {
      if (added.empty()) continue;
      ok = UpdateTermHessians(x, added, TermHessian::kClamped);
    }
    if (!ok) return *evaluated = false;
    if (DefiniteDirection(gradient_, direction)) {
      for (char flag : projected_set_) projected_terms_ += flag;
      return true;
    }
  }
  return false;
}

bool ProjectedNewtonSolver::NewtonDirection(const Eigen::VectorXd& x, Eigen::VectorXd* direction,
                                            std::string* status) {
  // kWhenIndefinite: the exact Hessian's step where the sum is definite;
  // kProgressive: the step of the partly projected Hessian where it is
  // definite; else (and as their fallback) every term projected.
  bool partial = false;
  TermHessian kind = TermHessian::kClamped;
  switch (projection_) {
    case HessianProjection::kWhenIndefinite:
      if (!AssembleHessian(x, TermHessian::kExact)) {
        *status = "Hessian cannot be evaluated";
        return false;
      }
      partial = DefiniteDirection(gradient_, direction);
      break;
    case HessianProjection::kProgressive: {
      bool evaluated = true;
      partial = ProgressiveDirection(x, direction, &evaluated);
      if (!evaluated) {
        *status = "Hessian cannot be evaluated";
        return false;
      }
      break;
    }
    case HessianProjection::kAbsolute:
      kind = TermHessian::kAbsolute;
      break;
    case HessianProjection::kTrustRegion:
      kind = model_fit_ < kTrustRegionFilterSwitch ? TermHessian::kAbsolute : TermHessian::kClamped;
      break;
    case HessianProjection::kDefault:  // resolved in the constructor
    case HessianProjection::kAlways:
    case HessianProjection::kInertia:  // rejected by ValidateOptimizerOptions
      break;
  }
  if (!partial) {
    if (!AssembleHessian(x, kind)) {
      *status = "Hessian cannot be evaluated";
      return false;
    }
    if (projection_ == HessianProjection::kProgressive) {
      projected_terms_ += static_cast<long>(potential_->terms().size());
    }
    if (!ComputeDirection(gradient_, direction)) {
      *status = "factorisation failed";
      return false;
    }
  }
  ++(partial ? exact_directions_ : projected_directions_);
  if (!partial && kind == TermHessian::kAbsolute) ++absolute_directions_;
  return true;
}

StepSolveResult ProjectedNewtonSolver::Solve(Eigen::VectorXd* x) {
  const auto solve_start = WallClock::now();
  if (built_version_ != potential_->structure_version()) BuildStructure();
  factorised_in_solve_ = false;
  StepSolveResult result;
  potential_->NotifyAccepted(x->data());
  double energy = 0.0;
  auto start = WallClock::now();
  const bool evaluated = potential_->Evaluate(x->data(), &energy, gradient_.data());
  timings_.gradient += SecondsSince(start);
  ++result.evaluations;
  if (!evaluated) {
    result.status = "energy cannot be evaluated at the initial guess";
    result.residual = std::numeric_limits<double>::infinity();
    return result;
  }
  const StepContext& context = potential_->context();
  result.residual = StoppingMeasure(gradient_, *state_, context);
  Eigen::VectorXd direction(state_->num_dofs());
  double alpha = 0.0;
  model_fit_ = 1.0;
  projected_set_.assign(potential_->terms().size(), 0);
  initial_residual_ = result.residual;
  for (int iteration = 0;; ++iteration) {
    if (sink_) {
      IterationRecord record;
      record.iteration = iteration;
      record.energy = energy;
      record.gradient_norm = gradient_.lpNorm<Eigen::Infinity>();
      record.step_size = alpha;
      record.seconds = SecondsSince(solve_start);
      record.residual = result.residual;
      sink_(record);
    }
    if (result.residual <= tolerance_) {
      result.converged = true;
      result.status = "converged";
      break;
    }
    if (iteration >= max_iterations_) {
      result.status = "iteration limit (" + std::to_string(max_iterations_) + ")";
      break;
    }
    if (SecondsSince(solve_start) > time_limit_) {
      result.status = "time limit: " + std::to_string(time_limit_) + " s";
      break;
    }
    // Inexact Newton (CG): the Newton system to a relative residual of
    // min(0.1, sqrt(r / r0)), r the stopping measure (a forcing term after
    // Eisenstat and Walker 1996): loose far from the solution, superlinear
    // near it. Measured on the 36,300-DOF bar's backward-Euler step: a cap of
    // 0.5 took 8 Newton iterations, 0.1 took 6 (the direct solver: 3).
    forcing_ =
        std::clamp(std::sqrt(result.residual / std::max(initial_residual_, 1e-300)), 1e-12, 0.1);
    std::string failure;
    if (!NewtonDirection(*x, &direction, &failure)) {
      result.status = failure;
      break;
    }
    ++result.iterations;
    start = WallClock::now();
    double slope = gradient_.dot(direction);
    const bool newton_direction = slope < 0.0;
    if (!newton_direction) {  // not a descent direction (round-off): steepest descent
      direction = -gradient_;
      for (int d = 0; d < state_->num_dofs(); ++d) {
        if (free_index_[d] < 0) direction[d] = 0.0;
      }
      slope = gradient_.dot(direction);
    }
    long double e0 = 0.0L;
    potential_->EvaluatePreciseEnergy(x->data(), &e0);
    alpha = 1.0;
    if (potential_->has_step_filters()) {
      trial_ = *x + direction;
      const double t = potential_->MaxStepSize(x->data(), trial_.data());
      if (t < 1.0) alpha = kStepFilterFraction * t;
    }
    bool accepted = false;
    for (int backtrack = 0; backtrack <= kMaxBacktracks; ++backtrack, alpha *= 0.5) {
      trial_ = *x + alpha * direction;
      long double e = 0.0L;
      ++result.evaluations;
      const bool evaluable = potential_->EvaluatePreciseEnergy(trial_.data(), &e);
      if (backtrack == 0 && newton_direction) {
        // The model's fit at the first trial: actual over predicted decrease,
        // the prediction -(alpha g^T p + alpha^2 / 2 p^T H p) with H p = -g.
        const double predicted = -slope * (alpha - 0.5 * alpha * alpha);
        model_fit_ = evaluable && predicted > 0.0 ? static_cast<double>(e0 - e) / predicted
                                                  : -std::numeric_limits<double>::infinity();
      }
      if (evaluable && e <= e0 + static_cast<long double>(kArmijo * alpha * slope)) {
        accepted = true;
        break;
      }
    }
    timings_.line_search += SecondsSince(start);
    if (!accepted) {
      result.status = "line search failed";
      break;
    }
    x->swap(trial_);
    potential_->NotifyAccepted(x->data());
    start = WallClock::now();
    ++result.evaluations;
    const bool ok = potential_->Evaluate(x->data(), &energy, gradient_.data());
    timings_.gradient += SecondsSince(start);
    if (!ok) {
      result.status = "energy cannot be evaluated at an accepted iterate";
      result.residual = std::numeric_limits<double>::infinity();
      break;
    }
    result.residual = StoppingMeasure(gradient_, *state_, context);
  }
  return result;
}

}  // namespace ipstep
