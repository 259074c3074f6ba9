#include "contact/contact_terms.h"

#include "contact/distance_hessian.h"
#include "contact/friction.h"
#include "geometry/point_edge.h"

namespace ipstep {

namespace {

// Residual max(d_hat - d, 0) and its Jacobian blocks -grad[block] (zero out of
// reach): `blocks` blocks of `dimension` components.
void WriteGapResidual(double d, double d_hat, const Eigen::Vector3d* grad, int blocks,
                      int dimension, double* residuals, double** jacobians) {
  const double u = d_hat - d;
  const bool active = u > 0.0;
  residuals[0] = active ? u : 0.0;
  if (jacobians == nullptr) return;
  for (int block = 0; block < blocks; ++block) {
    if (jacobians[block] == nullptr) continue;
    for (int k = 0; k < dimension; ++k) jacobians[block][k] = active ? -grad[block][k] : 0.0;
  }
}

// Row-major curvature over N blocks of `dimension` coordinates from the
// Hessian of d over N blocks of S coordinates (S = 3; 2 for the 2D point-edge
// term; a 2D term keeps the x, y rows and columns of each block, the Hessian
// of d restricted to the plane): -c0 Hess d while active, zero otherwise.
template <int N, int S>
void WriteGapCurvature(const Eigen::Matrix<double, N * S, N * S>& hessian, bool active, double c0,
                       int dimension, double* curvature) {
  const int n = N * dimension;
  for (int bi = 0; bi < N; ++bi) {
    for (int ki = 0; ki < dimension; ++ki) {
      double* row = curvature + (bi * dimension + ki) * n;
      for (int bj = 0; bj < N; ++bj) {
        for (int kj = 0; kj < dimension; ++kj) {
          row[bj * dimension + kj] = active ? -c0 * hessian(bi * S + ki, bj * S + kj) : 0.0;
        }
      }
    }
  }
}

}  // namespace

PointObstacleGap::PointObstacleGap(int dimension, const Obstacle* obstacle, const double* time,
                                   double d_hat, double min_distance)
    : dimension_(dimension),
      obstacle_(obstacle),
      time_(time),
      d_hat_(d_hat),
      min_distance_(min_distance) {
  set_num_residuals(1);
  mutable_parameter_block_sizes()->push_back(dimension);
}

bool PointObstacleGap::Evaluate(double const* const* x, double* residuals,
                                double** jacobians) const {
  Eigen::Vector3d gradient;
  const double d = obstacle_->Distance(ToPoint(x[0], dimension_), *time_, &gradient);
  if (!(d > min_distance_)) return false;
  WriteGapResidual(d, d_hat_, &gradient, 1, dimension_, residuals, jacobians);
  return true;
}

bool PointObstacleGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector3d y = ToPoint(x[0], dimension_);
  const double d = obstacle_->Distance(y, *time_);
  if (!(d > min_distance_)) return false;
  const bool active = d < d_hat_;
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  if (active && !ObstacleDistanceHessian(*obstacle_, y, *time_, &hessian)) return false;
  WriteGapCurvature<1, 3>(hessian, active, c[0], dimension_, curvature);
  return true;
}

EdgeObstacleGap::EdgeObstacleGap(int dimension, const Obstacle* obstacle, int feature,
                                 const double* time, double d_hat, double min_distance,
                                 const double* alpha)
    : dimension_(dimension),
      obstacle_(obstacle),
      feature_(feature),
      time_(time),
      d_hat_(d_hat),
      min_distance_(min_distance),
      alpha_(alpha) {
  set_num_residuals(1);
  for (int b = 0; b < 2; ++b) mutable_parameter_block_sizes()->push_back(dimension);
}

bool EdgeObstacleGap::Evaluate(double const* const* x, double* residuals,
                               double** jacobians) const {
  Eigen::Vector3d grad[2];
  const Eigen::Vector3d a = ToPoint(x[0], dimension_), b = ToPoint(x[1], dimension_);
  double d = obstacle_->EdgeDistance(feature_, a, b, *time_, &grad[0], &grad[1]);
  if (!(d > min_distance_)) return false;
  if (alpha_ != nullptr) {
    d = obstacle_->EdgePointDistance(feature_, a, b, *alpha_, *time_, &grad[0], &grad[1]);
  }
  WriteGapResidual(d, d_hat_, grad, 2, dimension_, residuals, jacobians);
  return true;
}

