// Cost functions of 3D self-contact (contact/pairs/point_triangle_pairs.h,
// edge_edge_pairs.h): four moving nodes, one parameter block of 3 each.
//
// PointTriangleGap: residual u = max(d_hat - d, 0), d the point-triangle
// distance (geometry/point_triangle.h), with the BarrierLoss
// (contact/barrier.h) like every other gap term (contact/contact_terms.h):
// 1/2 rho(u^2) = kappa w B(d). Curvature: -c0 Hess d
// (PointTriangleDistanceHessian, contact/distance_hessian.h).
//
// EdgeEdgeGap: the mollified barrier m(x) B(d(x)) (geometry/edge_edge_mollifier.h)
// in the same residual/loss form. Why not another form:
//  * the loss sees only s = |r|^2, so it cannot carry m (which depends on x
//    apart from d);
//  * r = sqrt(2 kappa w m B) without a loss gives the right value and
//    gradient, but Ceres's Gauss-Newton model is then grad e grad e^T / (2 e),
//    along grad d B'^2 / (2 B) instead of B'': about 1 / (2 ln(d_hat / d)) of
//    the barrier's curvature near contact (a tenth at d = d_hat / 100), so the
//    trust-region and Levenberg-Marquardt optimisers would see a much weaker
//    barrier for edge-edge pairs than for every other pair.
// Instead the residual is the gap of an "effective distance" d_m with
//   B(d_m) = m B(d),   d <= d_m <= d_hat   (B is decreasing on (0, d_hat)),
// u = d_hat - d_m, and the usual BarrierLoss: 1/2 rho(u^2) = kappa w B(d_m)
// = kappa w m B(d), exactly the mollified barrier. With m = 1 it is the plain
// gap (d_m = d). Derivatives by implicit differentiation of B(d_m) = beta,
// beta = m B(d):
//   B'(d_m) grad d_m = grad beta = B(d) grad m + m B'(d) grad d,
//   B''(d_m) grad d_m grad d_m^T + B'(d_m) Hess d_m = Hess beta
//     = B(d) Hess m + B'(d) (grad m grad d^T + grad d grad m^T)
//       + m (B''(d) grad d grad d^T + B'(d) Hess d).
// Ceres's model (rho' + 2 s rho'' = kappa w B''(d_m) along grad d_m: the loss's
// corrector, contact/barrier.h) is the Gauss-Newton part of the exact Hessian
// kappa w Hess beta, the same model quality as every other gap term, and the
// Newton models (core/term_hessian.h) add the residual curvature
// -c0 Hess d_m, which completes it to kappa w Hess beta exactly. d_m solves
// B(d_hat - u) = beta by Newton's method in u from u = d_hat - d: B(d_hat - u)
// is increasing and convex in u, so the iterates decrease monotonically to
// the root (never below it). At m = 0 (parallel edges) d_m = d_hat: no
// barrier, zero Jacobian (grad beta = B grad m = 0 there as grad c = 0).
// Evaluation fails where the true distance d <= min_distance, as every gap.
//
// SelfFriction: the friction of one contact (contact/friction.h, 3D form:
// 2-component residual r(v_t) with a FrictionLoss(mu lambda)) for the
// relative velocity of the two closest points, a fixed (lagged) combination
// v_rel = sum_k alpha_k v_k of the four nodes' velocities (point-triangle:
// (1, -w_a, -w_b, -w_c); edge-edge: (1 - s, s, -(1 - t), -t)), and
// v_t = T^T v_rel with a lagged orthonormal tangent basis T (3 x 2).
#pragma once

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include <array>
#include <vector>

#include "contact/pair_set.h"
#include "core/incremental_potential.h"
#include "core/step_context.h"

namespace ipstep {

class PointTriangleGap : public ceres::CostFunction {
 public:
  PointTriangleGap(double d_hat, double min_distance);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  double d_hat_;
  double min_distance_;
};

class EdgeEdgeGap : public ceres::CostFunction {
 public:
  // eps_x: the mollifier threshold (MollifierThreshold of the rest lengths).
  EdgeEdgeGap(double d_hat, double min_distance, double eps_x);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

  // The effective distance d_m of the header (and grad d_m over the 12
  // coordinates when not null, Hess d_m when not null); false where d <=
  // min_distance. d_m = d_hat when d >= d_hat (inactive).
  bool EffectiveDistance(const double* const* x, double* d_m, double* gradient,
                         double* hessian) const;

 private:
  double d_hat_;
  double min_distance_;
  double eps_x_;
};

// u in (0, d_hat) with B(d_hat - u) = beta (0 <= beta <= B(d_hat - u_max)),
// by monotone Newton from u_max.
double InverseBarrierGap(double beta, double d_hat, double u_max);

class SelfFriction : public ceres::CostFunction {
 public:
  SelfFriction(const StepContext* context, const int nodes[4], const double alpha[4],
               const Eigen::Matrix<double, 3, 2>& tangents, double eps_v);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;

 private:
  const StepContext* context_;
  int nodes_[4];
  double alpha_[4];
  Eigen::Matrix<double, 3, 2> tangents_;
  double eps_v_;
};

// A 3D self-contact's friction lagged at the start of the step: the relative
// velocity sum_i alpha_i v_i of its four nodes in the tangent basis, and the
// normal force kappa w (-B'(d)).
struct SelfFrictionLag {
  std::array<int, 4> nodes;
  std::array<double, 4> alpha;
  Eigen::Matrix<double, 3, 2> tangents;
  double normal_force;
};

// One SelfFriction term per lag (kind kDissipation, impulsive, owner
// `owner`, FrictionLoss mu lambda, mu the self-contact coefficient
// FrictionSettings::ForSelf); returns the number of lags, 0 (no terms) when
// mu is 0. Shared by the point-triangle and edge-edge kinds.
int AddSelfFrictionTerms(const std::vector<SelfFrictionLag>& lags, const StepContext* step,
                         const TermOwner& owner, const FrictionSettings& friction,
                         IncrementalPotential* potential);

}  // namespace ipstep
