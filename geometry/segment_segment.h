// 3D segment-segment distance between [a0, a1] and [b0, b1], the parameters of
// the closest points and the gradients with respect to the four end points.
#pragma once

#include <Eigen/Core>

namespace ipstep {

struct SegmentSegmentDistanceResult {
  double distance = 0.0;
  // Closest points a0 + s (a1 - a0) and b0 + t (b1 - b0), s, t in [0, 1].
  double s = 0.0;
  double t = 0.0;
  // Gradients of the distance: with n = (pa - pb) / |pa - pb|,
  //   d/da0 = (1 - s) n, d/da1 = s n, d/db0 = -(1 - t) n, d/db1 = -t n
  // ((s, t) minimise the distance, so they do not contribute). Zero when the
  // distance is zero.
  Eigen::Vector3d grad_a0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_a1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_b0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d grad_b1 = Eigen::Vector3d::Zero();
};

// Exact. f(s, t) = |pa(s) - pb(t)|^2 is a convex quadratic on [0, 1]^2: its
// minimum is the stationary point when that lies inside the square (and the
// segments are not parallel), otherwise on the square's boundary, i.e. the
// closest of the four end-point-to-segment distances. Parallel (and
// degenerate) segments take the boundary branch, so no division by a vanishing
// determinant; for overlapping parallel segments the closest points are then an
// end point and its projection (any pair along the overlap is equally close).
SegmentSegmentDistanceResult SegmentSegmentDistance(const Eigen::Vector3d& a0,
                                                    const Eigen::Vector3d& a1,
                                                    const Eigen::Vector3d& b0,
                                                    const Eigen::Vector3d& b1);

}  // namespace ipstep
