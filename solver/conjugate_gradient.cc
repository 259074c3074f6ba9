#include "solver/conjugate_gradient.h"

#include <algorithm>

namespace ipstep {

bool PreconditionedConjugateGradient::Solve(const Eigen::SparseMatrix<double>& lower,
                                            const Eigen::VectorXd& rhs, double relative_tolerance,
                                            Eigen::VectorXd* x) {
  cg_.setTolerance(std::max(relative_tolerance, 1e-14));
  cg_.setMaxIterations(std::max<Eigen::Index>(100, 4 * lower.rows()));
  cg_.compute(lower);
  if (cg_.preconditioner().info() != Eigen::Success) return false;
  *x = cg_.solve(rhs);
  iterations_ += cg_.iterations();
  return x->allFinite();
}

}  // namespace ipstep
