#include "contact/obstacle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "contact/point_triangle.h"
#include "contact/segment_parameter.h"
#include "contact/segment_segment.h"

namespace ipstep {

const char* ObstacleTypeName(ObstacleType type) {
  switch (type) {
    case ObstacleType::kPlane:
      return "plane";
    case ObstacleType::kSphere:
      return "sphere";
    case ObstacleType::kBox:
      return "box";
  }
  return "unknown";
}

double Obstacle::Distance(const Eigen::Vector3d& x, double t, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d y = x - velocity * t;  // in the obstacle's frame at time 0
  switch (type) {
    case ObstacleType::kPlane:
      if (gradient) *gradient = normal;
      return normal.dot(y - point);
    case ObstacleType::kSphere: {
      const Eigen::Vector3d r = y - point;
      const double norm = r.norm();
      if (gradient) {
        *gradient = Eigen::Vector3d::Zero();
        if (norm > 0.0) {
          *gradient = r / norm;
        } else {
          (*gradient)[0] = 1.0;  // any direction at the centre
        }
      }
      return norm - radius;
    }
    case ObstacleType::kBox: {
      Eigen::Vector3d outside = Eigen::Vector3d::Zero();
      bool inside = true;
      for (int k = 0; k < dimension; ++k) {
        if (y[k] < lower[k]) {
          outside[k] = y[k] - lower[k];
          inside = false;
        } else if (y[k] > upper[k]) {
          outside[k] = y[k] - upper[k];
          inside = false;
        }
      }
      if (!inside) {
        const double norm = outside.norm();
        if (gradient) *gradient = outside / norm;
        return norm;
      }
      // Inside: minus the distance to the nearest face.
      double best = std::numeric_limits<double>::infinity();
      Eigen::Vector3d direction = Eigen::Vector3d::Zero();
      for (int k = 0; k < dimension; ++k) {
        if (y[k] - lower[k] < best) {
          best = y[k] - lower[k];
          direction = -Eigen::Vector3d::Unit(k);
        }
        if (upper[k] - y[k] < best) {
          best = upper[k] - y[k];
          direction = Eigen::Vector3d::Unit(k);
        }
      }
      if (gradient) *gradient = direction;
      return -best;
    }
  }
  return 0.0;
}

namespace {

// Entry fraction of the segment y0 -> y1 into the box [lo, hi] (slab method).
double SegmentBoxEntry(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                       const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int dimension) {
  double enter = 0.0, leave = 1.0;
  bool start_inside = true;
  for (int k = 0; k < dimension; ++k) {
    if (y0[k] < lo[k] || y0[k] > hi[k]) start_inside = false;
  }
  if (start_inside) return 0.0;
  for (int k = 0; k < dimension; ++k) {
    const double delta = y1[k] - y0[k];
    if (delta == 0.0) {
      if (y0[k] < lo[k] || y0[k] > hi[k]) return Obstacle::kNoImpact;
      continue;
    }
    double s0 = (lo[k] - y0[k]) / delta, s1 = (hi[k] - y0[k]) / delta;
    if (s0 > s1) std::swap(s0, s1);
    enter = std::max(enter, s0);
    leave = std::min(leave, s1);
    if (enter > leave) return Obstacle::kNoImpact;
  }
  return enter;
}

}  // namespace

double Obstacle::TimeOfImpact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_a,
                              double t_b, double margin) const {
  const Eigen::Vector3d y0 = a - velocity * t_a;
  const Eigen::Vector3d y1 = b - velocity * t_b;
  switch (type) {
    case ObstacleType::kPlane: {
      const double f0 = normal.dot(y0 - point) - margin;
      const double f1 = normal.dot(y1 - point) - margin;
      if (f0 <= 0.0) return 0.0;
      if (f1 > 0.0) return kNoImpact;
      return std::clamp(f0 / (f0 - f1), 0.0, 1.0);
    }
    case ObstacleType::kSphere: {
      // |y0 - c + s (y1 - y0)|^2 = R^2, R = radius + margin.
      const double reach = radius + margin;
      const Eigen::Vector3d q = y0 - point, e = y1 - y0;
      const double c = q.squaredNorm() - reach * reach;
      if (c <= 0.0) return 0.0;
      const double a2 = e.squaredNorm();
      const double b2 = q.dot(e);
      if (a2 == 0.0 || b2 >= 0.0) return kNoImpact;  // not approaching
      const double discriminant = b2 * b2 - a2 * c;
      if (discriminant < 0.0) return kNoImpact;
      // Smaller root, written to avoid cancellation: s = c / (-b2 + sqrt(disc)).
      const double s = c / (-b2 + std::sqrt(discriminant));
      return s <= 1.0 ? std::max(s, 0.0) : kNoImpact;
    }
    case ObstacleType::kBox: {
      const Eigen::Vector3d grow = Eigen::Vector3d::Constant(margin);
      return SegmentBoxEntry(y0, y1, lower - grow, upper + grow, dimension);
    }
  }
  return kNoImpact;
}

