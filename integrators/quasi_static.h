// Quasi-static stepping: no inertia. Each step finds the equilibrium
//   minimise U(x) + U_gravity(x) + h R((x - x_n)/h),
// a rate problem when dissipation is present (grad U + B v = f_external) and a
// sequence of static equilibria driven by moving boundary nodes otherwise.
// Velocities are stored as the rates (x_{n+1} - x_n)/h; kinetic energy is zero by
// assumption and reported as such.
#pragma once

#include "integrators/variational_integrator.h"

namespace ipstep {

class QuasiStatic : public VariationalIntegrator {
 public:
  std::string name() const override { return "quasi_static"; }
  // No time-discretisation error: each step is an equilibrium.
  int order() const override { return 0; }
  void LocalErrorVector(const State&, const State& after, double,
                        Eigen::VectorXd* error) const override {
    *error = Eigen::VectorXd::Zero(after.x.size());
  }
  bool has_inertia() const override { return false; }
  void SetWeights(double h, StepContext* context) const override;
  void Predict(const State& state, const Eigen::VectorXd& gravity, double h, StepContext* context,
               Eigen::VectorXd* guess) const override;
  void Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt& impulsive_forces, double h,
              State* state) const override;
};

}  // namespace ipstep