bool EdgeObstacleGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector3d a = ToPoint(x[0], dimension_), b = ToPoint(x[1], dimension_);
  double d = obstacle_->EdgeDistance(feature_, a, b, *time_);
  if (!(d > min_distance_)) return false;
  if (alpha_ != nullptr) d = obstacle_->EdgePointDistance(feature_, a, b, *alpha_, *time_);
  const bool active = d < d_hat_;
  Matrix6d hessian = Matrix6d::Zero();
  if (active) {
    const bool ok =
        alpha_ != nullptr
            ? EdgePointDistanceHessian(*obstacle_, feature_, a, b, *alpha_, *time_, &hessian)
            : EdgeDistanceHessian(*obstacle_, feature_, a, b, *time_, &hessian);
    if (!ok) return false;
  }
  WriteGapCurvature<2, 3>(hessian, active, c[0], dimension_, curvature);
  return true;
}

FaceObstacleGap::FaceObstacleGap(const Obstacle* obstacle, int feature, const double* time,
                                 double d_hat, double min_distance, const Eigen::Vector3d* weights)
    : obstacle_(obstacle),
      feature_(feature),
      time_(time),
      d_hat_(d_hat),
      min_distance_(min_distance),
      weights_(weights) {
  set_num_residuals(1);
  for (int b = 0; b < 3; ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool FaceObstacleGap::Evaluate(double const* const* x, double* residuals,
                               double** jacobians) const {
  const Eigen::Vector3d a = ToPoint(x[0], 3), b = ToPoint(x[1], 3), c = ToPoint(x[2], 3);
  Eigen::Vector3d grad[3];
  double d = obstacle_->FaceDistance(feature_, a, b, c, *time_, grad);
  if (!(d > min_distance_)) return false;
  if (weights_ != nullptr) {
    d = obstacle_->FacePointDistance(feature_, a, b, c, *weights_, *time_, grad);
  }
  WriteGapResidual(d, d_hat_, grad, 3, 3, residuals, jacobians);
  return true;
}

bool FaceObstacleGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector3d a = ToPoint(x[0], 3), b = ToPoint(x[1], 3), v = ToPoint(x[2], 3);
  double d = obstacle_->FaceDistance(feature_, a, b, v, *time_);
  if (!(d > min_distance_)) return false;
  if (weights_ != nullptr) d = obstacle_->FacePointDistance(feature_, a, b, v, *weights_, *time_);
  const bool active = d < d_hat_;
  Matrix9d hessian = Matrix9d::Zero();
  if (active) {
    const bool ok =
        weights_ != nullptr
            ? FacePointDistanceHessian(*obstacle_, feature_, a, b, v, *weights_, *time_, &hessian)
            : FaceDistanceHessian(*obstacle_, feature_, a, b, v, *time_, &hessian);
    if (!ok) return false;
  }
  WriteGapCurvature<3, 3>(hessian, active, c[0], 3, curvature);
  return true;
}

EdgeBoxEdgeGap::EdgeBoxEdgeGap(const Obstacle* obstacle, int box_edge, const double* time,
                               double d_hat, double min_distance)
    : obstacle_(obstacle),
      box_edge_(box_edge),
      time_(time),
      d_hat_(d_hat),
      min_distance_(min_distance) {
  set_num_residuals(1);
  for (int b = 0; b < 2; ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool EdgeBoxEdgeGap::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  const Eigen::Vector3d a = ToPoint(x[0], 3), b = ToPoint(x[1], 3);
  Eigen::Vector3d grad[2];
  const double d = obstacle_->BoxEdgeDistance(box_edge_, a, b, *time_, &grad[0], &grad[1]);
  if (!(d > min_distance_)) return false;
  WriteGapResidual(d, d_hat_, grad, 2, 3, residuals, jacobians);
  return true;
}

bool EdgeBoxEdgeGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector3d a = ToPoint(x[0], 3), b = ToPoint(x[1], 3);
  const double d = obstacle_->BoxEdgeDistance(box_edge_, a, b, *time_);
  if (!(d > min_distance_)) return false;
  const bool active = d < d_hat_;
  Matrix6d hessian = Matrix6d::Zero();
  if (active && !BoxEdgeDistanceHessian(*obstacle_, box_edge_, a, b, *time_, &hessian)) {
    return false;
  }
  WriteGapCurvature<2, 3>(hessian, active, c[0], 3, curvature);
  return true;
}

PointEdgeGap::PointEdgeGap(double d_hat, double min_distance)
    : d_hat_(d_hat), min_distance_(min_distance) {
  set_num_residuals(1);
  for (int b = 0; b < 3; ++b) mutable_parameter_block_sizes()->push_back(2);
}

bool PointEdgeGap::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  const Eigen::Vector2d p(x[0][0], x[0][1]), a(x[1][0], x[1][1]), b(x[2][0], x[2][1]);
  const PointEdgeDistanceResult r = PointEdgeDistance(p, a, b);
  if (!(r.distance > min_distance_)) return false;
  const Eigen::Vector3d grad[3] = {{r.grad_p[0], r.grad_p[1], 0.0},
                                   {r.grad_a[0], r.grad_a[1], 0.0},
                                   {r.grad_b[0], r.grad_b[1], 0.0}};
  WriteGapResidual(r.distance, d_hat_, grad, 3, 2, residuals, jacobians);
  return true;
}

