// Reference projected Newton written directly on Eigen (no Ceres solver): the
// yardstick that shows what Ceres itself costs (docs/benchmarks.md). It is a
// StepSolver over the same IncrementalPotential terms with the same stopping
// rule (core/stopping_rule.h); the benchmark programs swap it into a Simulation
// with Simulation::ReplaceStepSolver. Not offered by the ipstep program.
//
// Per term, with residual r, Jacobian J, loss rho and family weight w, the
// Hessian of e = w/2 rho(|r|^2) is
//   H_e = w (rho' J^T J + 2 rho'' (J^T r)(J^T r)^T + rho' sum_k r_k Hess(r_k)).
// sum_k r_k Hess(r_k) comes from central differences of the term's analytic
// (autodiff) Jacobian: column j = (J(x + d e_j) - J(x - d e_j))^T r / (2 d),
// d = 1e-6 max(1, |x_j|). H_e is therefore exact up to O(1e-8) finite-difference
// error of analytic Jacobians, not exact to round-off. Inertia terms are linear
// in x by definition (core/term.h), so their second-order part is skipped.
// Each H_e is projected to the PSD cone (eigen-decomposition, negative
// eigenvalues clamped to 0) and assembled into a sparse matrix over the free
// degrees of freedom, factorised with Eigen::SimplicialLDLT whose symbolic
// analysis (AMD ordering) is done once per term structure. The Newton direction
// is searched with Armijo backtracking (c = 1e-4, halving) on the energy summed
// in extended precision; trial points the potential cannot evaluate (step
// filters, core/step_filter.h) are backtracked from, and with step filters the
// first trial step is capped by MaxStepSize (times 0.9).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "solver/step_solver.h"

namespace ipstep {

struct ProjectedNewtonOptions {
  double tolerance = 1e-6;  // stopping rule [m/s]
  int max_iterations = 100;
  double armijo = 1e-4;
  int max_backtracks = 60;
  double fd_relative_step = 1e-6;
  bool project_to_psd = true;  // false: the (FD) Hessian as is, regularised if indefinite
};

class ProjectedNewtonSolver : public StepSolver {
 public:
  // Largest term handled (nodes x dimension parameters, residuals): per-term
  // kernels work on fixed-capacity matrices without heap allocation.
  static constexpr int kMaxTermParameters = 24;
  static constexpr int kMaxTermResiduals = 24;

  // Seconds spent per phase, accumulated over all solves (for reports).
  struct Timings {
    double gradient = 0.0;   // energy + gradient (stopping measure)
    double hessian = 0.0;    // per-term Hessians, projection, assembly
    double factorize = 0.0;  // numeric factorisation + solve
    double analyze = 0.0;    // symbolic analysis (once per structure)
    double line_search = 0.0;
  };

  ProjectedNewtonSolver(IncrementalPotential* potential, const State* state,
                        const ProjectedNewtonOptions& options);
  StepSolveResult Solve(Eigen::VectorXd* x) override;

  // Assembles the projected Hessian over the free DOFs at full positions x
  // (lower triangle). False if a term cannot be evaluated. Public for tests and
  // micro-benchmarks.
  bool AssembleHessian(const Eigen::VectorXd& x);
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }
  int num_free_dofs() const { return num_free_; }
  // Terms whose second-order part was dropped (not evaluable beside x).
  long fd_fallbacks() const { return fd_fallbacks_; }
  const Timings& timings() const { return timings_; }

 private:
  using TermMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxTermParameters,
                                   kMaxTermParameters>;
  using TermVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxTermParameters, 1>;

  void BuildStructure();
  // Adds the term's projected Hessian at full positions x into hessian_ through
  // the term's slots.
  bool TermHessian(const Term& term, const double* x, double weight, const int* slots);
  // Factorises the Hessian (regularising if needed) and solves H p = -g.
  bool ComputeDirection(const Eigen::VectorXd& gradient, Eigen::VectorXd* direction);

  IncrementalPotential* potential_;
  const State* state_;
  ProjectedNewtonOptions options_;
  Timings timings_;
  long fd_fallbacks_ = 0;

  int built_version_ = -1;
  int num_free_ = 0;
  std::vector<int> free_index_;  // per DOF: index among free DOFs, or -1
  // Per term: offset into slots_, which holds for each lower-triangle local
  // pair (a >= b, both free) the index into hessian_.valuePtr(), or -1.
  std::vector<int> slot_offset_;
  std::vector<int> slots_;
  std::vector<int> diagonal_slots_;
  Eigen::SparseMatrix<double> hessian_;  // column-major, lower triangle
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt_;
  bool analyzed_ = false;

  // Scratch.
  Eigen::VectorXd gradient_;
  Eigen::VectorXd trial_;
  Eigen::VectorXd free_rhs_;
  Eigen::VectorXd free_step_;
  std::vector<double> local_x_;
  std::vector<double> residuals_;
  std::array<double, kMaxTermResiduals> fd_residuals_;
  std::vector<double> jacobian_blocks_;
  std::vector<double*> jacobian_pointers_;
  std::vector<const double*> parameter_pointers_;
  TermMatrix jacobian_;
  TermMatrix jacobian_fd_;
  TermMatrix local_hessian_;
  TermMatrix second_order_;
  TermVector jtr_;
  TermVector column_;
  TermVector eigenvalues_;
  Eigen::SelfAdjointEigenSolver<TermMatrix> eigen_;
};

}  // namespace ipstep
