#include "solver/projected_newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "core/input_error.h"
#include "core/stopping_rule.h"
#include "solver/node_ordering.h"

namespace ipstep {
namespace {

// The first trial step stops at this fraction of the collision-free distance
// (as the simulation's feasible start).
constexpr double kStepFilterFraction = 0.9;
constexpr double kArmijo = 1e-4;
constexpr int kMaxBacktracks = 60;

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

ProjectedNewtonSolver::ProjectedNewtonSolver(IncrementalPotential* potential, const State* state,
                                             const OptimizerOptions& options)
    : potential_(potential),
      state_(state),
      gradient_(state->num_dofs()),
      trial_(state->num_dofs()) {
  ValidateOptimizerOptions(options);
  tolerance_ = options.tolerance;
  max_iterations_ = options.max_iterations > 0 ? options.max_iterations : 100;
  time_limit_ = options.time_limit > 0.0 ? options.time_limit : 1e9;
  projection_ = options.hessian_projection;
  library_ = ProjectedNewtonSparseLibrary(options);
  ordering_ = ParseFillOrdering(options.linear_solver_ordering);
  BuildStructure();
}

void ProjectedNewtonSolver::BuildStructure() {
  const auto start = Clock::now();
  const int dim = state_->dimension;
  free_index_.assign(state_->num_dofs(), -1);
  num_free_ = 0;
  for (int i = 0; i < state_->num_nodes(); ++i) {
    if (!state_->is_free(i)) continue;
    for (int k = 0; k < dim; ++k) free_index_[dim * i + k] = num_free_++;
  }
  // Local index l = b * dim + k of a term maps to DOF dim * nodes[b] + k.
  auto free_of = [&](const Term& term, int l) {
    return free_index_[dim * term.nodes[l / dim] + l % dim];
  };
  std::vector<Eigen::Triplet<double>> triplets;
  for (int d = 0; d < num_free_; ++d) triplets.emplace_back(d, d, 0.0);
  for (const Term& term : potential_->terms()) {
    const int nt = dim * static_cast<int>(term.nodes.size());
    for (int a = 0; a < nt; ++a) {
      for (int b = 0; b < a; ++b) {
        const int fa = free_of(term, a), fb = free_of(term, b);
        if (fa >= 0 && fb >= 0) triplets.emplace_back(std::max(fa, fb), std::min(fa, fb), 0.0);
      }
    }
  }
  hessian_.resize(num_free_, num_free_);
  hessian_.setFromTriplets(triplets.begin(), triplets.end());
  hessian_.makeCompressed();
  auto slot_of = [&](int row, int col) {
    const int* begin = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[col];
    const int* end = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - hessian_.innerIndexPtr());
  };
  diagonal_slots_.resize(num_free_);
  for (int d = 0; d < num_free_; ++d) diagonal_slots_[d] = slot_of(d, d);
  slot_offset_.clear();
  slots_.clear();
  for (const Term& term : potential_->terms()) {
    slot_offset_.push_back(static_cast<int>(slots_.size()));
    const int nt = dim * static_cast<int>(term.nodes.size());
    for (int a = 0; a < nt; ++a) {
      for (int b = 0; b <= a; ++b) {
        const int fa = free_of(term, a), fb = free_of(term, b);
        slots_.push_back(fa >= 0 && fb >= 0 ? slot_of(std::max(fa, fb), std::min(fa, fb)) : -1);
      }
    }
  }
  parameters_.resize(kMaxTermCoordinates);
  free_rhs_.resize(num_free_);
  free_step_.resize(num_free_);
  analyzed_ = false;
  built_version_ = potential_->structure_version();
  timings_.analyze += Since(start);
}

bool ProjectedNewtonSolver::AddTermHessian(const Term& term, const double* x, double weight,
                                           const int* slots, bool project) {
  const int dim = state_->dimension;
  const int blocks = static_cast<int>(term.nodes.size());
  for (int b = 0; b < blocks; ++b) parameters_[b] = x + dim * term.nodes[b];
  if (!evaluator_.Evaluate(term, dim, weight, parameters_.data(), true, &model_)) return false;
  // Gauss-Newton models are PSD as they are (rho' J^T J, rho'' part only where
  // positive); the others are projected.
  const TermMatrix* h = &model_.hessian;
  if (!term.gauss_newton_model && project) {
    ProjectHessian(model_, &projected_);
    scaled_.noalias() = projected_.vectors * projected_.values.asDiagonal();
    local_hessian_.noalias() = scaled_ * projected_.vectors.transpose();
    h = &local_hessian_;
  }
  // Pair-difference terms: the full Hessian is [[K, -K], [-K, K]].
  const int n = static_cast<int>(h->rows());
  const int nt = dim * blocks;
  double* values = hessian_.valuePtr();
  int index = 0;
  for (int a = 0; a < nt; ++a) {
    for (int b = 0; b <= a; ++b, ++index) {
      if (slots[index] < 0) continue;
      if (term.pair_difference) {
        const double sign = (a < n) == (b < n) ? 1.0 : -1.0;
        values[slots[index]] += sign * (*h)(a % n, b % n);
      } else {
        values[slots[index]] += (*h)(a, b);
      }
    }
  }
  return true;
}

bool ProjectedNewtonSolver::AssembleHessian(const Eigen::VectorXd& x, bool project) {
  if (built_version_ != potential_->structure_version()) BuildStructure();
  const auto start = Clock::now();
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  const auto& terms = potential_->terms();
  const StepContext& context = potential_->context();
  bool ok = true;
  for (size_t t = 0; t < terms.size() && ok; ++t) {
    const double weight = TermWeight(terms[t].kind, context);
    if (weight == 0.0) continue;
    ok = AddTermHessian(terms[t], x.data(), weight, slots_.data() + slot_offset_[t], project);
  }
  timings_.hessian += Since(start);
  return ok;
}

void ProjectedNewtonSolver::EnsureAnalyzed() {
  if (analyzed_) return;
  const auto start = Clock::now();
  const FillOrdering ordering = ordering_ == FillOrdering::kAutomatic
                                    ? ChooseOrdering(state_->dimension, num_free_)
                                    : ordering_;
  if (!cholesky_ || cholesky_ordering_ != ordering) {
    cholesky_ = SparseCholesky::Create(library_, ordering);
    cholesky_ordering_ = ordering;
  }
  // Nested dissection of the nodes, expanded to their free unknowns
  // (solver/node_ordering.h); METIS on the unknowns if it fails.
  std::vector<int> permutation;
  if (ordering == FillOrdering::kNestedDissection && library_ == SparseLibrary::kSuiteSparse) {
    const int dim = state_->dimension;
    for (int node : NestedDissectionNodeOrder(*potential_, *state_)) {
      for (int k = 0; k < dim; ++k) {
        if (free_index_[dim * node + k] >= 0) permutation.push_back(free_index_[dim * node + k]);
      }
    }
    if (static_cast<int>(permutation.size()) != num_free_) permutation.clear();
  }
  analyzed_ = cholesky_->Analyze(hessian_, permutation.empty() ? nullptr : &permutation);
  timings_.analyze += Since(start);
}

bool ProjectedNewtonSolver::FactorizePositiveDefinite() {
  return analyzed_ && cholesky_->Factorize(hessian_) == SparseCholesky::Result::kSuccess;
}

bool ProjectedNewtonSolver::ComputeDirection(const Eigen::VectorXd& gradient,
                                             Eigen::VectorXd* direction) {
  EnsureAnalyzed();
  const auto start = Clock::now();
  // PSD projection leaves H singular only without inertia (quasi-static, free
  // rigid modes): then a growing multiple of the identity is added.
  double max_diagonal = 0.0;
  for (int slot : diagonal_slots_) max_diagonal = std::max(max_diagonal, hessian_.valuePtr()[slot]);
  double shift = 0.0;
  bool ok = false;
  for (int attempt = 0; attempt < 12 && !ok; ++attempt) {
    if (attempt > 0) {
      const double next = shift == 0.0 ? 1e-10 * std::max(max_diagonal, 1e-300) : 100.0 * shift;
      for (int slot : diagonal_slots_) hessian_.valuePtr()[slot] += next - shift;
      shift = next;
    }
    ok = FactorizePositiveDefinite();
  }
  ok = ok && SolveFactorised(gradient, direction);
  if (!ok) direction->setZero(state_->num_dofs());
  timings_.factorize += Since(start);
  return ok;
}

bool ProjectedNewtonSolver::DefiniteDirection(const Eigen::VectorXd& gradient,
                                              Eigen::VectorXd* direction) {
  EnsureAnalyzed();
  const auto start = Clock::now();
  const bool ok = FactorizePositiveDefinite() && SolveFactorised(gradient, direction);
  timings_.factorize += Since(start);
  return ok;
}

bool ProjectedNewtonSolver::SolveFactorised(const Eigen::VectorXd& gradient,
                                            Eigen::VectorXd* direction) {
  for (int d = 0; d < state_->num_dofs(); ++d) {
    if (free_index_[d] >= 0) free_rhs_[free_index_[d]] = -gradient[d];
  }
  if (!cholesky_->Solve(free_rhs_, &free_step_)) return false;
  direction->setZero(state_->num_dofs());
  for (int d = 0; d < state_->num_dofs(); ++d) {
    if (free_index_[d] >= 0) (*direction)[d] = free_step_[free_index_[d]];
  }
  return true;
}

StepSolveResult ProjectedNewtonSolver::Solve(Eigen::VectorXd* x) {
  const auto solve_start = Clock::now();
  if (built_version_ != potential_->structure_version()) BuildStructure();
  StepSolveResult result;
  potential_->NotifyAccepted(x->data());
  double energy = 0.0;
  auto start = Clock::now();
  const bool evaluated = potential_->Evaluate(x->data(), &energy, gradient_.data());
  timings_.gradient += Since(start);
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
  for (int iteration = 0;; ++iteration) {
    if (sink_) {
      IterationRecord record;
      record.iteration = iteration;
      record.energy = energy;
      record.gradient_norm = gradient_.lpNorm<Eigen::Infinity>();
      record.step_size = alpha;
      record.seconds = Since(solve_start);
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
    if (Since(solve_start) > time_limit_) {
      result.status = "time limit: " + std::to_string(time_limit_) + " s";
      break;
    }
    // The exact Hessian's step where the sum is definite (kWhenIndefinite),
    // else the projected model's.
    bool exact = false;
    if (projection_ == HessianProjection::kWhenIndefinite) {
      if (!AssembleHessian(*x, /*project=*/false)) {
        result.status = "Hessian cannot be evaluated";
        break;
      }
      exact = DefiniteDirection(gradient_, &direction);
    }
    if (!exact) {
      if (!AssembleHessian(*x)) {
        result.status = "Hessian cannot be evaluated";
        break;
      }
      if (!ComputeDirection(gradient_, &direction)) {
        result.status = "factorisation failed";
        break;
      }
    }
    ++(exact ? exact_directions_ : projected_directions_);
    ++result.iterations;
    start = Clock::now();
    double slope = gradient_.dot(direction);
    if (!(slope < 0.0)) {  // not a descent direction (round-off): steepest descent
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
      if (potential_->EvaluatePreciseEnergy(trial_.data(), &e) &&
          e <= e0 + static_cast<long double>(kArmijo * alpha * slope)) {
        accepted = true;
        break;
      }
    }
    timings_.line_search += Since(start);
    if (!accepted) {
      result.status = "line search failed";
      break;
    }
    x->swap(trial_);
    potential_->NotifyAccepted(x->data());
    start = Clock::now();
    ++result.evaluations;
    const bool ok = potential_->Evaluate(x->data(), &energy, gradient_.data());
    timings_.gradient += Since(start);
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
