// Hookean spring: e = k/2 (|d| - L)^2 with d = x_j - x_i.
// Residual r = sqrt(k) (|d| - L); Gauss-Newton curvature k n n^T (n = d/|d|) is
// the PSD part of the exact Hessian k n n^T + k (1 - L/|d|)(I - n n^T).
// A collapsed spring (|d| = 0) has no direction: evaluation fails there.
#pragma once

#include <cmath>

#include <ceres/jet.h>

#include "energies/spring_length.h"

namespace ipstep {

template <int kDim>
struct HookeanSpring {
  HookeanSpring(double stiffness, double rest_length)
      : sqrt_k(std::sqrt(stiffness)), rest_length(rest_length) {}

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    using std::sqrt;
    const T d2 = SquaredDistance<kDim>(xi, xj);
    if (!(d2 > T(0.0))) return false;
    residual[0] = sqrt_k * (sqrt(d2) - rest_length);
    return true;
  }

  double sqrt_k;
  double rest_length;
};

}  // namespace ipstep
