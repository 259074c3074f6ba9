// Stiffness-proportional Rayleigh dissipation of one spring on its length rate:
// R = 1/2 beta k (n^T (v_j - v_i))^2 where n is the spring direction at the start
// of the step (lagged, so B is constant within a step and R is an exact quadratic
// in v). Residual r = sqrt(beta k) n^T (v_j - v_i).
#pragma once

#include <cmath>

#include "core/step_context.h"

namespace ipstep {

template <int kDim>
struct RayleighStiffnessDamping {
  RayleighStiffnessDamping(const StepContext* context, int i, int j, double beta_k)
      : context(context), i(i), j(j), scale(std::sqrt(beta_k)) {}

  static constexpr bool kGaussNewtonModel = true;  // affine residuals

  template <typename T>
  bool operator()(const T* xi, const T* xj, T* residual) const {
    const double* pi = context->x_start.data() + kDim * i;
    const double* pj = context->x_start.data() + kDim * j;
    double n[kDim];
    double norm2 = 0.0;
    for (int k = 0; k < kDim; ++k) {
      n[k] = pj[k] - pi[k];
      norm2 += n[k] * n[k];
    }
    T vi[kDim], vj[kDim];
    context->Velocity(i, xi, vi);
    context->Velocity(j, xj, vj);
    T rate = T(0.0);
    if (norm2 > 0.0) {
      const double inv = 1.0 / std::sqrt(norm2);
      for (int k = 0; k < kDim; ++k) rate += (n[k] * inv) * (vj[k] - vi[k]);
    }
    residual[0] = scale * rate;
    return true;
  }

  const StepContext* context;
  int i;
  int j;
  double scale;
};

}  // namespace ipstep
