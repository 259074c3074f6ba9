#include "integrators/integrator.h"

#include <algorithm>

namespace ipstep {

double Integrator::LargestFreeNodeNorm(const State& state, const Eigen::VectorXd& v) {
  const int dim = state.dimension;
  double worst = 0.0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (state.is_free(i)) worst = std::max(worst, v.segment(dim * i, dim).norm());
  }
  return worst;
}

void Integrator::LocalErrorVector(const State& before, const State& after, double h,
                                  Eigen::VectorXd* error) const {
  *error = 0.5 * h * (after.v - before.v);
}

double Integrator::LocalError(const State& before, const State& after, double h) const {
  Eigen::VectorXd error;
  LocalErrorVector(before, after, h, &error);
  return LargestFreeNodeNorm(after, error);
}

}  // namespace ipstep
