#include "contact/friction.h"

#include <cmath>

namespace ipstep {

double FrictionF0(double y, double eps_v) {
  if (y >= eps_v) return y - eps_v / 3.0;
  return y * y / eps_v - y * y * y / (3.0 * eps_v * eps_v);
}

double FrictionF1(double y, double eps_v) {
  if (y >= eps_v) return 1.0;
  return 2.0 * y / eps_v - y * y / (eps_v * eps_v);
}

void FrictionLoss::Evaluate(double s, double rho[3]) const {
  if (!(s > 0.0)) {
    rho[0] = 0.0;
    rho[1] = 2.0 * scale_ / eps_v_;
    rho[2] = 0.0;
    return;
  }
  const double y = std::sqrt(s);
  rho[0] = 2.0 * scale_ * FrictionF0(y, eps_v_);
  if (y >= eps_v_) {
    rho[1] = scale_ / y;
    rho[2] = -scale_ / (2.0 * y * s);
  } else {
    rho[1] = scale_ * (2.0 / eps_v_ - y / (eps_v_ * eps_v_));
    rho[2] = -scale_ / (2.0 * y * eps_v_ * eps_v_);
  }
}

}  // namespace ipstep
