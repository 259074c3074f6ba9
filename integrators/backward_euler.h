// Backward (implicit) Euler as an incremental potential:
//   E(x) = 1/2 |x - x_tilde|_M^2 + h^2 U(x) + h^3 R((x - x_n)/h),
//   x_tilde = x_n + h v_n + h^2 g,
// whose stationarity is M (v_{n+1} - v_n)/h = -grad U - B v_{n+1} + M g with
// v_{n+1} = (x_{n+1} - x_n)/h. Unconditionally stable, first order, dissipative:
// on the linear oscillator the energy ratio per step is 1/(1 + (omega h)^2).
#pragma once

#include "integrators/variational_integrator.h"

namespace ipstep {

class BackwardEuler : public VariationalIntegrator {
 public:
  std::string name() const override { return "backward_euler"; }
  void SetWeights(double h, StepContext* context) const override;
  void Predict(const State& state, const Eigen::VectorXd& gravity, double h, StepContext* context,
               Eigen::VectorXd* guess) const override;
  void Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt& impulsive_forces, double h,
              State* state) const override;
};

}  // namespace ipstep
