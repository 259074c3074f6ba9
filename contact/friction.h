// Smoothed dry friction as in IPC (Li et al. 2020, section 5): the dissipation
// potential of a contact with lagged normal force magnitude lambda and lagged
// tangent basis T is
//   R(v) = mu lambda f0(|v_t|),   v_t = T^T v_rel  (relative tangential velocity),
// whose velocity gradient is the friction force mu lambda f1(|v_t|) v_t / |v_t|.
// The mollifier f1 ramps the force up over |v_t| < eps_v (static friction becomes
// a very stiff viscous law) and is exactly 1 (Coulomb) above:
//   f1(y) = 2 y / eps_v - y^2 / eps_v^2   for y < eps_v,   1 otherwise,
//   f0(y) = integral of f1 = y^2 / eps_v - y^3 / (3 eps_v^2) + eps_v / 3 for y < eps_v,
//           y otherwise (f0 is C^1; the constant makes it continuous).
// Here f0 is shifted by -eps_v/3 so that R(0) = 0.
//
// As a Ceres term the residual is not v_t itself but
//   r(v_t) = psi(|v_t|) v_t / |v_t|,   psi(y) = sqrt(2 f0(y))   (smooth, r ~ sqrt(2/eps_v) v_t
// near 0), with the linear loss rho(s) = mu lambda s, so 1/2 rho(|r|^2) = R. Why:
// Ceres's model Hessian of a term is rho' J^T J corrected only by rho'' > 0 (its
// corrector can add curvature along r, never remove it), and for a loss of
// s = |v_t|^2 rho'' < 0, so the residual v_t with rho(s) = 2 mu lambda f0(sqrt(s))
// gave mu lambda f1(y)/y in every tangent direction. The IPC Hessian is
//   mu lambda [ f1'(y) u u^T + f1(y)/y (I - u u^T) ],   u = v_t / |v_t|,
// i.e. 0 along the slip direction while sliding (y >= eps_v). With r above,
// the model is J^T J (rho' = mu lambda, rho'' = 0):
//   along u:  mu lambda psi'^2 = mu lambda f1^2 / (2 f0)   (f1(y)/y = 2/eps_v at y = 0,
//             exact there; 3/(4 eps_v) at eps_v; 1/(2 (y - eps_v/3)) while sliding),
//   across:   mu lambda psi^2 / y^2 = mu lambda 2 f0 / y^2 (2D has no across direction).
// Along the slip this is the smallest model curvature any split of R into a
// smooth odd residual and a loss with rho'' <= 0 can give (Ceres's rho' J^T J
// with rho' non-increasing is >= R'^2 / (2 R)); the old split gave f1/y, up to
// twice as much while sliding (where Gauss-Newton then converged linearly).
// In 3D the price is the across-slip curvature, 2 f0/y^2 instead of f1/y (at
// most 2x, and exact as y -> 0).
//
// 2D (one tangential component v) has an exact split, used by the 2D friction
// terms: R = mu lambda [P(v) + P(-v)] with the one-sided half
//   P(w) = (f0(|w|) + w) / 2 + eps_v / 6   (P(-v) + P(v) = f0(|v|) + eps_v / 3),
// convex and non-decreasing: P' = (1 + f1(|w|) sign w) / 2 in [0, 1],
// P'' = f1'(|w|) / 2 >= 0, P = 0 for w <= -eps_v (the constant eps_v / 6 makes
// P >= 0; it shifts R by mu lambda eps_v / 3, which no optimiser sees).
// Each half is a term with the positive scalar residual r = c sigma(w / c),
//   sigma(z) = e^z (z < 0),  1 + z + z^2 / 2 (z >= 0)   (C^2, increasing, > 0),
// and the loss rho(q) = 2 mu lambda P(w(q)), w(q) = c sigma^-1(sqrt(q) / c).
// Ceres's model curvature of a term in w is g'' r'^2 when rho'' > 0 and
// (g' / r) r'^2 otherwise (g(r) = P(w(r))); the exact one is
// g'' r'^2 + g' r'' = P'', so the model is off by at most P' |r''| / r'^2
// <= mu lambda / c (sigma'' / sigma'^2 <= 1): the pair of halves reproduces
// IPC's Hessian mu lambda f1'(|v|) (2 mu lambda / eps_v at rest, 0 while
// sliding) up to mu lambda / c. c = kFrictionSpeedScale eps_v: the residual
// and loss stay exact at every speed (sigma is invertible on all of R; the
// quadratic branch keeps r finite), and the reconstructed w is accurate to
// about eps c.
#pragma once

#include <ceres/loss_function.h>

namespace ipstep {

double FrictionF0(double y, double eps_v);  // shifted: FrictionF0(0) = 0
double FrictionF1(double y, double eps_v);

// r = psi(|v|) v / |v| for the m = 1 or 2 components of v; dr/dv (m x m,
// row-major) when dr_dv is not null.
void FrictionResidual(const double* v, int m, double eps_v, double* r, double* dr_dv);

// rho(s) = scale s, scale = mu * lambda [N].
class FrictionLoss : public ceres::LossFunction {
 public:
  explicit FrictionLoss(double scale) : scale_(scale) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  double scale_;
};

// c / eps_v of the 2D split (the model curvature error is mu lambda / c).
constexpr double kFrictionSpeedScale = 1e3;

// The one-sided half P(w) per unit mu lambda; P'(w), P''(w) when not null.
double FrictionHalf(double w, double eps_v, double* d1 = nullptr, double* d2 = nullptr);

// r = c sigma(w / c) and dr/dw.
void OneSidedFrictionResidual(double w, double c, double* r, double* dr_dw);

// rho(q) = 2 scale P(w(q)) for the residual above (scale = mu lambda).
class OneSidedFrictionLoss : public ceres::LossFunction {
 public:
  OneSidedFrictionLoss(double scale, double c, double eps_v)
      : scale_(scale), c_(c), eps_v_(eps_v) {}
  void Evaluate(double q, double rho[3]) const override;

 private:
  double scale_;
  double c_;
  double eps_v_;
};

}  // namespace ipstep
