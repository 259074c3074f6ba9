#include "geometry/self_ccd.h"

#include <algorithm>

#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"

namespace ipstep {

namespace {

// The advancement of the header over the four points x[0..3] (start) with
// displacements dx[0..3]; primitive A is points [0, split), B [split, 4).
template <class Distance>
double Advance(const Eigen::Vector3d* x, const Eigen::Vector3d* dx, int split, double margin,
               const Distance& distance) {
  const double d0 = distance(x);
  if (!(d0 > margin)) return 0.0;
  const Eigen::Vector3d mean = (dx[0] + dx[1] + dx[2] + dx[3]) / 4.0;
  double l_a = 0.0, l_b = 0.0;
  for (int i = 0; i < 4; ++i) {
    const double l = (dx[i] - mean).norm();
    if (i < split) {
      l_a = std::max(l_a, l);
    } else {
      l_b = std::max(l_b, l);
    }
  }
  const double speed = l_a + l_b;
  if (!(speed > 0.0)) return kSelfNoImpact;
  const double goal = margin + kGapFraction * (d0 - margin);
  const double tolerance = kAdvanceTolerance * (d0 - goal);
  double s = 0.0, d = d0;
  Eigen::Vector3d y[4];
  for (int step = 0; step < kMaxAdvances; ++step) {
    const double next = s + (d - goal) / speed;
    if (next >= 1.0) return kSelfNoImpact;
    s = next;
    for (int i = 0; i < 4; ++i) y[i] = x[i] + s * dx[i];
    d = distance(y);
    if (d - goal <= tolerance) return s;
  }
  return s;
}

}  // namespace

double PointTriangleTimeOfImpact(const Eigen::Vector3d& p0, const Eigen::Vector3d& a0,
                                 const Eigen::Vector3d& b0, const Eigen::Vector3d& c0,
                                 const Eigen::Vector3d& p1, const Eigen::Vector3d& a1,
                                 const Eigen::Vector3d& b1, const Eigen::Vector3d& c1,
                                 double margin) {
  const Eigen::Vector3d x[4] = {p0, a0, b0, c0};
  const Eigen::Vector3d dx[4] = {p1 - p0, a1 - a0, b1 - b0, c1 - c0};
  return Advance(x, dx, 1, margin, [](const Eigen::Vector3d* y) {
    return PointTriangleDistance(y[0], y[1], y[2], y[3]).distance;
  });
}

double EdgeEdgeTimeOfImpact(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                            const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                            const Eigen::Vector3d& a0_end, const Eigen::Vector3d& a1_end,
                            const Eigen::Vector3d& b0_end, const Eigen::Vector3d& b1_end,
                            double margin) {
  const Eigen::Vector3d x[4] = {a0, a1, b0, b1};
  const Eigen::Vector3d dx[4] = {a0_end - a0, a1_end - a1, b0_end - b0, b1_end - b1};
  return Advance(x, dx, 2, margin, [](const Eigen::Vector3d* y) {
    return SegmentSegmentDistance(y[0], y[1], y[2], y[3]).distance;
  });
}

}  // namespace ipstep
