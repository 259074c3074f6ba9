#include "geometry/point_triangle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "geometry/segment_parameter.h"

namespace ipstep {

PointTriangleDistanceResult PointTriangleDistance(const Eigen::Vector3d& p,
                                                  const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b,
                                                  const Eigen::Vector3d& c) {
  PointTriangleDistanceResult r;
  const Eigen::Vector3d e0 = b - a, e1 = c - a, v = p - a;
  const double d00 = e0.squaredNorm(), d01 = e0.dot(e1), d11 = e1.squaredNorm();
  const double det = d00 * d11 - d01 * d01;  // |e0 x e1|^2
  bool inside = false;
  if (det > 1e-14 * d00 * d11) {
    // Projection q = a + beta e0 + gamma e1 with (q - p) orthogonal to e0, e1:
    //   [d00 d01; d01 d11] [beta; gamma] = [v.e0; v.e1].
    const double v0 = v.dot(e0), v1 = v.dot(e1);
    const double beta = (d11 * v0 - d01 * v1) / det;
    const double gamma = (d00 * v1 - d01 * v0) / det;
    if (beta >= 0.0 && gamma >= 0.0 && beta + gamma <= 1.0) {
      r.weights = Eigen::Vector3d(1.0 - beta - gamma, beta, gamma);
      inside = true;
    }
  }
  if (!inside) {
    // On the boundary: the closest of the three edges.
    const Eigen::Vector3d* corners[3] = {&a, &b, &c};
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const int i = k, j = (k + 1) % 3;
      const double s = ClosestSegmentParameter(p, *corners[i], *corners[j]);
      const double d2 = (*corners[i] + s * (*corners[j] - *corners[i]) - p).squaredNorm();
      if (d2 < best) {
        best = d2;
        r.weights.setZero();
        r.weights[i] = 1.0 - s;
        r.weights[j] = s;
      }
    }
  }
  PointTrianglePointDistance(p, a, b, c, r.weights, &r.grad_a, &r.grad_b, &r.grad_c);
  const Eigen::Vector3d q = r.weights[0] * a + r.weights[1] * b + r.weights[2] * c;
  r.distance = (q - p).norm();
  if (r.distance > 0.0) r.grad_p = (p - q) / r.distance;
  return r;
}

double PointTrianglePointDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                                  const Eigen::Vector3d& w, Eigen::Vector3d* grad_a,
                                  Eigen::Vector3d* grad_b, Eigen::Vector3d* grad_c) {
  const Eigen::Vector3d y = w[0] * a + w[1] * b + w[2] * c - p;
  const double distance = y.norm();
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  if (distance > 0.0) n = y / distance;
  if (grad_a) *grad_a = w[0] * n;
  if (grad_b) *grad_b = w[1] * n;
  if (grad_c) *grad_c = w[2] * n;
  return distance;
}

bool SegmentIntersectsTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                               const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double sp = n.dot(p - a), sq = n.dot(q - a);
  if ((sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0)) return false;
  if (sp == 0.0 && sq == 0.0) {
    // In the plane: it meets the triangle iff an end point is inside or it
    // crosses an edge, i.e. iff its distance to the triangle is zero: the
    // distance from [p, q] is at most that of the end points, and crossing an
    // edge means touching that edge's segment.
    if (PointTriangleDistance(p, a, b, c).distance == 0.0) return true;
    const Eigen::Vector3d* corners[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& u = *corners[k];
      const Eigen::Vector3d& v = *corners[(k + 1) % 3];
      // Coplanar segments [p, q] and [u, v] intersect iff each one's end points
      // are not strictly on the same side of the other's line (in the plane).
      const double s1 = n.dot((v - u).cross(p - u)), s2 = n.dot((v - u).cross(q - u));
      const double s3 = n.dot((q - p).cross(u - p)), s4 = n.dot((q - p).cross(v - p));
      if ((s1 > 0.0 && s2 > 0.0) || (s1 < 0.0 && s2 < 0.0)) continue;
      if ((s3 > 0.0 && s4 > 0.0) || (s3 < 0.0 && s4 < 0.0)) continue;
      if (s1 == 0.0 && s2 == 0.0) {
        // Collinear: overlapping projections onto the line.
        const Eigen::Vector3d d = v - u;
        const double tp = (p - u).dot(d), tq = (q - u).dot(d), l2 = d.squaredNorm();
        if (std::max(tp, tq) < 0.0 || std::min(tp, tq) > l2) continue;
      }
      return true;
    }
    return false;
  }
  // The crossing point of the plane, inside the triangle iff it is on the
  // inner side of all three edges.
  const Eigen::Vector3d x = p + (sp / (sp - sq)) * (q - p);
  const double s0 = n.dot((b - a).cross(x - a));
  const double s1 = n.dot((c - b).cross(x - b));
  const double s2 = n.dot((a - c).cross(x - c));
  return s0 >= 0.0 && s1 >= 0.0 && s2 >= 0.0;
}

}  // namespace ipstep