double PointSegmentDistance(const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double* alpha) {
  const double s = ClosestSegmentParameter(c, a, b);
  if (alpha) *alpha = s;
  return (a + s * (b - a) - c).norm();
}

int Obstacle::NumEdgeFeatures() const {
  switch (type) {
    case ObstacleType::kSphere:
      return 1;
    case ObstacleType::kBox:
      return dimension == 2 ? 4 : 0;
    case ObstacleType::kPlane:
      return 0;
  }
  return 0;
}

Eigen::Vector3d Obstacle::EdgeFeature(int feature, double t) const {
  Eigen::Vector3d c = point;
  if (type == ObstacleType::kBox) {
    c = Eigen::Vector3d((feature & 1 ? upper : lower)[0], (feature & 2 ? upper : lower)[1], 0.0);
  }
  return c + velocity * t;
}

double Obstacle::EdgeDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              double t, Eigen::Vector3d* grad_a, Eigen::Vector3d* grad_b) const {
  const double r = type == ObstacleType::kSphere ? radius : 0.0;
  const Eigen::Vector3d c = EdgeFeature(feature, t);
  double alpha = 0.0;
  const double distance = PointSegmentDistance(c, a, b, &alpha);
  if (grad_a != nullptr || grad_b != nullptr) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    if (distance > 0.0) n = (a + alpha * (b - a) - c) / distance;
    if (grad_a) *grad_a = (1.0 - alpha) * n;
    if (grad_b) *grad_b = alpha * n;
  }
  return distance - r;
}

double Obstacle::EdgePointDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   double alpha, double t, Eigen::Vector3d* grad_a,
                                   Eigen::Vector3d* grad_b) const {
  const double r = type == ObstacleType::kSphere ? radius : 0.0;
  const Eigen::Vector3d y = a + alpha * (b - a) - EdgeFeature(feature, t);
  const double distance = y.norm();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  if (distance > 0.0) n = y / distance;
  if (grad_a) *grad_a = (1.0 - alpha) * n;
  if (grad_b) *grad_b = alpha * n;
  return distance - r;
}

namespace {

double Horner(const double* p, int n, double s) {
  double v = p[n];
  for (int k = n - 1; k >= 0; --k) v = v * s + p[k];
  return v;
}

// Real roots in [0, 1] of p[0] + p[1] s + ... + p[n] s^n (n <= 4), where the
// polynomial changes sign or vanishes: the critical points (roots of p')
// split [0, 1] into monotone pieces, each bisected. Appends to `roots`.
void UnitRoots(const double* p, int n, std::vector<double>* roots) {
  double scale = 0.0;
  for (int k = 0; k <= n; ++k) scale = std::max(scale, std::abs(p[k]));
  if (scale == 0.0) return;
  while (n > 0 && std::abs(p[n]) <= 1e-14 * scale) --n;
  if (n == 0) return;
  if (n == 1) {
    const double s = -p[0] / p[1];
    if (s >= 0.0 && s <= 1.0) roots->push_back(s);
    return;
  }
  double derivative[4];
  for (int k = 0; k < n; ++k) derivative[k] = (k + 1) * p[k + 1];
  std::vector<double> points = {0.0};
  UnitRoots(derivative, n - 1, &points);
  points.push_back(1.0);
  std::sort(points.begin(), points.end());
  for (size_t k = 0; k + 1 < points.size(); ++k) {
    double lo = points[k], hi = points[k + 1];
    double f_lo = Horner(p, n, lo);
    const double f_hi = Horner(p, n, hi);
    if (f_lo == 0.0) {
      roots->push_back(lo);
      continue;
    }
    if ((f_lo < 0.0) == (f_hi < 0.0) || f_hi == 0.0) continue;
    for (int iteration = 0; iteration < 200 && lo < hi; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      const double f_mid = Horner(p, n, mid);
      if ((f_mid < 0.0) == (f_lo < 0.0)) {
        lo = mid;
        f_lo = f_mid;
      } else {
        hi = mid;
      }
    }
    roots->push_back(lo);  // the last point on the starting side
  }
  if (Horner(p, n, 1.0) == 0.0) roots->push_back(1.0);
}

// Coefficients (ascending) of the product of two polynomials.
template <size_t N, size_t M>
std::array<double, N + M - 1> Multiply(const std::array<double, N>& a,
                                       const std::array<double, M>& b) {
  std::array<double, N + M - 1> c{};
  for (size_t i = 0; i < N; ++i) {
    for (size_t j = 0; j < M; ++j) c[i + j] += a[i] * b[j];
  }
  return c;
}

// u(s) . v(s) for u = u0 + s u1, v = v0 + s v1.
std::array<double, 3> DotPoly(const Eigen::Vector3d& u0, const Eigen::Vector3d& u1,
                              const Eigen::Vector3d& v0, const Eigen::Vector3d& v1) {
  return {u0.dot(v0), u0.dot(v1) + u1.dot(v0), u1.dot(v1)};
}

}  // namespace

