#include "contact/adaptive_kappa.h"

#include <algorithm>

#include "contact/barrier.h"

namespace ipstep {

AdaptiveKappa::AdaptiveKappa(double fixed, double node_stiffness, double mean_weight, double d_hat)
    : d_hat_(d_hat),
      kappa_min_(node_stiffness / (mean_weight * BarrierSecondDerivative(0.5 * d_hat, d_hat))),
      kappa_max_(kRange * kappa_min_),
      adaptive_(!(fixed > 0.0)),
      kappa_(adaptive_ ? kappa_min_ : fixed) {}

void AdaptiveKappa::Update(double gap,
                           const std::function<void(Eigen::VectorXd*)>& barrier_gradient,
                           const std::function<bool(Eigen::VectorXd*)>& rest_gradient) {
  if (!adaptive_) return;
  if (!balanced_ && gap < d_hat_) {
    Eigen::VectorXd g_b, g_e;
    barrier_gradient(&g_b);
    const bool ok = rest_gradient(&g_e);
    const double norm2 = g_b.squaredNorm();
    if (ok && norm2 > 0.0) {
      kappa_ = std::clamp(-g_b.dot(g_e) / norm2, kappa_min_, kappa_max_);
      balanced_ = true;
    }
  } else if (gap < kShrinkingGapFraction * d_hat_ && gap < previous_gap_) {
    kappa_ = std::min(2.0 * kappa_, kappa_max_);
  }
  previous_gap_ = gap;
}

}  // namespace ipstep
