#include "geometry/triangle_intersection.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "geometry/exact_orientation.h"

namespace ipstep {

namespace {

int Orientation2(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                 int i, int j) {
  return ExactOrient2d(a, b, c, i, j);
}

// Closed 2D segments [p, q], [u, v] (coordinates i, j) intersect.
bool Segments2Intersect(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                        const Eigen::Vector3d& u, const Eigen::Vector3d& v, int i, int j) {
  const int o1 = Orientation2(p, q, u, i, j), o2 = Orientation2(p, q, v, i, j);
  const int o3 = Orientation2(u, v, p, i, j), o4 = Orientation2(u, v, q, i, j);
  if (o1 * o2 > 0 || o3 * o4 > 0) return false;
  if (o1 == 0 && o2 == 0) {
    // Collinear: overlapping extents in both coordinates.
    for (int k : {i, j}) {
      if (std::max(p[k], q[k]) < std::min(u[k], v[k]) ||
          std::max(u[k], v[k]) < std::min(p[k], q[k])) {
        return false;
      }
    }
  }
  return true;
}

// Point p in the closed 2D triangle (a, b, c).
bool Inside2(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& c, int i, int j) {
  const int o1 = Orientation2(a, b, p, i, j), o2 = Orientation2(b, c, p, i, j),
            o3 = Orientation2(c, a, p, i, j);
  const bool has_negative = o1 < 0 || o2 < 0 || o3 < 0;
  const bool has_positive = o1 > 0 || o2 > 0 || o3 > 0;
  return !(has_negative && has_positive);
}

}  // namespace

int Orientation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                const Eigen::Vector3d& d) {
  return ExactOrient3d(a, b, c, d);
}

bool SegmentTriangleIntersect(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                              const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c) {
  const int op = Orientation(a, b, c, p), oq = Orientation(a, b, c, q);
  if (op * oq > 0) return false;
  if (op != 0 || oq != 0) {
    const int s1 = Orientation(p, q, a, b), s2 = Orientation(p, q, b, c),
              s3 = Orientation(p, q, c, a);
    const bool has_negative = s1 < 0 || s2 < 0 || s3 < 0;
    const bool has_positive = s1 > 0 || s2 > 0 || s3 > 0;
    return !(has_negative && has_positive);
  }
  // Coplanar: drop the axis of the normal's largest component.
  const Eigen::Vector3d n = (b - a).cross(c - a);
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int i = (drop + 1) % 3, j = (drop + 2) % 3;
  if (Inside2(p, a, b, c, i, j) || Inside2(q, a, b, c, i, j)) return true;
  return Segments2Intersect(p, q, a, b, i, j) || Segments2Intersect(p, q, b, c, i, j) ||
         Segments2Intersect(p, q, c, a, i, j);
}

bool TrianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                        const Eigen::Vector3d& c0, const Eigen::Vector3d& a1,
                        const Eigen::Vector3d& b1, const Eigen::Vector3d& c1) {
  return SegmentTriangleIntersect(a0, b0, a1, b1, c1) ||
         SegmentTriangleIntersect(b0, c0, a1, b1, c1) ||
         SegmentTriangleIntersect(c0, a0, a1, b1, c1) ||
         SegmentTriangleIntersect(a1, b1, a0, b0, c0) ||
         SegmentTriangleIntersect(b1, c1, a0, b0, c0) ||
         SegmentTriangleIntersect(c1, a1, a0, b0, c0);
}

}  // namespace ipstep
