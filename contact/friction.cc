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

double FrictionHalf(double w, double eps_v, double* d1, double* d2) {
  const double t = std::abs(w) / eps_v;
  const double one_minus_t = t < 1.0 ? 1.0 - t : 0.0;
  if (d2 != nullptr) *d2 = one_minus_t / eps_v;  // f1'(|w|) / 2
  if (w >= 0.0) {
    // (f0(w) + w) / 2 + eps_v / 6 with f0 = eps_v (t^2 - t^3 / 3) or w - eps_v / 3.
    if (d1 != nullptr) *d1 = 1.0 - 0.5 * one_minus_t * one_minus_t;
    if (t >= 1.0) return w;
    return 0.5 * eps_v * (t * t - t * t * t / 3.0 + t) + eps_v / 6.0;
  }
  // (f0(|w|) - |w|) / 2 + eps_v / 6 = eps_v (1 - t)^3 / 6 for t < 1, else 0.
  const double c3 = one_minus_t * one_minus_t * one_minus_t;
  if (d1 != nullptr) *d1 = 0.5 * one_minus_t * one_minus_t;
  return eps_v * c3 / 6.0;
}

void OneSidedFrictionResidual(double w, double c, double* r, double* dr_dw) {
  const double z = w / c;
  if (z < 0.0) {
    *r = c * std::exp(z);
    if (dr_dw != nullptr) *dr_dw = std::exp(z);
  } else {
    *r = c * (1.0 + z + 0.5 * z * z);
    if (dr_dw != nullptr) *dr_dw = 1.0 + z;
  }
}

void OneSidedFrictionLoss::Evaluate(double q, double rho[3]) const {
  // w(q) and its derivatives w_q, w_qq (q = r^2).
  const double r = std::sqrt(q);
  double w, w_q, w_qq;
  if (!(r > 0.0)) {
    // r underflowed: w far below -eps_v, where P is 0 and flat.
    rho[0] = rho[1] = rho[2] = 0.0;
    return;
  }
  if (r < c_) {
    w = c_ * std::log1p(r / c_ - 1.0);
    w_q = c_ / (2.0 * q);
    w_qq = -c_ / (2.0 * q * q);
  } else {
    const double root = std::sqrt(2.0 * r / c_ - 1.0);  // 1 + z
    w = c_ * (root - 1.0);
    w_q = 1.0 / (2.0 * r * root);
    w_qq = -0.25 * (1.0 / (q * r * root) + 1.0 / (q * c_ * root * root * root));
  }
  double p1, p2;
  const double p0 = FrictionHalf(w, eps_v_, &p1, &p2);
  rho[0] = 2.0 * scale_ * p0;
  if (p1 == 0.0 && p2 == 0.0) {
    // Flat (w <= -eps_v): no force, no curvature (w_q may overflow here).
    rho[1] = rho[2] = 0.0;
    return;
  }
  rho[1] = 2.0 * scale_ * p1 * w_q;
  rho[2] = 2.0 * scale_ * (p2 * w_q * w_q + p1 * w_qq);
  // Where p1 underflows, rho' may be 0 with rho'' > 0, which Ceres's corrector
  // aborts on: WeightedLoss (core/term.h), through which every loss reaches
  // Ceres, drops rho'' there.
}

}  // namespace ipstep
