// ProjectedNewtonSolver (solver/projected_newton_solver.h): the Newton system
// H p = -g over the free degrees of freedom. Sparse Cholesky (symbolic
// analysis once per structure, nested dissection of the nodes or AMD) with a
// growing diagonal shift where H is singular, or conjugate gradients
// (--linear_solver=CG).
#include "solver/projected_newton_solver.h"

#include <algorithm>
#include <vector>

#include "core/scoped_timer.h"
#include "solver/node_ordering.h"

namespace ipstep {

void ProjectedNewtonSolver::EnsureAnalyzed() {
  if (analyzed_) return;
  const auto start = WallClock::now();
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
  timings_.analyze += SecondsSince(start);
}

bool ProjectedNewtonSolver::FactorizePositiveDefinite() {
  factorised_in_solve_ =
      analyzed_ && cholesky_->Factorize(hessian_) == SparseCholesky::Result::kSuccess;
  return factorised_in_solve_;
}

bool ProjectedNewtonSolver::SolveWithLastStepMatrix(const Eigen::VectorXd& rhs,
                                                    Eigen::VectorXd* y) {
  if (!factorised_in_solve_ || use_cg_) return false;
  // SolveFactorised returns -A^-1 g.
  if (!SolveFactorised(-rhs, y)) return false;
  return true;
}

bool ProjectedNewtonSolver::ComputeDirection(const Eigen::VectorXd& gradient,
                                             Eigen::VectorXd* direction) {
  if (use_cg_) {
    const auto start = WallClock::now();
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
    timings_.factorize += SecondsSince(start);
    return ok;
  }
  EnsureAnalyzed();
  const auto start = WallClock::now();
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
  timings_.factorize += SecondsSince(start);
  return ok;
}

bool ProjectedNewtonSolver::DefiniteDirection(const Eigen::VectorXd& gradient,
                                              Eigen::VectorXd* direction) {
  EnsureAnalyzed();
  const auto start = WallClock::now();
  const bool ok = FactorizePositiveDefinite() && SolveFactorised(gradient, direction);
  timings_.factorize += SecondsSince(start);
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

}  // namespace ipstep
