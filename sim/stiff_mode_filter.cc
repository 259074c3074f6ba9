#include "sim/stiff_mode_filter.h"

#include <vector>

namespace ipstep {
namespace {

bool SamePattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  if (a.rows() != b.rows() || a.nonZeros() != b.nonZeros()) return false;
  for (int c = 0; c <= a.outerSize(); ++c) {
    if (a.outerIndexPtr()[c] != b.outerIndexPtr()[c]) return false;
  }
  for (int k = 0; k < a.nonZeros(); ++k) {
    if (a.innerIndexPtr()[k] != b.innerIndexPtr()[k]) return false;
  }
  return true;
}

}  // namespace

StiffModeFilter::StiffModeFilter(IncrementalPotential* potential, const State* state,
                                 const OptimizerOptions& options)
    : state_(state), assembler_(potential, state, options) {}

bool StiffModeFilter::Apply(const Eigen::VectorXd& x, Eigen::VectorXd* error) {
  if (!assembler_.AssembleHessian(x, ProjectedNewtonSolver::TermHessian::kClamped)) return false;
  const Eigen::SparseMatrix<double>& hessian = assembler_.hessian();
  const std::vector<int>& free = assembler_.free_index();
  const int dim = state_->dimension;
  if (!cholesky_ || !SamePattern(hessian, analysed_)) {
    cholesky_ = SparseCholesky::Create(SparseLibrary::kSuiteSparse,
                                       ChooseOrdering(dim, static_cast<int>(hessian.rows())));
    if (!cholesky_->Analyze(hessian)) {
      cholesky_.reset();
      return false;
    }
    analysed_ = hessian;
  }
  if (cholesky_->Factorize(hessian) != SparseCholesky::Result::kSuccess) return false;
  Eigen::VectorXd rhs(hessian.rows()), filtered;
  for (int d = 0; d < static_cast<int>(free.size()); ++d) {
    if (free[d] >= 0) rhs[free[d]] = state_->mass[d / dim] * (*error)[d];
  }
  if (!cholesky_->Solve(rhs, &filtered)) return false;
  for (int d = 0; d < static_cast<int>(free.size()); ++d) {
    if (free[d] >= 0) (*error)[d] = filtered[free[d]];
  }
  return true;
}

}  // namespace ipstep
