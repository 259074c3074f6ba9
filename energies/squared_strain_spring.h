// Squared-strain spring: e = k/2 L^2 (|d|^2/L^2 - 1)^2, d = x_j - x_i.
// Residual r = sqrt(k) L (|d|^2/L^2 - 1): polynomial, smooth even at |d| = 0,
// with Hess r = 2 sqrt(k) / L I.
#pragma once

#include <cmath>

#include "energies/spring_length.h"

namespace ipstep {

template <int kDim>
struct SquaredStrainSpring {
  SquaredStrainSpring(double stiffness, double rest_length)
      : scale(std::sqrt(stiffness) * rest_length), inv_l2(1.0 / (rest_length * rest_length)) {}

  static constexpr bool kPairDifference = true;

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    residual[0] = scale * (SquaredDistance<kDim>(xi, xj) * inv_l2 - 1.0);
    return true;
  }

  bool ResidualCurvature(const double* const*, const double* c, double* curvature) const {
    for (int a = 0; a < kDim; ++a) {
      for (int b = 0; b < kDim; ++b)
        curvature[a * kDim + b] = a == b ? 2.0 * c[0] * scale * inv_l2 : 0.0;
    }
    return true;
  }

  double scale;
  double inv_l2;
};

}  // namespace ipstep
