// Inertia: e = 1/2 m |x_i - x_tilde_i|^2, residual r = sqrt(m) (x_i - x_tilde_i).
// The predictor x_tilde is read from the step context at every evaluation.
#pragma once

#include <cmath>

#include "core/step_context.h"

namespace ipstep {

template <int kDim>
struct InertiaResidual {
  InertiaResidual(const StepContext* context, int node, double mass)
      : context(context), node(node), sqrt_mass(std::sqrt(mass)) {}

  static constexpr bool kGaussNewtonModel = true;  // affine residuals

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const double* x_tilde = context->x_tilde.data() + kDim * node;
    for (int k = 0; k < kDim; ++k) residual[k] = sqrt_mass * (x[k] - x_tilde[k]);
    return true;
  }

  const StepContext* context;
  int node;
  double sqrt_mass;
};

}  // namespace ipstep
