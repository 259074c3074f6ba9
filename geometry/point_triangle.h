// 3D point-triangle distance: the distance from a point p to the closed
// triangle [a, b, c], the barycentric coordinates of the closest point and the
// gradients with respect to all four points.
#pragma once

#include <Eigen/Core>

namespace ipstep {

struct PointTriangleDistanceResult {
  double distance = 0.0;
  // Closest point q = w[0] a + w[1] b + w[2] c, w >= 0, sum 1.
  Eigen::Vector3d weights = Eigen::Vector3d(1.0, 0.0, 0.0);
  // Gradients of the distance: with n = (q - p) / |q - p|,
  //   d/dp = -n,  d/da = w[0] n,  d/db = w[1] n,  d/dc = w[2] n
  // (q minimises |q - p| over the triangle, so moving the weights does not
  // change the distance to first order: only the vertices' own motion at fixed
  // weights counts). Zero when the distance is zero.
  Eigen::Vector3d grad_p = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_c = Eigen::Vector3d::Zero();
};

// Exact: the projection of p onto the triangle's plane when it falls inside
// (all barycentrics >= 0), otherwise the closest of the three edges (the
// squared distance is convex over the triangle, so its minimum is either the
// interior stationary point or on the boundary). A degenerate triangle
// (collinear or coincident vertices) is treated as its edges.
PointTriangleDistanceResult PointTriangleDistance(const Eigen::Vector3d& p,
                                                  const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b,
                                                  const Eigen::Vector3d& c);

// Distance from p to the fixed point w[0] a + w[1] b + w[2] c of the triangle
// (>= the triangle's distance; equal when w are the closest point's weights),
// with the gradients w[i] n with respect to the vertices.
double PointTrianglePointDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  const Eigen::Vector3d& w, Eigen::Vector3d* grad_a = nullptr,
                                  Eigen::Vector3d* grad_b = nullptr,
                                  Eigen::Vector3d* grad_c = nullptr);

// True when the closed segment [p, q] meets the closed triangle [a, b, c]
// (non-degenerate triangle; a segment in the triangle's plane counts when it
// crosses one of the triangle's edges or lies inside).
bool SegmentIntersectsTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

}  // namespace ipstep
