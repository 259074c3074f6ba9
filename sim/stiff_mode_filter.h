// The filtered local error estimate of an adaptive step (sim/run_trajectory.h):
// the raw estimate e of the integrator (Integrator::LocalErrorVector) with the
// modes that the step does not resolve taken out,
//   e_f = H^-1 M e,
// H = M + c K the Hessian of the step's incremental potential at its result
// (c = h^2 for backward Euler, beta h^2 for Newmark; K the stiffness of the
// potentials, barriers and the damping's h D included), M the mass matrix.
//
// Why: e measures h/2 |dv| (backward Euler) or h^2 |beta - 1/6| |da|
// (Newmark), and a stiff mode of frequency w (an elastic element's, the
// barrier's) with amplitude A has |a| = w^2 A: its share of e grows like
// (w h)^2 A while the position error it can cause is bounded by A (backward
// Euler damps it; Newmark keeps its amplitude). On a mode of frequency w the
// filter multiplies e by 1 / (1 + c w^2): the resolved modes (c w^2 << 1)
// keep their estimate, an unresolved one is left at its amplitude. This is
// the filtered estimate of stiff solvers (Shampine 1984; Hairer and Wanner,
// Solving ODEs II, IV.8, (8.20) and (8.21): err = (I - h gamma J)^-1 err for
// SDIRK/Radau codes), here with the step's own matrix M + c K, which the
// Newton solve has (near) its result anyway.
//
// The Hessian is the potential's projected one (every term's eigenvalues
// clamped to >= 0: core/term_hessian.h), so H >= M > 0 on the free DOFs and
// the solve always has an answer; it is assembled and factorised once per
// estimate (a sparse Cholesky, solver/sparse_cholesky.h: about one Newton
// iteration's linear algebra). Simulation::LocalError uses this class only
// when the step solver kept no factorisation of its own
// (StepSolver::SolveWithLastStepMatrix: projected_newton keeps its last
// Newton iteration's, of an iterate near the result).
#pragma once

#include <memory>

#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "solver/projected_newton_solver.h"
#include "solver/sparse_cholesky.h"

namespace ipstep {

class StiffModeFilter {
 public:
  // `potential` and `state` outlive the filter; the potential's context holds
  // the weights of the step being judged. `options`: the simulation's (its
  // threads).
  StiffModeFilter(IncrementalPotential* potential, const State* state,
                  const OptimizerOptions& options);

  // Solves H(x) y = rhs over the free DOFs of full-length vectors (y is 0 on
  // the others): StepSolver::SolveWithLastStepMatrix's contract, with H
  // assembled and factorised at x. False when the Hessian cannot be
  // assembled at x or the factorisation fails.
  bool Solve(const Eigen::VectorXd& x, const Eigen::VectorXd& rhs, Eigen::VectorXd* y);

 private:
  const IncrementalPotential* potential_;
  ProjectedNewtonSolver assembler_;  // assembles H (no solve)
  std::unique_ptr<SparseCholesky> cholesky_;
  // The potential's structure_version when cholesky_ analysed H's pattern
  // (the pattern follows the terms: the assembler rebuilds it on a change).
  int analysed_version_ = -1;
};

}  // namespace ipstep
