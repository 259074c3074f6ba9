// 2D point-edge geometry for self-contact: the distance from a point p to the
// segment [a, b] and continuous collision detection of a moving point against a
// moving segment (all three moving linearly over the same interval).
#pragma once

#include <Eigen/Core>

namespace ipstep {

struct PointEdgeDistanceResult {
  double distance = 0.0;
  double alpha = 0.0;  // closest point a + alpha (b - a), alpha in [0, 1]
  // Gradients of the distance with respect to p, a and b.
  Eigen::Vector2d grad_p = Eigen::Vector2d::Zero();
  Eigen::Vector2d grad_a = Eigen::Vector2d::Zero();
  Eigen::Vector2d grad_b = Eigen::Vector2d::Zero();
};

// Unsigned distance |p - c| to the closest point c of the segment. Gradients are
// those of the active piece (interior: distance to the line; ends: distance to
// the end point); they are zero when the distance is zero.
PointEdgeDistanceResult PointEdgeDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b);

// First fraction s in [0, 1] at which p(s) lies on the segment [a(s), b(s)],
// with p(s) = p0 + s (p1 - p0) etc.; kNoImpact when the paths never meet.
double PointEdgeTimeOfImpact(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                             const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                             const Eigen::Vector2d& b0, const Eigen::Vector2d& b1);

// True when the closed segments [a, b] and [c, d] intersect.
bool SegmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d);

constexpr double kNoPointEdgeImpact = 2.0;

}  // namespace ipstep
