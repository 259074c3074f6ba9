// newton and dogleg: the terms' cost functions in a ceres::Problem built once
// per scene (one parameter block per node over a buffer that never
// reallocates; constrained nodes constant) and solved with a trust region.
#pragma once

#include <memory>
#include <vector>

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
  std::unique_ptr<StoppingCallback> callback_;
};

}  // namespace ipstep
