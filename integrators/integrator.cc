#include "integrators/integrator.h"

#include <algorithm>

namespace ipstep {

double Integrator::LargestFreeNodeChange(const State& state, const Eigen::VectorXd& before,
                                         const Eigen::VectorXd& after) {
  const int dim = state.dimension;
  double worst = 0.0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (!state.is_free(i)) continue;
    worst = std::max(worst, (after.segment(dim * i, dim) - before.segment(dim * i, dim)).norm());
  }
  return worst;
}

double Integrator::LocalError(const State& before, const State& after, double h) const {
  return 0.5 * h * LargestFreeNodeChange(after, before.v, after.v);
}

}  // namespace ipstep
