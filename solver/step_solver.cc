#include "solver/step_solver.h"

#include "solver/line_search_solver.h"
#include "solver/trust_region_solver.h"

namespace ipstep {

std::unique_ptr<StepSolver> MakeStepSolver(IncrementalPotential* potential, const State* state,
                                           const OptimizerOptions& options) {
  if (IsTrustRegion(options.optimizer)) {
    return std::make_unique<TrustRegionSolver>(potential, state, options);
  }
  return std::make_unique<LineSearchSolver>(potential, state, options);
}

}  // namespace ipstep
