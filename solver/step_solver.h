// Solves one time step: minimises the incremental potential over the free
// nodes' positions with a Ceres optimiser, then recomputes the stopping rule.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "solver/optimizer_options.h"

namespace ipstep {

// One optimiser iteration, for --iterations_log.
struct IterationRecord {
  int iteration = 0;
  double energy = 0.0;         // incremental potential E
  double gradient_norm = 0.0;  // max-norm of Ceres's gradient (in its coordinates)
  double step_size = 0.0;      // |step| (trust region) or line-search step length
  double seconds = 0.0;        // since the start of the solve
  double residual = 0.0;       // stopping measure at this iterate [m/s]
};
using IterationSink = std::function<void(const IterationRecord&)>;

struct StepSolveResult {
  bool converged = false;
  std::string status;        // "converged" or the failure reason
  int iterations = 0;        // optimiser iterations (trust region: including rejected steps)
  int evaluations = 0;       // energy/gradient (or residual/Jacobian) evaluations
  double residual = 0.0;     // stopping measure at the returned x [m/s]
  std::string ceres_report;  // Ceres's BriefReport
};

class StepSolver {
 public:
  virtual ~StepSolver() = default;
  // x: full position vector; constrained nodes already at their prescribed
  // positions, free nodes at the initial guess. On return, the final iterate.
  virtual StepSolveResult Solve(Eigen::VectorXd* x) = 0;
  // How the Newton systems are solved, for the programs' run header, e.g.
  // "CHOLMOD LL^T (SUITE_SPARSE), AMD ordering"; empty without one.
  virtual std::string LinearSolverDescription() const { return ""; }
  // Solves A y = rhs with the positive definite step matrix A that the last
  // Solve factorised (the projected Hessian of an iterate near its result),
  // over the free DOFs of full-length vectors (y is 0 on the others). False
  // when that solve factorised none (solvers without a factorisation: Ceres's,
  // CG; a solve that took no Newton step).
  virtual bool SolveWithLastStepMatrix(const Eigen::VectorXd& rhs, Eigen::VectorXd* y) {
    (void)rhs;
    (void)y;
    return false;
  }
  void set_iteration_sink(IterationSink sink) { sink_ = std::move(sink); }

 protected:
  IterationSink sink_;
};

// Builds the solver for options.optimizer: trust region on a ceres::Problem, or
// line search on a ceres::GradientProblem. The potential and state must outlive
// it (the state supplies masses and node kinds; its positions are not used).
// Throws InputError for invalid options.
std::unique_ptr<StepSolver> MakeStepSolver(IncrementalPotential* potential, const State* state,
                                           const OptimizerOptions& options);

}  // namespace ipstep
