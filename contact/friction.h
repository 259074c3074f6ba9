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
// As a Ceres term the residual is v_t (1 component in 2D, 2 in 3D) and the loss
//   rho(s) = 2 mu lambda (f0(sqrt(s)) - eps_v/3),   1/2 rho(|v_t|^2) = R.
//   rho'(s)  = mu lambda f1(y) / y               (> 0; 2 mu lambda / eps_v at y = 0)
//   rho''(s) = mu lambda (f1'(y) y - f1(y)) / (2 y^3)   (<= 0)
// Since rho'' <= 0, Ceres's corrector uses the model Hessian rho' J^T J =
// mu lambda f1(y)/y J^T J: positive semi-definite, exact across the slip
// direction and an upper bound along it (f1 is concave).
#pragma once

#include <ceres/loss_function.h>

namespace ipstep {

double FrictionF0(double y, double eps_v);  // shifted: FrictionF0(0) = 0
double FrictionF1(double y, double eps_v);

class FrictionLoss : public ceres::LossFunction {
 public:
  // scale = mu * lambda [N].
  FrictionLoss(double scale, double eps_v) : scale_(scale), eps_v_(eps_v) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  double scale_;
  double eps_v_;
};

}  // namespace ipstep
