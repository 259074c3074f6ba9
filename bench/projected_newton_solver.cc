#include "bench/projected_newton_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "core/stopping_rule.h"

namespace ipstep {
namespace {

// The first trial step stops at this fraction of the collision-free distance
// (as the simulation's feasible start).
constexpr double kStepFilterFraction = 0.9;

using Clock = std::chrono::steady_clock;

// Clamps the negative eigenvalues of the symmetric n x n matrix h to zero, with
// a fixed-size eigen-decomposition for the common term sizes (closed form for
// n <= 3).
template <int N, class Matrix>
void ProjectFixed(Matrix* h) {
  using Fixed = Eigen::Matrix<double, N, N>;
  const Fixed a = h->template topLeftCorner<N, N>();
  Eigen::SelfAdjointEigenSolver<Fixed> eigen;
  if (N <= 3) {
    eigen.computeDirect(a);
  } else {
    eigen.compute(a);
  }
  if (eigen.info() != Eigen::Success || eigen.eigenvalues().minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, N, 1> clamped = eigen.eigenvalues().cwiseMax(0.0);
  h->template topLeftCorner<N, N>() =
      eigen.eigenvectors() * clamped.asDiagonal() * eigen.eigenvectors().transpose();
}

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

ProjectedNewtonSolver::ProjectedNewtonSolver(IncrementalPotential* potential, const State* state,
                                             const ProjectedNewtonOptions& options)
    : potential_(potential),
      state_(state),
      options_(options),
      gradient_(state->num_dofs()),
      trial_(state->num_dofs()) {
  if (!(options.tolerance > 0.0)) throw std::invalid_argument("tolerance must be > 0");
  if (options.max_iterations < 1) throw std::invalid_argument("max_iterations must be >= 1");
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
  int max_residuals = 1;
  for (const Term& term : potential_->terms()) {
    const int nt = dim * static_cast<int>(term.nodes.size());
    if (nt > kMaxTermParameters || term.cost->num_residuals() > kMaxTermResiduals) {
      throw std::invalid_argument("projected newton: term of family '" + term.family +
                                  "' is larger than the reference solver supports");
    }
    max_residuals = std::max(max_residuals, term.cost->num_residuals());
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
  residuals_.resize(max_residuals);
  jacobian_blocks_.resize(static_cast<size_t>(max_residuals) * kMaxTermParameters);
  jacobian_pointers_.resize(kMaxTermParameters);
  parameter_pointers_.resize(kMaxTermParameters);
  local_x_.resize(kMaxTermParameters);
  free_rhs_.resize(num_free_);
  free_step_.resize(num_free_);
  analyzed_ = false;
  built_version_ = potential_->structure_version();
  timings_.analyze += Since(start);
}

bool ProjectedNewtonSolver::TermHessian(const Term& term, const double* x, double weight,
                                        const int* slots) {
  const int dim = state_->dimension;
  const int blocks = static_cast<int>(term.nodes.size());
  const int nt = dim * blocks;
  const int m = term.cost->num_residuals();
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < dim; ++k) local_x_[b * dim + k] = x[dim * term.nodes[b] + k];
    parameter_pointers_[b] = local_x_.data() + b * dim;
    jacobian_pointers_[b] = jacobian_blocks_.data() + static_cast<size_t>(b) * m * dim;
  }
  // Row-major m x dim blocks into an m x nt Jacobian.
  auto evaluate = [&](double* residuals, TermMatrix* jacobian) {
    if (!term.cost->Evaluate(parameter_pointers_.data(), residuals, jacobian_pointers_.data())) {
      return false;
    }
    jacobian->resize(m, nt);
    for (int b = 0; b < blocks; ++b) {
      for (int r = 0; r < m; ++r) {
        for (int k = 0; k < dim; ++k)
          (*jacobian)(r, b * dim + k) = jacobian_pointers_[b][r * dim + k];
      }
    }
    return true;
  };
  if (!evaluate(residuals_.data(), &jacobian_)) return false;
  const Eigen::Map<const Eigen::VectorXd> r(residuals_.data(), m);
  const double s = r.squaredNorm();
  double rho[3] = {s, 1.0, 0.0};
  if (term.loss) term.loss->Evaluate(s, rho);
  jtr_.noalias() = jacobian_.transpose() * r;
  local_hessian_.noalias() = rho[1] * jacobian_.transpose() * jacobian_;
  local_hessian_.noalias() += (2.0 * rho[2]) * jtr_ * jtr_.transpose();
  // Second-order part rho' sum_k r_k Hess(r_k) by central differences of J^T r
  // with r held fixed. Inertia residuals are linear in x.
  if (term.kind != TermKind::kInertia && rho[1] != 0.0) {
    bool ok = true;
    second_order_.resize(nt, nt);
    for (int j = 0; j < nt && ok; ++j) {
      const double saved = local_x_[j];
      const double step = options_.fd_relative_step * std::max(1.0, std::abs(saved));
      local_x_[j] = saved + step;
      const double up = local_x_[j];
      ok = evaluate(fd_residuals_.data(), &jacobian_fd_);
      if (ok) column_.noalias() = jacobian_fd_.transpose() * r;
      local_x_[j] = saved - step;
      const double down = local_x_[j];
      ok = ok && evaluate(fd_residuals_.data(), &jacobian_fd_);
      if (ok) second_order_.col(j) = (column_ - jacobian_fd_.transpose() * r) / (up - down);
      local_x_[j] = saved;
    }
    // A term that cannot be evaluated beside x (e.g. a barrier at the edge of its
    // domain) keeps only its Gauss-Newton part, which is PSD.
    if (ok) {
      local_hessian_ += (0.5 * rho[1]) * (second_order_ + second_order_.transpose());
    } else {
      ++fd_fallbacks_;
    }
  }
  local_hessian_ *= weight;
  if (options_.project_to_psd && term.kind != TermKind::kInertia) {
    switch (nt) {
      case 1:
        local_hessian_(0, 0) = std::max(local_hessian_(0, 0), 0.0);
        break;
      case 2:
        ProjectFixed<2>(&local_hessian_);
        break;
      case 3:
        ProjectFixed<3>(&local_hessian_);
        break;
      case 4:
        ProjectFixed<4>(&local_hessian_);
        break;
      case 6:
        ProjectFixed<6>(&local_hessian_);
        break;
      default:
        eigen_.compute(local_hessian_);
        if (eigen_.info() == Eigen::Success && eigen_.eigenvalues().minCoeff() < 0.0) {
          eigenvalues_ = eigen_.eigenvalues().cwiseMax(0.0);
          local_hessian_.noalias() =
              eigen_.eigenvectors() * eigenvalues_.asDiagonal() * eigen_.eigenvectors().transpose();
        }
        break;
    }
  }
  double* values = hessian_.valuePtr();
  int index = 0;
  for (int a = 0; a < nt; ++a) {
    for (int b = 0; b <= a; ++b, ++index) {
      if (slots[index] >= 0) values[slots[index]] += local_hessian_(a, b);
    }
  }
  return true;
}

bool ProjectedNewtonSolver::AssembleHessian(const Eigen::VectorXd& x) {
  if (built_version_ != potential_->structure_version()) BuildStructure();
  const auto start = Clock::now();
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  const auto& terms = potential_->terms();
  const StepContext& context = potential_->context();
  bool ok = true;
  for (size_t t = 0; t < terms.size() && ok; ++t) {
    const double weight = TermWeight(terms[t].kind, context);
    if (weight == 0.0) continue;
    ok = TermHessian(terms[t], x.data(), weight, slots_.data() + slot_offset_[t]);
  }
  timings_.hessian += Since(start);
  return ok;
}

bool ProjectedNewtonSolver::ComputeDirection(const Eigen::VectorXd& gradient,
                                             Eigen::VectorXd* direction) {
  if (!analyzed_) {
    const auto start = Clock::now();
    ldlt_.analyzePattern(hessian_);
    analyzed_ = true;
    timings_.analyze += Since(start);
  }
  const auto start = Clock::now();
  const int dim = state_->dimension;
  for (int d = 0; d < state_->num_dofs(); ++d) {
    if (free_index_[d] >= 0) free_rhs_[free_index_[d]] = -gradient[d];
  }
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
    ldlt_.factorize(hessian_);
    ok = ldlt_.info() == Eigen::Success && ldlt_.vectorD().minCoeff() > 0.0;
  }
  if (ok) {
    free_step_ = ldlt_.solve(free_rhs_);
    ok = free_step_.allFinite();
  }
  direction->setZero(state_->num_dofs());
  if (ok) {
    for (int i = 0; i < state_->num_nodes(); ++i) {
      for (int k = 0; k < dim; ++k) {
        const int f = free_index_[dim * i + k];
        if (f >= 0) (*direction)[dim * i + k] = free_step_[f];
      }
    }
  }
  timings_.factorize += Since(start);
  return ok;
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
    if (result.residual <= options_.tolerance) {
      result.converged = true;
      result.status = "converged";
      break;
    }
    if (iteration >= options_.max_iterations) {
      result.status = "iteration limit (" + std::to_string(options_.max_iterations) + ")";
      break;
    }
    if (!AssembleHessian(*x)) {
      result.status = "Hessian cannot be evaluated";
      break;
    }
    if (!ComputeDirection(gradient_, &direction)) {
      result.status = "factorisation failed";
      break;
    }
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
    for (int backtrack = 0; backtrack <= options_.max_backtracks; ++backtrack, alpha *= 0.5) {
      trial_ = *x + alpha * direction;
      long double e = 0.0L;
      ++result.evaluations;
      if (potential_->EvaluatePreciseEnergy(trial_.data(), &e) &&
          e <= e0 + static_cast<long double>(options_.armijo * alpha * slope)) {
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
