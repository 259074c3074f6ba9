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

void FrictionResidual(const double* v, int m, double eps_v, double* r, double* dr_dv) {
  double y2 = 0.0;
  for (int k = 0; k < m; ++k) y2 += v[k] * v[k];
  const double y = std::sqrt(y2);
  // psi(y) / y and psi'(y) = f1(y) / psi(y), without dividing by y near 0.
  double psi_over_y, f1_over_y;
  if (y < eps_v) {
    psi_over_y = std::sqrt(2.0 * (1.0 / eps_v - y / (3.0 * eps_v * eps_v)));
    f1_over_y = 2.0 / eps_v - y / (eps_v * eps_v);
  } else {
    psi_over_y = std::sqrt(2.0 * (y - eps_v / 3.0)) / y;
    f1_over_y = 1.0 / y;
  }
  const double dpsi = f1_over_y / psi_over_y;
  for (int k = 0; k < m; ++k) r[k] = psi_over_y * v[k];
  if (dr_dv == nullptr) return;
  // dr/dv = psi/y I + (psi' - psi/y) u u^T, u = v / y.
  const double c = y > 0.0 ? (dpsi - psi_over_y) / y2 : 0.0;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j) dr_dv[i * m + j] = (i == j ? psi_over_y : 0.0) + c * v[i] * v[j];
  }
}

void FrictionLoss::Evaluate(double s, double rho[3]) const {
  rho[0] = scale_ * s;
  rho[1] = scale_;
  rho[2] = 0.0;
}

}  // namespace ipstep
