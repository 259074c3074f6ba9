// Gravity as a potential term, used only where it cannot be folded into the
// inertia predictor (the quasi-static integrator has no inertia).
//
// U_g = -m g.x is linear, not a sum of squares. It is written as
//   e = m |g| (H - g_hat.(x - x_start)) = U_g + constant,  r = sqrt(2 e),
// re-centred at the start of every step (x_start), with an offset H (metres)
// beyond any motion along g within one step. Value and gradient are exact. Two
// costs of the least-squares form, both shrinking as H grows in opposite ways:
// the Gauss-Newton curvature m|g| / (2e) ~ m|g| / H is a small positive number
// instead of 0, and the constant m|g|H in the cost limits how small a force
// imbalance a cost-based optimiser can still resolve. Evaluation fails if a node
// falls H below x_start in one step. Reported potential energies use -m g.x
// directly, without the offset.
#pragma once

#include <cmath>

#include "core/step_context.h"

namespace ipstep {

template <int kDim>
struct GravityPotential {
  GravityPotential(const StepContext* context, int node, double mass, const double* gravity,
                   double offset)
      : context(context), node(node) {
    double g2 = 0.0;
    for (int k = 0; k < kDim; ++k) g2 += gravity[k] * gravity[k];
    weight = mass * std::sqrt(g2);
    for (int k = 0; k < kDim; ++k) {
      direction[k] = g2 > 0.0 ? gravity[k] / std::sqrt(g2) : 0.0;
    }
    this->offset = offset;
  }

  // Its exact Hessian is zero, and a zero model cannot carry its gradient
  // (solver/newton_model_cost.h): Newton methods keep the Gauss-Newton
  // curvature m|g| / (2e) described above.
  static constexpr bool kGaussNewtonModel = true;
  // -m g.x: the exact Hessian is zero (Term::affine_energy).
  static constexpr bool kAffineEnergy = true;
  // Reports count gravity from the gravity vector, without the offset
  // (Term::uniform_gravity).
  static constexpr bool kUniformGravity = true;

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    using std::sqrt;
    const double* reference = context->x_start.data() + kDim * node;
    T along = T(0.0);
    for (int k = 0; k < kDim; ++k) along += direction[k] * (x[k] - reference[k]);
    const T e = weight * (offset - along);
    if (!(e > T(0.0))) return false;
    residual[0] = sqrt(2.0 * e);
    return true;
  }

  const StepContext* context;
  int node;
  double weight;
  double direction[kDim];
  double offset;
};

}  // namespace ipstep
