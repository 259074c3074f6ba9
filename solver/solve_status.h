// Turns Ceres's termination into ipstep's verdict: converged only when the
// stopping rule holds at the returned iterate, whatever Ceres reports (a stalled
// line search is reported by Ceres as CONVERGENCE).
#pragma once

#include <string>

#include <ceres/types.h>

#include "solver/step_solver.h"

namespace ipstep {

void ClassifySolve(ceres::TerminationType termination, const std::string& message, int iterations,
                   int max_iterations, double tolerance, StepSolveResult* result);

}  // namespace ipstep
