// newton and dogleg: the terms' cost functions in a ceres::Problem built once
// per scene (one parameter block per node over a buffer that never
// reallocates; constrained nodes constant) and solved with a trust region.
// The Problem is rebuilt only when the potential's terms change (e.g. contact).
// Step filters see every trial point through a ceres::EvaluationCallback and
// veto infeasible ones by failing the evaluation.
#pragma once

#include <memory>
#include <vector>

#include <ceres/evaluation_callback.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "solver/step_solver.h"
#include "solver/stopping_callback.h"

namespace ipstep {

class TrustRegionSolver : public StepSolver {
 public:
  TrustRegionSolver(IncrementalPotential* potential, const State* state,
                    const OptimizerOptions& options);
  StepSolveResult Solve(Eigen::VectorXd* x) override;

  ceres::Problem& problem() { return *problem_; }

 private:
  class FilterCallback : public ceres::EvaluationCallback {
   public:
    explicit FilterCallback(TrustRegionSolver* solver) : solver_(solver) {}
    void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override;

   private:
    TrustRegionSolver* solver_;
  };

  void BuildProblem();
  double MeasureAt(const double* x);

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
  bool veto_ = false;  // the current trial point was rejected by a step filter
  FilterCallback filter_callback_{this};
  std::unique_ptr<StoppingCallback> callback_;
};

}  // namespace ipstep
