// Mass-proportional Rayleigh dissipation of one node: R = 1/2 alpha m |v_i|^2,
// residual r = sqrt(alpha m) v_i(x_i), with v(x) the integrator's discrete
// velocity (StepContext::Velocity).
#pragma once

#include <cmath>

#include "core/step_context.h"

namespace ipstep {

template <int kDim>
struct RayleighMassDamping {
  RayleighMassDamping(const StepContext* context, int node, double alpha_mass)
      : context(context), node(node), scale(std::sqrt(alpha_mass)) {}

  static constexpr bool kGaussNewtonModel = true;  // affine residuals

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    T v[kDim];
    context->Velocity(node, x, v);
    for (int k = 0; k < kDim; ++k) residual[k] = scale * v[k];
    return true;
  }

  const StepContext* context;
  int node;
  double scale;
};

}  // namespace ipstep
