// The obstacle interface's shared part (contact/obstacle.h): an edge against
// the obstacle's edge features (distance and continuous collision detection),
// the same for every shape. Faces and box edges: obstacle_mesh_features.cc.
#include "contact/obstacle.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/segment_parameter.h"

namespace ipstep {

Obstacle::Obstacle(int dimension, const Eigen::Vector3d& velocity, std::string name)
    : dimension_(dimension), name_(std::move(name)) {
  motion_.velocity = velocity;
}

double Obstacle::RotatedDistance(const Eigen::Vector3d& x, double t,
                                 Eigen::Vector3d* gradient) const {
  const double d = RestDistance(ToRest(x, t), gradient);
  if (gradient) *gradient = motion_.Rotation(t) * *gradient;  // d/dx = R d/dy
  return d;
}

bool Obstacle::DistanceHessian(const Eigen::Vector3d& x, double t, Eigen::Matrix3d* hessian) const {
  if (!rotates()) return RestDistanceHessian(x - Shift(t), hessian);
  if (!RestDistanceHessian(ToRest(x, t), hessian)) return false;
  const Eigen::Matrix3d r = motion_.Rotation(t);
  *hessian = r * *hessian * r.transpose();
  return true;
}

double Obstacle::RestPathBound(const Eigen::Vector3d* x0, const Eigen::Vector3d* x1, int n,
                               double t0, double t1) const {
  double bound = 0.0;
  if (!rotates()) {
    const Eigen::Vector3d shift0 = Shift(t0), shift1 = Shift(t1);
    for (int k = 0; k < n; ++k)
      bound = std::max(bound, ((x1[k] - shift1) - (x0[k] - shift0)).norm());
    return bound;
  }
  // The rate of tau per unit s: |t1 - t0| while the obstacle moves in part of
  // the interval (all of it unless until() lies inside), 0 once it stopped.
  const double rate = until() <= std::min(t0, t1) ? 0.0 : std::abs(t1 - t0);
  const Eigen::Vector3d o0 = motion_.Center(t0), o1 = motion_.Center(t1);
  double radius = 0.0;
  for (int k = 0; k < n; ++k) {
    bound = std::max(bound, (x1[k] - x0[k]).norm());
    radius = std::max({radius, (x0[k] - o0).norm(), (x1[k] - o1).norm()});
  }
  return bound + rate * (velocity().norm() + angular_velocity().norm() * radius);
}

double Obstacle::DistanceChangeBound(double t0, double t1, double radius) const {
  if (!rotates()) return (Shift(t1) - Shift(t0)).norm();
  const double dtau = std::abs(std::min(t1, until()) - std::min(t0, until()));
  const double shift = velocity().norm() * dtau;
  return shift + angular_velocity().norm() * dtau * (radius + shift);
}

double Obstacle::RotatedTimeOfImpact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_a,
                                     double t_b, double margin) const {
  auto gap = [&](double s) {
    return RestDistance(ToRest(a + s * (b - a), t_a + s * (t_b - t_a)), nullptr);
  };
  return Advance(gap, RestPathBound(&a, &b, 1, t_a, t_b), margin);
}

double PointSegmentDistance(const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double* alpha) {
  const double s = ClosestSegmentParameter(c, a, b);
  if (alpha) *alpha = s;
  return (a + s * (b - a) - c).norm();
}

double Obstacle::EdgeDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              double t, Eigen::Vector3d* grad_a, Eigen::Vector3d* grad_b) const {
  const double r = FeatureRadius();
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
  const double r = FeatureRadius();
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
  const double r = FeatureRadius();
  if (CurvedPath(t0, t1)) {
    // The rest-frame paths are curved: conservative advancement.
    const Eigen::Vector3d c = RestFeature(feature);
    const Eigen::Vector3d x0[2] = {a0, b0}, x1[2] = {a1, b1};
    auto gap = [&](double s) {
      const double t = t0 + s * (t1 - t0);
      return PointSegmentDistance(c, ToRest(a0 + s * (a1 - a0), t), ToRest(b0 + s * (b1 - b0), t)) -
             r;
    };
    return Advance(gap, RestPathBound(x0, x1, 2, t0, t1), margin);
  }
  // In the obstacle's frame: the feature c is fixed, the end points move
  // linearly: q(s) = c - a(s) = q0 + s q1, e(s) = b(s) - a(s) = e0 + s e1.
  const Eigen::Vector3d c = RestFeature(feature);
  const Eigen::Vector3d ya = ToRest(a0, t0), da = ToRest(a1, t1) - ya;
  const Eigen::Vector3d yb = ToRest(b0, t0), db = ToRest(b1, t1) - yb;
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
