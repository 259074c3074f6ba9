#include "solver/step_solver.h"

#include "solver/line_search_solver.h"
#include "solver/projected_newton_solver.h"
#include "solver/trust_region_solver.h"

namespace ipstep {

std::unique_ptr<StepSolver> MakeStepSolver(IncrementalPotential* potential, const State* state,
                                           const OptimizerOptions& options) {
  switch (FamilyOf(options.optimizer)) {
    case OptimizerFamily::kTrustRegion:
      return std::make_unique<TrustRegionSolver>(potential, state, options);
    case OptimizerFamily::kEigenNewton:
      return std::make_unique<ProjectedNewtonSolver>(potential, state, options);
    case OptimizerFamily::kLineSearch:
      break;
  }
  return std::make_unique<LineSearchSolver>(potential, state, options);
}

}  // namespace ipstep
