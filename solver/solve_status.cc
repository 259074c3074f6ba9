#include "solver/solve_status.h"

#include <cmath>

namespace ipstep {

void ClassifySolve(ceres::TerminationType termination, const std::string& message, int iterations,
                   int max_iterations, double tolerance, StepSolveResult* result) {
  result->converged = std::isfinite(result->residual) && result->residual <= tolerance;
  if (result->converged) {
    result->status = "converged";
    return;
  }
  switch (termination) {
    case ceres::NO_CONVERGENCE:
      result->status = iterations >= max_iterations
                           ? "iteration limit (" + std::to_string(max_iterations) + ")"
                           : "time limit: " + message;
      break;
    case ceres::FAILURE:
      result->status = "optimizer failure: " + message;
      break;
    case ceres::CONVERGENCE:
    case ceres::USER_SUCCESS:
      result->status = "stalled: " + message;
      break;
    default:
      result->status = "aborted: " + message;
      break;
  }
  if (!std::isfinite(result->residual)) result->status += " (residual not finite)";
}

}  // namespace ipstep