bool PointEdgeGap::Curvature(const double* const* x, const double* c, double* curvature) const {
  const Eigen::Vector2d p(x[0][0], x[0][1]), a(x[1][0], x[1][1]), b(x[2][0], x[2][1]);
  const double d = PointEdgeDistance(p, a, b).distance;
  if (!(d > min_distance_)) return false;
  const bool active = d < d_hat_;
  Matrix6d hessian = Matrix6d::Zero();
  if (active && !PointEdgeDistanceHessian(p, a, b, &hessian)) return false;
  WriteGapCurvature<3, 2>(hessian, active, c[0], 2, curvature);
  return true;
}

ObstacleFriction::ObstacleFriction(const StepContext* context, int node,
                                   const Eigen::Matrix3d& tangents,
                                   const Eigen::Vector3d& obstacle_velocity, double eps_v, int side,
                                   double speed_scale)
    : context_(context),
      node_(node),
      dimension_(context->dimension),
      tangents_(tangents),
      obstacle_velocity_(obstacle_velocity),
      eps_v_(eps_v),
      side_(side),
      speed_scale_(speed_scale) {
  set_num_residuals(side_ == 0 ? dimension_ - 1 : 1);
  mutable_parameter_block_sizes()->push_back(dimension_);
}

bool ObstacleFriction::Evaluate(double const* const* x, double* residuals,
                                double** jacobians) const {
  double v[3] = {0.0, 0.0, 0.0};
  context_->Velocity(node_, x[0], v);
  const int m = dimension_ - 1;
  double v_t[2] = {0.0, 0.0};
  for (int j = 0; j < m; ++j) {
    for (int k = 0; k < dimension_; ++k) v_t[j] += tangents_(k, j) * (v[k] - obstacle_velocity_[k]);
  }
  const bool want_jacobian = jacobians != nullptr && jacobians[0] != nullptr;
  double dr_dv[4];
  if (side_ != 0) {
    OneSidedFrictionResidual(side_ * v_t[0], speed_scale_, residuals, dr_dv);
    dr_dv[0] *= side_;
  } else {
    FrictionResidual(v_t, m, eps_v_, residuals, want_jacobian ? dr_dv : nullptr);
  }
  if (want_jacobian) {
    // dr/dx = dr/dv_t * slope T^T.
    for (int i = 0; i < m; ++i) {
      for (int k = 0; k < dimension_; ++k) {
        double sum = 0.0;
        for (int j = 0; j < m; ++j) sum += dr_dv[i * m + j] * tangents_(k, j);
        jacobians[0][i * dimension_ + k] = context_->velocity_slope * sum;
      }
    }
  }
  return true;
}

EdgeFriction::EdgeFriction(const StepContext* context, int p, int a, int b,
                           const Eigen::Vector2d& tangent, double alpha, int side,
                           double speed_scale)
    : context_(context),
      nodes_{p, a, b},
      tangent_(tangent),
      coefficients_{1.0, -(1.0 - alpha), -alpha},
      side_(side),
      speed_scale_(speed_scale) {
  set_num_residuals(1);
  for (int block = 0; block < 3; ++block) mutable_parameter_block_sizes()->push_back(2);
}

bool EdgeFriction::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  double v_t = 0.0;
  for (int block = 0; block < 3; ++block) {
    double v[2];
    context_->Velocity(nodes_[block], x[block], v);
    v_t += coefficients_[block] * (tangent_[0] * v[0] + tangent_[1] * v[1]);
  }
  double dr_dv = 0.0;
  OneSidedFrictionResidual(side_ * v_t, speed_scale_, residuals, &dr_dv);
  dr_dv *= side_;
  if (jacobians != nullptr) {
    for (int block = 0; block < 3; ++block) {
      if (jacobians[block] == nullptr) continue;
      for (int k = 0; k < 2; ++k) {
        jacobians[block][k] = dr_dv * coefficients_[block] * context_->velocity_slope * tangent_[k];
      }
    }
  }
  return true;
}

}  // namespace ipstep
