#include "sim/stiff_mode_filter.h"

#include <vector>

namespace ipstep {

StiffModeFilter::StiffModeFilter(IncrementalPotential* potential, const State* state,
                                 const OptimizerOptions& options)
    : potential_(potential), assembler_(potential, state, options) {}

bool StiffModeFilter::Solve(const Eigen::VectorXd& x, const Eigen::VectorXd& rhs,
                            Eigen::VectorXd* y) {
  if (!assembler_.AssembleHessian(x, ProjectedNewtonSolver::TermHessian::kClamped)) return false;
  const Eigen::SparseMatrix<double>& hessian = assembler_.hessian();
  const std::vector<int>& free = assembler_.free_index();
  if (!cholesky_ || analysed_version_ != potential_->structure_version()) {
    cholesky_ = SparseCholesky::Create(
        SparseLibrary::kSuiteSparse,
        ChooseOrdering(potential_->dimension(), static_cast<int>(hessian.rows())));
    if (!cholesky_->Analyze(hessian)) {
      cholesky_.reset();
      return false;
    }
    analysed_version_ = potential_->structure_version();
  }
  if (cholesky_->Factorize(hessian) != SparseCholesky::Result::kSuccess) return false;
  Eigen::VectorXd free_rhs(hessian.rows()), free_y;
  for (int d = 0; d < static_cast<int>(free.size()); ++d) {
    if (free[d] >= 0) free_rhs[free[d]] = rhs[d];
  }
  if (!cholesky_->Solve(free_rhs, &free_y)) return false;
  y->setZero(rhs.size());
  for (int d = 0; d < static_cast<int>(free.size()); ++d) {
    if (free[d] >= 0) (*y)[d] = free_y[free[d]];
  }
  return true;
}

}  // namespace ipstep
