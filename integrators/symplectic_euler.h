// Symplectic (semi-implicit) Euler, the explicit, non-optimising baseline:
//   v_{n+1} = v_n + h M^-1 f(x_n, v_n),  x_{n+1} = x_n + h v_{n+1}.
// On the linear oscillator its amplification matrix has trace 2 - Omega^2 and
// determinant 1: bounded for Omega = omega h < 2, exponentially growing above.
#pragma once

#include "integrators/explicit_integrator.h"

namespace ipstep {

class SymplecticEuler : public ExplicitIntegrator {
 public:
  std::string name() const override { return "symplectic_euler"; }
  void SetWeights(double h, StepContext* context) const override;
  void Advance(const Eigen::VectorXd& forces, double h, State* state) const override;
};

}  // namespace ipstep
