#include "geometry/point_edge.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ipstep {

namespace {

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u[0] * v[1] - u[1] * v[0];
}

// Real roots of c0 + c1 s + c2 s^2 in [0, 1], ascending (at most 2).
int RootsInUnitInterval(double c0, double c1, double c2, std::array<double, 2>* roots) {
  int count = 0;
  auto keep = [&](double s) {
    if (s >= 0.0 && s <= 1.0) (*roots)[count++] = s;
  };
  const double scale = std::abs(c0) + std::abs(c1) + std::abs(c2);
  if (scale == 0.0) {
    (*roots)[count++] = 0.0;  // identically zero: collinear throughout
    return count;
  }
  if (std::abs(c2) <= 1e-14 * scale) {
    if (c1 != 0.0) keep(-c0 / c1);
    return count;
  }
  const double discriminant = c1 * c1 - 4.0 * c2 * c0;
  if (discriminant < 0.0) return 0;
  const double root = std::sqrt(discriminant);
  // Numerically stable pair of roots.
  const double q = -0.5 * (c1 + (c1 >= 0.0 ? root : -root));
  double s0 = q / c2;
  double s1 = q != 0.0 ? c0 / q : s0;
  if (s0 > s1) std::swap(s0, s1);
  keep(s0);
  if (s1 != s0) keep(s1);
  return count;
}

}  // namespace

PointEdgeDistanceResult PointEdgeDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                          const Eigen::Vector2d& b) {
  PointEdgeDistanceResult r;
  const Eigen::Vector2d e = b - a;
  const double length2 = e.squaredNorm();
  double alpha = length2 > 0.0 ? (p - a).dot(e) / length2 : 0.0;
  if (alpha <= 0.0 || alpha >= 1.0 || length2 == 0.0) {
    // Closest to an end point: d = |p - end|.
    const bool at_a = alpha <= 0.5 || length2 == 0.0;
    alpha = at_a ? 0.0 : 1.0;
    const Eigen::Vector2d diff = p - (at_a ? a : b);
    r.distance = diff.norm();
    r.alpha = alpha;
    if (r.distance > 0.0) {
      r.grad_p = diff / r.distance;
      (at_a ? r.grad_a : r.grad_b) = -r.grad_p;
    }
    return r;
  }
  // Interior: d = |cross(e, p - a)| / |e|.
  const double length = std::sqrt(length2);
  const double cross = Cross(e, p - a);
  r.alpha = alpha;
  r.distance = std::abs(cross) / length;
  if (r.distance == 0.0) return r;
  const double sign = cross > 0.0 ? 1.0 : -1.0;
  // n: unit normal of the edge on p's side; d = n . (p - a).
  const Eigen::Vector2d n = sign * Eigen::Vector2d(-e[1], e[0]) / length;
  r.grad_p = n;
  // d(d)/da and d(d)/db: with c = cross(b - a, p - a),
  // dc/da = (b_y - p_y, p_x - b_x), dc/db = (a_y - p_y, p_x - a_x) rotated
  // appropriately; d(|e|)/db = e/|e| = -d(|e|)/da.
  const Eigen::Vector2d dc_da(b[1] - p[1], p[0] - b[0]);
  const Eigen::Vector2d dc_db(p[1] - a[1], a[0] - p[0]);
  const Eigen::Vector2d de_db = e / length;
  r.grad_a = sign * dc_da / length + r.distance * de_db / length;
  r.grad_b = sign * dc_db / length - r.distance * de_db / length;
  return r;
}

double PointEdgeTimeOfImpact(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1,
                             const Eigen::Vector2d& a0, const Eigen::Vector2d& a1,
                             const Eigen::Vector2d& b0, const Eigen::Vector2d& b1) {
  // c(s) = cross(e(s), q(s)), e = b - a, q = p - a, both linear in s.
  const Eigen::Vector2d e0 = b0 - a0, de = (b1 - a1) - e0;
  const Eigen::Vector2d q0 = p0 - a0, dq = (p1 - a1) - q0;
  const double c0 = Cross(e0, q0);
  const double c1 = Cross(e0, dq) + Cross(de, q0);
  const double c2 = Cross(de, dq);
  std::array<double, 2> roots{};
  const int count = RootsInUnitInterval(c0, c1, c2, &roots);
  for (int k = 0; k < count; ++k) {
    const double s = roots[k];
    const Eigen::Vector2d e = e0 + s * de, q = q0 + s * dq;
    const double length2 = e.squaredNorm();
    if (length2 == 0.0) {
      if (q.squaredNorm() == 0.0) return s;
      continue;
    }
    const double alpha = q.dot(e) / length2;
    // A little slack: a point sliding exactly over an end point counts as a hit.
    if (alpha >= -1e-12 && alpha <= 1.0 + 1e-12) return s;
  }
  // Identically collinear paths: check the end points' projections over time.
  if (c0 == 0.0 && c1 == 0.0 && c2 == 0.0) {
    for (double s : {0.0, 1.0}) {
      const Eigen::Vector2d e = e0 + s * de, q = q0 + s * dq;
      const double alpha = e.squaredNorm() > 0.0 ? q.dot(e) / e.squaredNorm() : 0.0;
      if (alpha >= 0.0 && alpha <= 1.0) return s;
    }
  }
  return kNoPointEdgeImpact;
}

bool SegmentsIntersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  auto on_segment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                       const Eigen::Vector2d& r) {
    return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
           std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
  };
  if (d1 == 0 && on_segment(a, b, c)) return true;
  if (d2 == 0 && on_segment(a, b, d)) return true;
  if (d3 == 0 && on_segment(c, d, a)) return true;
  if (d4 == 0 && on_segment(c, d, b)) return true;
  return false;
}

}  // namespace ipstep
