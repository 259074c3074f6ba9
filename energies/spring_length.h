// Shared helpers of the spring energies: |x_j - x_i|^2 for autodiff types, and
// the second derivatives of a residual that depends on the length only.
#pragma once

#include <cmath>

namespace ipstep {

template <int kDim, typename T>
T SquaredDistance(const T* xi, const T* xj) {
  T d2 = T(0.0);
  for (int k = 0; k < kDim; ++k) {
    const T dk = xj[k] - xi[k];
    d2 += dk * dk;
  }
  return d2;
}

// For a residual r(l) of the length l = |d|, d = x_j - x_i (a pair-difference
// term, core/term.h), writes c Hess_d r = c (r''(l) n n^T + r'(l)/l (I - n n^T)),
// n = d / l, row-major kDim x kDim. `derivatives(l, &r1, &r2)` sets r'(l) and
// r''(l). False at l = 0 (no direction).
template <int kDim, class Derivatives>
bool RadialResidualCurvature(const double* xi, const double* xj, double c,
                             const Derivatives& derivatives, double* curvature) {
  double d[kDim];
  for (int k = 0; k < kDim; ++k) d[k] = xj[k] - xi[k];
  const double length = std::sqrt(SquaredDistance<kDim>(xi, xj));
  if (!(length > 0.0)) return false;
  double r1 = 0.0, r2 = 0.0;
  derivatives(length, &r1, &r2);
  const double along = c * r2, across = c * r1 / length;
  for (int a = 0; a < kDim; ++a) {
    for (int b = 0; b < kDim; ++b) {
      const double nn = d[a] * d[b] / (length * length);
      curvature[a * kDim + b] = along * nn + across * ((a == b ? 1.0 : 0.0) - nn);
    }
  }
  return true;
}

}  // namespace ipstep
