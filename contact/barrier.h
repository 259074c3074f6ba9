// The IPC log barrier and its formulation as a Ceres loss function.
//
// Barrier (Li et al., "Incremental Potential Contact", 2020), per contact pair
// with gap d and activation distance d_hat, here with the stiffness kappa and the
// pair's weight w (boundary length in 2D, area in 3D) factored out:
//   B(d) = -(d - d_hat)^2 ln(d / d_hat)   for 0 < d < d_hat,   0 for d >= d_hat,
//   b(d) = kappa w B(d).
// B, B' and B'' all vanish at d_hat, so the zero extension is C^2; B tends to
// +infinity as d -> 0.
// With u = d_hat - d > 0:
//   B'(d)  = 2 u ln(d/d_hat) - u^2 / d                        (< 0)
//   B''(d) = -2 ln(d/d_hat) + 4 u / d + u^2 / d^2             (> 0)
//
// As a Ceres term: the residual is the scalar gap
// violation u(x) = max(d_hat - d(x), 0) and the loss is
//   rho(s) = 2 kappa w B(d_hat - sqrt(s)),   so   1/2 rho(u^2) = b(d).
// Writing d = d_hat - u, u = sqrt(s):
//   rho'(s)  = -b'(d) / u           = kappa w (-2 ln(d/d_hat) + u/d)        > 0
//   rho''(s) = (b''(d) + b'(d)/u) / (2 u^2) = kappa w (3/(u d) + 1/d^2) / 2 > 0
// and Ceres's corrector builds the model curvature
//   rho' + 2 s rho'' = b''(d)
// along grad d: the exact barrier Hessian for a linear gap (plane), its PSD part
// b'' grad d grad d^T for curved gaps (sphere, point-edge). Both rho' and rho''
// are positive for u > 0, as the corrector requires (it aborts when rho'' > 0
// and rho' <= 0); at s = 0 (no violation) rho = [0, 0, 0]. ln(d/d_hat) is
// computed as log1p(-u/d_hat), exact for small u.
#pragma once

#include <ceres/loss_function.h>

namespace ipstep {

// B(d), B'(d), B''(d) for kappa = w = 1; zero for d >= d_hat; +inf / -inf /
// +inf for d <= 0.
double Barrier(double d, double d_hat);
double BarrierDerivative(double d, double d_hat);
double BarrierSecondDerivative(double d, double d_hat);

// rho(s) = 2 kappa w B(d_hat - sqrt(s)) with kappa read through a pointer
// (adaptive stiffness changes it between solves without rebuilding terms).
class BarrierLoss : public ceres::LossFunction {
 public:
  BarrierLoss(double d_hat, double weight, const double* kappa)
      : d_hat_(d_hat), weight_(weight), kappa_(kappa) {}
  void Evaluate(double s, double rho[3]) const override;

 private:
  double d_hat_;
  double weight_;
  const double* kappa_;
};

}  // namespace ipstep
