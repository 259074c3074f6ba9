#include "contact/barrier.h"

#include <cmath>
#include <limits>

namespace ipstep {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
}  // namespace

double Barrier(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  if (d <= 0.0) return kInfinity;
  const double u = d_hat - d;
  return -u * u * std::log1p(-u / d_hat);
}

double BarrierDerivative(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  if (d <= 0.0) return -kInfinity;
  const double u = d_hat - d;
  return 2.0 * u * std::log1p(-u / d_hat) - u * u / d;
}

double BarrierSecondDerivative(double d, double d_hat) {
  if (d >= d_hat) return 0.0;
  if (d <= 0.0) return kInfinity;
  const double u = d_hat - d;
  const double r = u / d;
  return -2.0 * std::log1p(-u / d_hat) + 4.0 * r + r * r;
}

void BarrierLoss::Evaluate(double s, double rho[3]) const {
  if (!(s > 0.0)) {
    rho[0] = rho[1] = rho[2] = 0.0;
    return;
  }
  const double u = std::sqrt(s);
  const double d = d_hat_ - u;
  const double scale = *kappa_ * weight_;
  if (!(d > 0.0)) {
    // Only reachable through a residual the cost function should have refused.
    rho[0] = rho[1] = rho[2] = kInfinity;
    return;
  }
  const double log_ratio = std::log1p(-u / d_hat_);  // ln(d / d_hat)
  rho[0] = -2.0 * scale * s * log_ratio;
  rho[1] = scale * (-2.0 * log_ratio + u / d);
  rho[2] = 0.5 * scale * (3.0 / (u * d) + 1.0 / (d * d));
}

}  // namespace ipstep
