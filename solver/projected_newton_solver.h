// projected_newton: ipstep's own Newton method, not Ceres.
// The yardstick for what Ceres itself costs (docs/benchmarks.md), and an
// optimiser of its own (`--optimizer=projected_newton`). A StepSolver over the
// same IncrementalPotential terms with the same stopping rule
// (core/stopping_rule.h).
//
// Per iteration: every term's projected Newton model (core/term_hessian.h:
// exact Hessian from analytic curvature or central differences of the term's
// Jacobian, eigenvalues floored at 1e-8 of the term's curvature scale; terms
// with a Gauss-Newton model as Ceres builds it) is assembled into a sparse
// matrix over the free degrees of freedom, factorised by the sparse Cholesky
// of solver/sparse_cholesky.h (CHOLMOD LL^T by default, Eigen's SimplicialLDLT
// with sparse_library EIGEN_SPARSE; symbolic analysis once per term
// structure) or solved by conjugate gradients (linear_solver CG), and the
// direction searched with Armijo backtracking (c = 1e-4,
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
// against line search) and linear algebra (Ceres's sparse Cholesky of J^T J
// against the factorisation of the assembled matrix), not in the Newton model.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "core/term_hessian.h"
#include "solver/conjugate_gradient.h"
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
  std::string LinearSolverDescription() const override;
  bool SolveWithLastStepMatrix(const Eigen::VectorXd& rhs, Eigen::VectorXd* y) override;

  // How a term's Hessian enters the assembled matrix: exact, or projected
  // with eigenvalues clamped or by their magnitude (core/term_hessian.h).
  enum class TermHessian : char { kExact, kClamped, kAbsolute };
  // Assembles the Hessian over the free DOFs at full positions x (lower
  // triangle), every term's as `kind`; with `projected_terms` (one flag per
  // term), the flagged terms clamped and the others exact. The terms' models
  // are computed on the potential's thread pool and summed in term order
  // (the same matrix for any number of threads). False if a term cannot be
  // evaluated. Public for tests and micro-benchmarks.
  bool AssembleHessian(const Eigen::VectorXd& x, TermHessian kind,
                       const std::vector<char>* projected_terms = nullptr);
  // project: kClamped, else kExact.
  bool AssembleHessian(const Eigen::VectorXd& x, bool project = true) {
    return AssembleHessian(x, project ? TermHessian::kClamped : TermHessian::kExact);
  }
  const Eigen::SparseMatrix<double>& hessian() const { return hessian_; }
  // Free DOF index of each DOF (-1 for constrained ones).
  const std::vector<int>& free_index() const { return free_index_; }
  const Timings& timings() const { return timings_; }
  // Iterations whose direction came from a matrix with some terms exact
  // (kWhenIndefinite, kProgressive) and from a fully projected one, over
  // all solves; term models projected (kProgressive: terms projected, of
  // all terms' models computed).
  long exact_directions() const { return exact_directions_; }
  long projected_directions() const { return projected_directions_; }
  long projected_terms() const { return projected_terms_; }
  // Iterations whose terms were projected with the absolute-value filter
  // (kAbsolute, kTrustRegion).
  long absolute_directions() const { return absolute_directions_; }
  // CG iterations of all solves (--linear_solver=CG).
  long cg_iterations() const { return cg_.iterations(); }
  long term_models() const { return term_models_; }

 private:
  // Per-thread memory of the term models.
  struct Scratch {
    TermModelEvaluator evaluator;
    TermModel model;
    ProjectedHessian projected;
    TermMatrix local;
    TermMatrix scaled;
    std::vector<const double*> parameters;
  };
  // A factorisation of this solve's (SolveWithLastStepMatrix).
  bool factorised_in_solve_ = false;
  void BuildStructure();
  // The term's model Hessian at x, weighted, as `kind`, into its lower
  // triangle at local_values_ + slot_offset_[t].
  bool TermLocalHessian(int t, const double* x, double weight, TermHessian kind, Scratch* scratch);
  // The direction of one iteration (projection_), into direction; false if
  // no model could be evaluated or factorised (status set).
  bool NewtonDirection(const Eigen::VectorXd& x, Eigen::VectorXd* direction, std::string* status);
  // kProgressive: flags the terms at a node whose share of the stopping
  // measure is above `threshold` (adding to projected_set_); returns those
  // newly flagged.
  std::vector<int> GrowProjectedSet(double threshold);
  // kProgressive: the direction of the partly projected Hessian, projecting
  // more terms while it is not positive definite; false if it stays so
  // (evaluated: false if a term could not be evaluated).
  bool ProgressiveDirection(const Eigen::VectorXd& x, Eigen::VectorXd* direction, bool* evaluated);
  // Recomputes the listed terms' local matrices as `kind` and sums all again.
  bool UpdateTermHessians(const Eigen::VectorXd& x, const std::vector<int>& terms,
                          TermHessian kind);
  // hessian_ = the sum of the terms' local matrices, in term order.
  bool ScatterTermHessians();
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
  long projected_terms_ = 0;
  long term_models_ = 0;
  long absolute_directions_ = 0;
  // kTrustRegion: the last step's model fit (actual / predicted decrease).
  double model_fit_ = 1.0;
  // kProgressive: the terms projected in this solve.
  std::vector<char> projected_set_;
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
  // --linear_solver=CG: the iterative solver and this iteration's forcing
  // term (relative residual of the Newton system).
  bool use_cg_ = false;
  PreconditionedConjugateGradient cg_;
  double forcing_ = 0.1;
  double initial_residual_ = 0.0;
  bool analyzed_ = false;

  // Scratch: per thread, and the terms' local matrices (slots_'s layout).
  std::vector<Scratch> scratch_;
  std::vector<double> local_values_;
  std::vector<char> term_ok_;
  Eigen::VectorXd gradient_;
  Eigen::VectorXd trial_;
  Eigen::VectorXd free_rhs_;
  Eigen::VectorXd free_step_;
};

}  // namespace ipstep
