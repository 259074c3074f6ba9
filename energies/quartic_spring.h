// Anharmonic quartic spring: e = c (|d| - L)^4, d = x_j - x_i (the soft springs
// of the Fermi-Pasta-Ulam chain). Residual r = sqrt(2c) (|d| - L)^2, with
// r' = 2 sqrt(2c) (|d| - L), r'' = 2 sqrt(2c) along d.
#pragma once

#include <cmath>

#include "energies/spring_length.h"

namespace ipstep {

template <int kDim>
struct QuarticSpring {
  QuarticSpring(double c, double rest_length)
      : scale(std::sqrt(2.0 * c)), rest_length(rest_length) {}

  static constexpr bool kPairDifference = true;

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    using std::sqrt;
    const T d2 = SquaredDistance<kDim>(xi, xj);
    if (!(d2 > T(0.0))) return false;
    const T stretch = sqrt(d2) - rest_length;
    residual[0] = scale * stretch * stretch;
    return true;
  }

  bool ResidualCurvature(const double* const* x, const double* c, double* curvature) const {
    return RadialResidualCurvature<kDim>(
        x[0], x[1], c[0],
        [this](double length, double* r1, double* r2) {
          *r1 = 2.0 * scale * (length - rest_length);
          *r2 = 2.0 * scale;
        },
        curvature);
  }

  double scale;
  double rest_length;
};

}  // namespace ipstep