double Obstacle::EdgeTimeOfImpact(int feature, const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                  const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, double t0,
                                  double t1, double margin) const {
  // In the obstacle's frame: the feature c is fixed, the end points move
  // linearly: q(s) = c - a(s) = q0 + s q1, e(s) = b(s) - a(s) = e0 + s e1.
  const Eigen::Vector3d c = EdgeFeature(feature, 0.0);
  const double r = type == ObstacleType::kSphere ? radius : 0.0;
  const Eigen::Vector3d ya = a0 - velocity * t0, da = (a1 - velocity * t1) - ya;
  const Eigen::Vector3d yb = b0 - velocity * t0, db = (b1 - velocity * t1) - yb;
  auto gap = [&](double s) { return PointSegmentDistance(c, ya + s * da, yb + s * db) - r; };
  const double d0 = gap(0.0);
  if (!(d0 > margin)) return 0.0;
  const double bound = std::max(da.norm(), db.norm());
  const double goal = std::max(margin, kEdgeGapFraction * d0);
  if (d0 - bound > goal) return kNoImpact;  // every point moves by at most `bound`
  // The first s with gap(s) <= goal lies where the distance to an end point or
  // (closest point inside) to the line reaches R' = r + goal, or where the
  // closest point changes piece: candidates are the roots in [0, 1] of
  //   |c - a|^2 - R'^2, |c - b|^2 - R'^2                         (quadratics)
  //   |e x q|^2 - R'^2 |e|^2                                      (quartic)
  //   q . e,  q . e - |e|^2                                       (quadratics)
  const double reach2 = (r + goal) * (r + goal);
  const Eigen::Vector3d q0 = c - ya, q1 = -da, e0 = yb - ya, e1 = db - da;
  const Eigen::Vector3d p0 = c - yb, p1 = -db;
  std::vector<double> candidates;
  std::array<double, 3> ends[2] = {DotPoly(q0, q1, q0, q1), DotPoly(p0, p1, p0, p1)};
  for (auto& poly : ends) {
    poly[0] -= reach2;
    UnitRoots(poly.data(), 2, &candidates);
  }
  const std::array<double, 3> ee = DotPoly(e0, e1, e0, e1);
  std::array<double, 3> qe = DotPoly(q0, q1, e0, e1);
  UnitRoots(qe.data(), 2, &candidates);
  for (int k = 0; k < 3; ++k) qe[k] -= ee[k];
  UnitRoots(qe.data(), 2, &candidates);
  // e x q = w0 + s w1 + s^2 w2.
  const Eigen::Vector3d w0 = e0.cross(q0), w1 = e0.cross(q1) + e1.cross(q0), w2 = e1.cross(q1);
  std::array<double, 5> interior{};
  for (int k = 0; k < 3; ++k) {
    const std::array<double, 3> component = {w0[k], w1[k], w2[k]};
    const auto square = Multiply(component, component);
    for (int m = 0; m < 5; ++m) interior[m] += square[m];
  }
  for (int k = 0; k < 3; ++k) interior[k] -= reach2 * ee[k];
  UnitRoots(interior.data(), 4, &candidates);
  candidates.push_back(1.0);
  std::sort(candidates.begin(), candidates.end());
  // Walk the candidates in order; between two of them the gap is checked at the
  // midpoint too (a guard against a missed root: the path is then refused from
  // the previous candidate on, conservatively).
  const double accept = goal * (1.0 + 1e-9);
  double previous = 0.0;
  for (double s : candidates) {
    if (gap(0.5 * (previous + s)) <= goal) return previous;
    if (gap(s) <= accept) return s;
    previous = s;
  }
  return kNoImpact;
}

}  // namespace ipstep
