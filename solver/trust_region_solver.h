// newton, dogleg and gauss_newton: the terms in a ceres::Problem built once
// per scene (one parameter block per node over a buffer that never
// reallocates; constrained nodes constant) and solved with a trust region.
// newton and dogleg hand Ceres each term's projected Newton model
// (solver/newton_model_cost.h); gauss_newton gives it the terms' own cost
// functions and losses, whose J^T J is Ceres's Gauss-Newton model. Terms whose
// Gauss-Newton model is exact (Term::gauss_newton_model) are plain residual
// blocks in all three.
// The Problem is rebuilt only when the potential's terms change (e.g. contact).
// Step filters see every trial point through a ceres::EvaluationCallback and
// veto infeasible ones by failing the evaluation.
//
// Backtracking rejected steps (OptimizerOptions::backtrack_rejected_steps):
// Ceres cannot shorten a step, only shrink its trust region, and from the
// initial radius 1e16 (chosen so Levenberg-Marquardt takes full model steps)
// it shrinks it by 2, 4, 8, ... on consecutive rejections: about ten
// rejections before the radius bites. Two cases made that common:
//  * a model step that ignores a contact not yet within d_hat passes through
//    the obstacle and a step filter refuses it;
//  * friction's stick-slip curvature changes over eps_v, so a Newton step
//    across the transition raises the energy.
// Measured with Gauss-Newton on `slope` (tolerance 1e-6): first-contact steps
// took 41-45 iterations against 7 for the projected Newton reference. So when
// Ceres rejects a trial point, an iteration callback backtracks along the
// rejected step as a projected Newton line search would: from 0.9 of the
// filters' largest feasible fraction (MaxStepSize, continuous collision
// detection) for a refused point, from the minimiser of the quadratic through
// E(0), E'(0) and E(1) (clamped to [0.1, 0.5]) for a point that raised the
// energy; halved until the Armijo rule (1e-4) with a strict decrease holds,
// energies in extended precision. The rejected point itself is tried first:
// Ceres compares costs in double precision and near convergence rejects steps
// whose decrease is below its cost sum's round-off (the precision floor: the
// 20x20 cloth stalled at about 2e-6 m/s; now it converges at 1e-8). The same
// search runs when Ceres ends a solve because a trial's cost equalled the
// current one ("function tolerance"). If a point is found, the callback ends
// the Ceres solve and the solver restarts Ceres from it with a fresh trust
// region (iterations and evaluations add up over restarts; the rejected
// iteration is the one that moved). Otherwise Ceres goes on shrinking its
// radius, as it does after 20 restarts in a row whose first step raised the
// energy again (poor model directions; measured with Gauss-Newton, kept for
// all models). With the Newton model the backtracking keeps newton at the
// Eigen projected Newton's iteration counts (docs/benchmarks.md).
// Not for quasi-static steps (no inertia): their model can be nearly singular
// (a body free to move, with only gravity's tiny curvature: a falling cloth
// draped over a sphere took steps of kilometres, each refused, each cut to a
// tiny advance; cloth_sphere's first quasi-static step failed after 330
// iterations instead of converging in 79 with Gauss-Newton), and there the
// trust region's memory of a small radius is the better globalisation.
// Measured again with the Newton model: backtracking quasi-static steps helped
// two_squares and cloth_box, and made slope and cloth_sphere fail every step.
// One case is kept for quasi-static steps: a full trial step that Ceres
// rejected although the extended-precision energy decreased (the round-off
// of Ceres's double cost): the quasi-static gravity potential carries a
// constant of m |g| H (energies/gravity_potential.h; 15.6 kJ on the 2 m bar
// of bench/quasi_static_bar), whose round-off (2e-12 J) is larger than the
// last Newton decreases, and newton stalled there at 1.6e-4 m/s for ten
// rejected iterations.
#pragma once

#include <memory>
#include <vector>

#include <ceres/evaluation_callback.h>
#include <ceres/iteration_callback.h>
#include <ceres/ordered_groups.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "core/term_hessian.h"
#include "solver/newton_model_cache.h"
#include "solver/step_solver.h"
#include "solver/stopping_callback.h"

namespace ipstep {

class TrustRegionSolver : public StepSolver {
 public:
  TrustRegionSolver(IncrementalPotential* potential, const State* state,
                    const OptimizerOptions& options);
  StepSolveResult Solve(Eigen::VectorXd* x) override;
  std::string LinearSolverDescription() const override;

  ceres::Problem& problem() { return *problem_; }

 private:
  class FilterCallback : public ceres::EvaluationCallback {
   public:
    explicit FilterCallback(TrustRegionSolver* solver) : solver_(solver) {}
    void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override;

   private:
    TrustRegionSolver* solver_;
  };

  // kTrustRegion projection: picks the next models' eigenvalue filter from
  // the last step's fit.
  class FitCallback : public ceres::IterationCallback {
   public:
    explicit FitCallback(TrustRegionSolver* solver) : solver_(solver) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;

   private:
    TrustRegionSolver* solver_;
  };

  // Ends the Ceres solve after a rejected step that could be backtracked.
  class BacktrackCallback : public ceres::IterationCallback {
   public:
    explicit BacktrackCallback(TrustRegionSolver* solver) : solver_(solver) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;

   private:
    TrustRegionSolver* solver_;
  };

  void BuildProblem();
  // The nested-dissection node order (solver/node_ordering.h) when the
  // options ask for it (or choose it: ChooseOrdering in
  // solver/sparse_cholesky.h) and Ceres factorises with SUITE_SPARSE.
  void ChooseOrdering();
  std::shared_ptr<ceres::ParameterBlockOrdering> MakeOrdering();
  double MeasureAt(const double* x);
  // positions_ holds the accepted iterate and rejected_ the rejected trial
  // point: finds the restart point (into restart_point_); false if none.
  bool BacktrackRejectedStep();

  IncrementalPotential* potential_;
  const State* state_;
  OptimizerOptions options_;
  ceres::Solver::Options ceres_options_;
  Eigen::VectorXd positions_;  // parameter memory: sized once, never reallocated
  Eigen::VectorXd gradient_;
  std::vector<std::unique_ptr<ceres::CostFunction>> weighted_costs_;
  std::vector<std::unique_ptr<ceres::LossFunction>> weighted_losses_;
  std::unique_ptr<ceres::Problem> problem_;
  int built_version_ = -1;
  std::vector<int> node_order_;   // empty: Ceres's own ordering (AMD)
  bool veto_ = false;             // the current trial point was rejected by a step filter
  bool rejected_vetoed_ = false;  // rejected_ was refused by a step filter
  bool trial_since_callback_ = false;
  Eigen::VectorXd rejected_;       // the last trial point
  Eigen::VectorXd restart_point_;  // where Ceres restarts after backtracking
  Eigen::VectorXd trial_;
  int backtrack_evaluations_ = 0;
  // Backtracks to a fraction < 1 of a step that raised the energy since
  // Ceres's last successful step; at kMaxShortBacktracks they stop.
  int short_backtracks_ = 0;
  static constexpr int kMaxShortBacktracks = 20;
  FilterCallback filter_callback_{this};
  BacktrackCallback backtrack_callback_{this};
  FitCallback fit_callback_{this};
  // newton, dogleg: the terms' models for the point Ceres evaluates, and the
  // eigenvalue filter they are projected with.
  std::unique_ptr<NewtonModelCache> cache_;
  EigenvalueFilter filter_ = EigenvalueFilter::kClamp;
  std::unique_ptr<StoppingCallback> callback_;
};

}  // namespace ipstep
