// lbfgs, bfgs, ncg, gradient_descent: ceres::GradientProblemSolver on the
// FirstOrderPotential (built once per scene).
#pragma once

#include <memory>
#include <vector>

#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>

#include "solver/first_order_potential.h"
#include "solver/step_solver.h"
#include "solver/stopping_callback.h"

namespace ipstep {

class LineSearchSolver : public StepSolver {
 public:
  LineSearchSolver(IncrementalPotential* potential, const State* state,
                   const OptimizerOptions& options);
  StepSolveResult Solve(Eigen::VectorXd* x) override;

 private:
  double MeasureAt(const double* parameters);

  IncrementalPotential* potential_;
  const State* state_;
  OptimizerOptions options_;
  ceres::GradientProblemSolver::Options ceres_options_;
  FirstOrderPotential* function_;  // owned by problem_
  std::unique_ptr<ceres::GradientProblem> problem_;
  std::vector<double> parameters_;
  Eigen::VectorXd gradient_;
  std::unique_ptr<StoppingCallback> callback_;
};

}  // namespace ipstep
