// The closest point of a segment to a point, as the segment parameter.
#pragma once

#include <algorithm>

#include <Eigen/Core>

namespace ipstep {

// Parameter s in [0, 1] of the point a + s (b - a) closest to p (0 for a
// degenerate segment).
inline double ClosestSegmentParameter(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                      const Eigen::Vector3d& b) {
  const Eigen::Vector3d e = b - a;
  const double length2 = e.squaredNorm();
  return length2 > 0.0 ? std::clamp((p - a).dot(e) / length2, 0.0, 1.0) : 0.0;
}

}  // namespace ipstep
