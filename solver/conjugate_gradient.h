// projected_newton's iterative option (--linear_solver=CG): the Newton system
// H p = -g solved inexactly by conjugate gradients preconditioned with an
// incomplete Cholesky factorisation of H (Eigen's IncompleteCholesky with AMD
// ordering and its diagonal shift for robustness), to a relative residual
// |H p + g| <= eta |g| that the caller sets per iteration (inexact Newton:
// the forcing term, solver/projected_newton_solver.h). No factorisation is
// stored: the memory is the matrix's and the preconditioner's, not the
// Cholesky factor's fill.
#pragma once

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

namespace ipstep {

class PreconditionedConjugateGradient {
 public:
  // Solves lower's symmetric matrix (lower triangle stored) times x = rhs.
  // False if the preconditioner fails or the result is not finite; a solve
  // that stops at the iteration limit before the tolerance still returns its
  // iterate (a descent direction for a positive definite matrix).
  bool Solve(const Eigen::SparseMatrix<double>& lower, const Eigen::VectorXd& rhs,
             double relative_tolerance, Eigen::VectorXd* x);
  // CG iterations of all solves.
  long iterations() const { return iterations_; }

 private:
  using Preconditioner = Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>;
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower, Preconditioner> cg_;
  long iterations_ = 0;
};

}  // namespace ipstep
