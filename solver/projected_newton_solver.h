// projected_newton: ipstep's own projected Newton method on Eigen, not Ceres.
// The yardstick for what Ceres itself costs (docs/benchmarks.md), and an
// optimiser of its own (`--optimizer=projected_newton`). A StepSolver over the
// same IncrementalPotential terms with the same stopping rule
// (core/stopping_rule.h).
//
// Per iteration: every term's projected Newton model (core/term_hessian.h:
// exact Hessian from analytic curvature or central differences of the term's
// Jacobian, eigenvalues floored at 1e-8 of the term's curvature scale; terms
// with a Gauss-Newton model as Ceres builds it) is assembled into a sparse
// matrix over the free degrees of freedom, factorised with
// Eigen::SimplicialLDLT (AMD ordering, symbolic analysis once per term
// structure) and the direction searched with Armijo backtracking (c = 1e-4,
// halving) on the energy summed in extended precision. Trial points the
// potential cannot evaluate (step filters, core/step_filter.h) are
// backtracked from; with step filters the first trial step is capped at 0.9 of
// MaxStepSize. A singular matrix (quasi-static, free rigid modes) gets a
// growing multiple of the identity on its diagonal.
//
// With OptimizerOptions::hessian_projection = kWhenIndefinite, each iteration
// first assembles the exact Hessian (terms unprojected; Gauss-Newton terms
// keep their model) and factorises it once: if LDL^T finds it positive
// definite (every pivot > 0) its Newton step is taken, else the projected
// model is assembled and used as above. Per-term projection discards negative
// curvature that the sum (inertia M/h^2 plus all terms) does not have, and
// then converges only linearly (compressed springs, buckling strips); the
// exact step keeps Newton's quadratic convergence wherever the sum is
// definite. Measured in docs/benchmarks.md ("Hessian projection").
//
// The projected model is the same model Ceres's newton and dogleg receive
// (solver/newton_model_cost.h): the two differ in globalisation (trust region
// against line search) and linear algebra (CXSparse Cholesky of J^T J against
// Eigen's LDL^T of the assembled matrix), not in the Newton model.
#pragma once

#include <vector>

#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "core/term_hessian.h"
#include "solver/sparse_cholesky.h"
#include "solver/step_solver.h"

namespace ipstep {

class ProjectedNewtonSolver : public StepSolver {
 public:
  // Seconds spent per phase, accumulated over all solves (for reports).
  struct Timings {
    double gradient = 0.0;   // energy + gradient (stopping measure)
    double hessian = 0.0;    // per-term models, projection, assembly
    double factorize = 0.0;  // numeric factorisation + solve
    double analyze = 0.0;    // symbolic analysis (once per structure)
    double line_search = 0.0;
  };

  // Uses options.tolerance, max_iterations, time_limit and hessian_projection.
  // Throws InputError
  // for invalid values.
  ProjectedNewtonSolver(IncrementalPotential* potential, const State* state,
                        const OptimizerOptions& options);
  StepSolveResult Solve(Eigen::VectorXd* x) override;

  // Assembles the projected (project = false: exact) Hessian over the free
  // DOFs at full positions x (lower triangle). False if a term cannot be
  // evaluated. Public for tests and micro-benchmarks.
  bool AssembleHessian(const Eigen::VectorXd& x, bool project = true);
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }
  // Free DOF index of each DOF (-1 for constrained ones).
  const std::vector<int>& free_index() const { return free_index_; }
  const Timings& timings() const { return timings_; }
  // Iterations whose direction came from the exact Hessian (kWhenIndefinite)
  // and from the projected one, over all solves.
  long exact_directions() const { return exact_directions_; }
  long projected_directions() const { return projected_directions_; }

 private:
  void BuildStructure();
  // Adds the term's projected (or exact) model Hessian at x into hessian_
  // through its slots.
  bool AddTermHessian(const Term& term, const double* x, double weight, const int* slots,
                      bool project);
  // The symbolic analysis of hessian_'s pattern, once per structure.
  void EnsureAnalyzed();
  // Factorises hessian_ as it is; true if it is positive definite (the
  // Cholesky factorisation succeeded).
  bool FactorizePositiveDefinite();
  // Factorises the Hessian (regularising if needed) and solves H p = -g.
  bool ComputeDirection(const Eigen::VectorXd& gradient, Eigen::VectorXd* direction);
  // Factorises the Hessian as it is; if it is positive definite, solves
  // H p = -g and returns true.
  bool DefiniteDirection(const Eigen::VectorXd& gradient, Eigen::VectorXd* direction);
  // The factorisation's solve for -g, scattered to every DOF (0 on
  // constrained ones). False if not finite.
  bool SolveFactorised(const Eigen::VectorXd& gradient, Eigen::VectorXd* direction);

  IncrementalPotential* potential_;
  const State* state_;
  double tolerance_;
  int max_iterations_;
  HessianProjection projection_;
  long exact_directions_ = 0;
  long projected_directions_ = 0;
  double time_limit_;
  Timings timings_;

  int built_version_ = -1;
  int num_free_ = 0;
  std::vector<int> free_index_;  // per DOF: index among free DOFs, or -1
  // Per term: offset into slots_, which holds for each lower-triangle local
  // pair (a >= b, both free) the index into hessian_.valuePtr(), or -1.
  std::vector<int> slot_offset_;
  std::vector<int> slots_;
  std::vector<int> diagonal_slots_;
  Eigen::SparseMatrix<double> hessian_;  // column-major, lower triangle
  SparseLibrary library_ = SparseLibrary::kSuiteSparse;
  FillOrdering ordering_ = FillOrdering::kAutomatic;
  std::unique_ptr<SparseCholesky> cholesky_;
  FillOrdering cholesky_ordering_ = FillOrdering::kAutomatic;
  bool analyzed_ = false;

  // Scratch.
  TermModelEvaluator evaluator_;
  TermModel model_;
  ProjectedHessian projected_;
  TermMatrix local_hessian_;
  TermMatrix scaled_;
  std::vector<const double*> parameters_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd trial_;
  Eigen::VectorXd free_rhs_;
  Eigen::VectorXd free_step_;
};

}  // namespace ipstep
