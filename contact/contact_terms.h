// Ceres cost functions of the contact terms (analytic Jacobians).
//
// Gap terms (barrier, kind kPotential, with a BarrierLoss): one residual
//   u = max(d_hat - d(x), 0)
// where d is the point-obstacle or point-edge distance. Evaluation fails
// (returns false) when d <= min_distance: the point is in (or touching) the
// obstacle, so the trial point is infeasible. Beyond d_hat the residual and its
// Jacobian are zero, so terms of pairs out of reach cost nothing.
// Second derivatives (Term::curvature, core/term_hessian.h): sum_k c_k Hess r_k
// = -c_0 Hess d while active (u > 0), zero beyond d_hat; Hess d is analytic
// (contact/distance_hessian.h), so Newton models stay exact where the gap is
// far below the 1e-6 step of finite differences. The plane gap is affine in x:
// its terms are Gauss-Newton models instead (GapCurvature's caller decides).
//
// Friction terms (kind kDissipation) of the relative tangential velocity
// v_t = T^T v_rel, with the velocity map of the step context
// v(x) = v_base + slope (x - x_base) (contact/friction.h):
//  * 3D (side 0, with a FrictionLoss): the residual r(v_t), 2 components;
//  * 2D (side +1 or -1, with a OneSidedFrictionLoss): one half of the exact
//    split, the scalar residual c sigma(side v_t / c); a contact has one term
//    per side.
#pragma once

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "contact/obstacle.h"
#include "core/step_context.h"
#include "core/term.h"

namespace ipstep {

// Term::curvature of a gap term built on `gap`, any of the five classes below
// (the term owns its cost function, so the pointer lives as long as the term).
template <class Gap>
ResidualCurvature GapCurvature(const Gap* gap) {
  return [gap](const double* const* x, const double* c, double* curvature) {
    return gap->Curvature(x, c, curvature);
  };
}

class PointObstacleGap : public ceres::CostFunction {
 public:
  // `time`: the obstacle time to evaluate at, read at every evaluation.
  PointObstacleGap(int dimension, const Obstacle* obstacle, const double* time, double d_hat,
                   double min_distance);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  // Term::curvature: -c[0] Hess d while active, zero beyond d_hat.
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  int dimension_;
  const Obstacle* obstacle_;
  const double* time_;
  double d_hat_;
  double min_distance_;
};

// Edge [a, b] (blocks 0, 1, `dimension` each) against an edge feature of an
// obstacle (sphere centre or 2D box corner, Obstacle::EdgeDistance).
class EdgeObstacleGap : public ceres::CostFunction {
 public:
  // `alpha` (read at every evaluation; null: the true closest point): the
  // barrier's gap is the distance of the fixed point a + alpha (b - a), while
  // evaluation fails when the true segment distance is at most min_distance.
  EdgeObstacleGap(int dimension, const Obstacle* obstacle, int feature, const double* time,
                  double d_hat, double min_distance, const double* alpha = nullptr);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  // Term::curvature: -c[0] Hess d while active, zero beyond d_hat.
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  int dimension_;
  const Obstacle* obstacle_;
  int feature_;
  const double* time_;
  double d_hat_;
  double min_distance_;
  const double* alpha_;
};

// 3D face [a, b, c] (blocks 0, 1, 2, three components each) against a face
// feature of an obstacle (sphere centre or 3D box corner,
// Obstacle::FaceDistance). With `weights` (read at every evaluation; the
// contact manager lags them for sphere centres) the barrier's gap is the
// distance of the fixed point w[0] a + w[1] b + w[2] c: convex in the
// vertices; without (null), the true point-triangle distance. Evaluation fails
// when the true distance is at most min_distance.
class FaceObstacleGap : public ceres::CostFunction {
 public:
  FaceObstacleGap(const Obstacle* obstacle, int feature, const double* time, double d_hat,
                  double min_distance, const Eigen::Vector3d* weights = nullptr);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  // Term::curvature: -c[0] Hess d while active, zero beyond d_hat.
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  const Obstacle* obstacle_;
  int feature_;
  const double* time_;
  double d_hat_;
  double min_distance_;
  const Eigen::Vector3d* weights_;
};

// 3D edge [a, b] (blocks 0, 1) against an edge of a 3D box: the barrier's gap
// is the true segment-segment distance (Obstacle::BoxEdgeDistance); evaluation
// fails when it is at most min_distance.
class EdgeBoxEdgeGap : public ceres::CostFunction {
 public:
  EdgeBoxEdgeGap(const Obstacle* obstacle, int box_edge, const double* time, double d_hat,
                 double min_distance);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  // Term::curvature: -c[0] Hess d while active, zero beyond d_hat.
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  const Obstacle* obstacle_;
  int box_edge_;
  const double* time_;
  double d_hat_;
  double min_distance_;
};

// 2D: point p (block 0) against the edge [a, b] (blocks 1, 2).
class PointEdgeGap : public ceres::CostFunction {
 public:
  PointEdgeGap(double d_hat, double min_distance);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;
  // Term::curvature: -c[0] Hess d while active, zero beyond d_hat.
  bool Curvature(const double* const* x, const double* c, double* curvature) const;

 private:
  double d_hat_;
  double min_distance_;
};

// Node against an obstacle: v_t = T^T (v(x_node) - v_obstacle). The columns of
// `tangents` (dimension - 1 of them) are the lagged tangent basis.
class ObstacleFriction : public ceres::CostFunction {
 public:
  // `side`: 0 in 3D; +1 or -1 in 2D, with `speed_scale` c.
  ObstacleFriction(const StepContext* context, int node, const Eigen::Matrix3d& tangents,
                   const Eigen::Vector3d& obstacle_velocity, double eps_v, int side = 0,
                   double speed_scale = 0.0);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;

 private:
  const StepContext* context_;
  int node_;
  int dimension_;
  Eigen::Matrix3d tangents_;
  Eigen::Vector3d obstacle_velocity_;
  double eps_v_;
  int side_;
  double speed_scale_;
};

// 2D point p against edge [a, b]: v_t = t . (v_p - (1 - alpha) v_a - alpha v_b),
// with the lagged unit tangent t and closest-point parameter alpha; the
// one-sided residual of `side` (+1 or -1) with speed scale c.
class EdgeFriction : public ceres::CostFunction {
 public:
  EdgeFriction(const StepContext* context, int p, int a, int b, const Eigen::Vector2d& tangent,
               double alpha, int side, double speed_scale);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;

 private:
  const StepContext* context_;
  int nodes_[3];
  Eigen::Vector2d tangent_;
  double coefficients_[3];
  int side_;
  double speed_scale_;
};

}  // namespace ipstep
