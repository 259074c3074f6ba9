#include "geometry/segment_segment.h"

#include <algorithm>
#include <limits>

#include "geometry/segment_parameter.h"

namespace ipstep {

SegmentSegmentDistanceResult SegmentSegmentDistance(const Eigen::Vector3d& a0,
                                                    const Eigen::Vector3d& a1,
                                                    const Eigen::Vector3d& b0,
                                                    const Eigen::Vector3d& b1) {
  SegmentSegmentDistanceResult r;
  const Eigen::Vector3d u = a1 - a0, v = b1 - b0, w = a0 - b0;
  // f(s, t) = |w + s u - t v|^2; stationary point:
  //   [uu -uv; uv -vv] [s; t] = [-uw; -vw],  det = uu vv - uv^2 = |u x v|^2.
  const double uu = u.squaredNorm(), uv = u.dot(v), vv = v.squaredNorm();
  const double uw = u.dot(w), vw = v.dot(w);
  const double det = uu * vv - uv * uv;
  bool inside = false;
  if (det > 1e-14 * uu * vv) {
    const double s = (uv * vw - vv * uw) / det;
    const double t = (uu * vw - uv * uw) / det;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0) {
      r.s = s;
      r.t = t;
      inside = true;
    }
  }
  if (!inside) {
    // Boundary of [0, 1]^2: s = 0, s = 1 (end points of A against B) and
    // t = 0, t = 1 (end points of B against A).
    double best = std::numeric_limits<double>::infinity();
    auto consider = [&](double s, double t) {
      const double d2 = (a0 + s * u - b0 - t * v).squaredNorm();
      if (d2 < best) {
        best = d2;
        r.s = s;
        r.t = t;
      }
    };
    consider(0.0, ClosestSegmentParameter(a0, b0, b1));
    consider(1.0, ClosestSegmentParameter(a1, b0, b1));
    consider(ClosestSegmentParameter(b0, a0, a1), 0.0);
    consider(ClosestSegmentParameter(b1, a0, a1), 1.0);
  }
  const Eigen::Vector3d y = a0 + r.s * u - b0 - r.t * v;
  r.distance = y.norm();
  if (r.distance > 0.0) {
    const Eigen::Vector3d n = y / r.distance;
    r.grad_a0 = (1.0 - r.s) * n;
    r.grad_a1 = r.s * n;
    r.grad_b0 = -(1.0 - r.t) * n;
    r.grad_b1 = -r.t * n;
  }
  return r;
}

}  // namespace ipstep
