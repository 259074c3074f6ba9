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
//
// Parameter ranges (MakeIntegrator rejects anything else, naming the option):
//  * beta in [1e-3, 1]. beta = 0 is the explicit central-difference scheme,
//    which is not a minimisation; as beta -> 0 the step solves for
//    x - x_hat = beta h^2 a_{n+1} and recovers a_{n+1} by dividing by beta h^2,
//    so round-off in x (~1e-16 |x|) becomes an acceleration error growing as
//    1/beta, the weights beta h^2 and beta^2 h^3 / gamma approach underflow
//    (1e-300 was accepted and every step "converged" to a wrong motion), and
//    the stopping rule measures forces scaled by 1/(beta h^2). At 1e-3 three
//    digits are lost relative to beta = 1/4. For an explicit method use
//    symplectic_euler. The upper bound 1 is generous: beta >= gamma / 2 (at
//    most 1/2) already gives unconditional stability, larger beta only adds
//    period error.
//  * gamma in [1/2, 1]. gamma < 1/2 is numerical anti-damping: the amplification
//    factor exceeds 1 at every step size, so every run grows without bound.
//    gamma = 1/2 conserves energy on linear problems, larger gamma dissipates;
//    beyond 1 the method is only more dissipative and first order.
//  Unconditional stability additionally needs beta >= gamma / 2; smaller beta
//  is conditionally stable (like symplectic Euler) and is allowed.
#pragma once

#include "integrators/variational_integrator.h"

namespace ipstep {

class Newmark : public VariationalIntegrator {
 public:
  Newmark(double beta, double gamma) : beta_(beta), gamma_(gamma) {}
  std::string name() const override { return "newmark"; }
  void SetWeights(double h, StepContext* context) const override;
  // a_0 = M^-1 f(x_0, v_0) without the impulsive forces (see Update): the
  // barrier of pairs within d_hat at x_0 is not in a_0.
  bool InitializeState(IncrementalPotential* potential, const Eigen::VectorXd& gravity,
                       State* state) const override;
  void Predict(const State& state, const Eigen::VectorXd& gravity, double h, StepContext* context,
               Eigen::VectorXd* guess) const override;
  // Contact: impulsive forces f_c (barrier, friction) are kept out of the
  // acceleration history. With the step's solution x (stationarity:
  // x = x_hat + beta h^2 (a_s + M^-1 f_c), a_s from the smooth forces),
  //   a_{n+1} = a_s = (x - x_hat)/(beta h^2) - M^-1 f_c,
  //   v_{n+1} = v_n + h ((1 - gamma) a_n + gamma a_s) + 2 beta h M^-1 f_c.
  // The contact part is then a full-step impulse 2 beta h f_c(x_{n+1}) whose
  // position change is h/2 times its velocity change (trapezoidal kinematics for
  // beta = 1/4, gamma = 1/2): its work 2 beta f_c(x_{n+1}) . (x_{n+1} - x_n) never
  // exceeds the decrease of 2 beta times the barrier energy (convex along a
  // linear gap; the barrier's effective stiffness is 2 beta kappa), so impacts
  // cannot create energy; a body resting on an obstacle is a fixed point
  // (f_c = -m g / (2 beta) balances gravity through x). With the
  // force in a_{n+1} instead (plain Newmark), the stiff barrier's force spike is
  // replayed in the next step and impacts gain or lose energy at random
  // (docs/contact.md). The friction terms' velocity map matches v_{n+1} for
  // gamma = 2 beta. Without impulsive forces this is the plain Newmark update.
  void Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt& impulsive_forces, double h,
              State* state) const override;
  // The impulse 2 beta h f_c with the position change beta h^2 f_c is the
  // trapezoidal rule with the contact force at the end point only: a barrier
  // of stiffness kappa acts as one of 2 beta kappa, and stores that energy.
  double impulsive_energy_factor() const override { return 2.0 * beta_; }

  // Second order for gamma = 1/2, first otherwise.
  int order() const override { return gamma_ == 0.5 ? 2 : 1; }
  // The local error's leading term h^2 (|beta - 1/6| + |gamma - 1/2|) |a_{n+1} - a_n|
  // (Zienkiewicz and Xie, 1991, for gamma = 1/2: the step's positions against
  // a cubic through the same accelerations) with the smooth accelerations the
  // state keeps: contact impulses are not in them (Update), the
  // controller budgets an impact's timing separately.
  void LocalErrorVector(const State& before, const State& after, double h,
                        Eigen::VectorXd* error) const override;

  static constexpr double kMinBeta = 1e-3;
  static constexpr double kMaxBeta = 1.0;
  static constexpr double kMinGamma = 0.5;
  static constexpr double kMaxGamma = 1.0;

  double beta() const { return beta_; }
  double gamma() const { return gamma_; }

 private:
  Eigen::VectorXd ExplicitPart(const State& s, double h) const;  // x_hat
  // Update with the impulsive forces at x_next.
  void UpdateWithImpulses(const Eigen::VectorXd& x_next, const Eigen::VectorXd& impulsive_forces,
                          double h, State* s) const;
  double beta_;
  double gamma_;
};

}  // namespace ipstep
