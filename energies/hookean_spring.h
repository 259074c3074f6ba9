// Hookean spring: e = k/2 (|d| - L)^2 with d = x_j - x_i.
// Residual r = sqrt(k) (|d| - L); Gauss-Newton curvature k n n^T (n = d/|d|) is
// the PSD part of the exact Hessian k n n^T + k (1 - L/|d|)(I - n n^T), whose
// second part (negative when compressed) the Newton models add from
// Hess r = sqrt(k) (I - n n^T) / |d|.
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

  static constexpr bool kPairDifference = true;

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    using std::sqrt;
    const T d2 = SquaredDistance<kDim>(xi, xj);
    if (!(d2 > T(0.0))) return false;
    residual[0] = sqrt_k * (sqrt(d2) - rest_length);
    return true;
  }

  bool ResidualCurvature(const double* const* x, const double* c, double* curvature) const {
    return RadialResidualCurvature<kDim>(
        x[0], x[1], c[0],
        [this](double, double* r1, double* r2) {
          *r1 = sqrt_k;
          *r2 = 0.0;
        },
        curvature);
  }

  double sqrt_k;
  double rest_length;
};

}  // namespace ipstep
