#include "core/stopping_rule.h"

#include <cmath>
#include <limits>

namespace ipstep {

double StoppingMeasure(const Eigen::VectorXd& gradient, const State& s, const StepContext& c) {
  const int dim = s.dimension;
  double worst = 0.0;
  for (int i = 0; i < s.num_nodes(); ++i) {
    if (!s.is_free(i)) continue;
    const double norm = gradient.segment(dim * i, dim).norm();
    if (!std::isfinite(norm)) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, norm / s.mass[i]);
  }
  return c.time_step * worst / c.potential_weight;
}

}  // namespace ipstep
