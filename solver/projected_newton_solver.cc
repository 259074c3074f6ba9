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
// kProgressive: the threshold's shrink factor and the attempts per iteration
// before every term is projected.
constexpr double kProgressiveShrink = 0.25;
constexpr int kProgressiveAttempts = 6;

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
  local_values_.resize(slots_.size());
  free_rhs_.resize(num_free_);
  free_step_.resize(num_free_);
  analyzed_ = false;
  built_version_ = potential_->structure_version();
  timings_.analyze += Since(start);
}

bool ProjectedNewtonSolver::TermLocalHessian(int t, const double* x, double weight,
                                             TermHessian kind, Scratch* scratch) {
  const Term& term = potential_->terms()[t];
  const int dim = state_->dimension;
  const int blocks = static_cast<int>(term.nodes.size());
  scratch->parameters.resize(blocks);
  for (int b = 0; b < blocks; ++b) scratch->parameters[b] = x + dim * term.nodes[b];
  TermModel& model = scratch->model;
  if (kind == TermHessian::kExact && term.affine_energy) {
    // The exact Hessian of an affine energy: zero (Term::affine_energy).
    const int nt = dim * blocks;
    std::fill_n(local_values_.data() + slot_offset_[t], nt * (nt + 1) / 2, 0.0);
    return true;
  }
  if (!scratch->evaluator.Evaluate(term, dim, weight, scratch->parameters.data(), true, &model)) {
    return false;
  }
  // Gauss-Newton models are PSD as they are (rho' J^T J, rho'' part only where
  // positive); the others are projected unless exact.
  const TermMatrix* h = &model.hessian;
  if (!term.gauss_newton_model && kind != TermHessian::kExact) {
    ProjectedHessian& projected = scratch->projected;
    ProjectHessian(
        model, &projected,
        kind == TermHessian::kAbsolute ? EigenvalueFilter::kAbsolute : EigenvalueFilter::kClamp);
    scratch->scaled.noalias() = projected.vectors * projected.values.asDiagonal();
    scratch->local.noalias() = scratch->scaled * projected.vectors.transpose();
    h = &scratch->local;
  }
  // Pair-difference terms: the full Hessian is [[K, -K], [-K, K]].
  const int n = static_cast<int>(h->rows());
  const int nt = dim * blocks;
  double* out = local_values_.data() + slot_offset_[t];
  int index = 0;
  for (int a = 0; a < nt; ++a) {
    for (int b = 0; b <= a; ++b, ++index) {
      if (term.pair_difference) {
        const double sign = (a < n) == (b < n) ? 1.0 : -1.0;
        out[index] = sign * (*h)(a % n, b % n);
      } else {
        out[index] = (*h)(a, b);
      }
    }
  }
  return true;
}

bool ProjectedNewtonSolver::AssembleHessian(const Eigen::VectorXd& x, TermHessian kind,
                                            const std::vector<char>* projected_terms) {
  if (built_version_ != potential_->structure_version()) BuildStructure();
  const auto start = Clock::now();
  const auto& terms = potential_->terms();
  const StepContext& context = potential_->context();
  const int n = static_cast<int>(terms.size());
  ThreadPool& pool = potential_->thread_pool();
  if (static_cast<int>(scratch_.size()) < pool.num_threads()) scratch_.resize(pool.num_threads());
  term_ok_.resize(n);
  // term_ok_: 1 computed, 0 failed, 2 skipped (weight 0).
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    for (int t = begin; t < end; ++t) {
      const double weight = TermWeight(terms[t].kind, context);
      if (weight == 0.0) {
        term_ok_[t] = 2;
        continue;
      }
      const TermHessian term_kind = projected_terms == nullptr ? kind
                                    : (*projected_terms)[t]    ? TermHessian::kClamped
                                                               : TermHessian::kExact;
      term_ok_[t] = TermLocalHessian(t, x.data(), weight, term_kind, &scratch_[thread]) ? 1 : 0;
    }
  });
  const bool ok = ScatterTermHessians();
  term_models_ += n;
  timings_.hessian += Since(start);
  return ok;
}

bool ProjectedNewtonSolver::UpdateTermHessians(const Eigen::VectorXd& x,
                                               const std::vector<int>& terms, TermHessian kind) {
  const auto start = Clock::now();
  const StepContext& context = potential_->context();
  const auto& all = potential_->terms();
  const int n = static_cast<int>(terms.size());
  ThreadPool& pool = potential_->thread_pool();
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    for (int k = begin; k < end; ++k) {
      const int t = terms[k];
      const double weight = TermWeight(all[t].kind, context);
      term_ok_[t] = weight == 0.0
                        ? 2
                        : (TermLocalHessian(t, x.data(), weight, kind, &scratch_[thread]) ? 1 : 0);
    }
  });
  term_models_ += n;
  const bool ok = ScatterTermHessians();
  timings_.hessian += Since(start);
  return ok;
}

bool ProjectedNewtonSolver::ScatterTermHessians() {
  // The sum in term order: the same matrix for any number of threads.
  const int n = static_cast<int>(potential_->terms().size());
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  double* values = hessian_.valuePtr();
  for (int t = 0; t < n; ++t) {
    if (term_ok_[t] == 2) continue;
    if (term_ok_[t] != 1) return false;
    const int begin = slot_offset_[t];
    const int end = t + 1 < n ? slot_offset_[t + 1] : static_cast<int>(slots_.size());
    for (int i = begin; i < end; ++i) {
      if (slots_[i] >= 0) values[slots_[i]] += local_values_[i];
    }
  }
  return true;
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
  if (use_cg_) {
    const auto start = Clock::now();
    for (int d = 0; d < state_->num_dofs(); ++d) {
      if (free_index_[d] >= 0) free_rhs_[free_index_[d]] = -gradient[d];
    }
    const bool ok = cg_.Solve(hessian_, free_rhs_, forcing_, &free_step_);
    direction->setZero(state_->num_dofs());
    if (ok) {
      for (int d = 0; d < state_->num_dofs(); ++d) {
        if (free_index_[d] >= 0) (*direction)[d] = free_step_[free_index_[d]];
      }
    }
    timings_.factorize += Since(start);
    return ok;
  }
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
    start = Clock::now();
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
