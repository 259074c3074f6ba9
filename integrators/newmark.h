// Newmark(beta, gamma) in the variational form of Kane, Marsden, Ortiz & West
// (1999): with the explicit part of the position update
//   x_hat = x_n + h v_n + h^2 (1/2 - beta) a_n,
// x_{n+1} minimises
//   E(x) = 1/2 |x - x_hat - beta h^2 g|_M^2 + beta h^2 U(x) + (beta^2 h^3/gamma) R(v(x)),
//   a_{n+1} = (x - x_hat)/(beta h^2),  v(x) = v_n + h (1 - gamma) a_n + gamma h a_{n+1},
// whose stationarity is M a_{n+1} = -grad U(x_{n+1}) - B v_{n+1} + M g (the Newmark
// equation of motion). beta = 1/4, gamma = 1/2 is the trapezoidal rule: second
// order, energy-conserving on linear problems, period elongated by
// Omega / (2 atan(Omega/2)); gamma > 1/2 adds numerical dissipation.
// beta must be > 0 (beta = 0 is the explicit central-difference scheme).
#pragma once

#include "integrators/integrator.h"

namespace ipstep {

class Newmark : public Integrator {
 public:
  Newmark(double beta, double gamma) : beta_(beta), gamma_(gamma) {}
  std::string name() const override { return "newmark"; }
  bool needs_initial_acceleration() const override { return true; }
  void SetWeights(double h, StepContext* context) const override;
  void Predict(const State& state, const Eigen::VectorXd& gravity, double h, StepContext* context,
               Eigen::VectorXd* guess) const override;
  void Update(const Eigen::VectorXd& x_next, double h, State* state) const override;

  double beta() const { return beta_; }
  double gamma() const { return gamma_; }

 private:
  Eigen::VectorXd ExplicitPart(const State& s, double h) const;  // x_hat
  double beta_;
  double gamma_;
};

}  // namespace ipstep
