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

}  // namespace ipstep
