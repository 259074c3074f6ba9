// Obstacle's 3D features (contact/obstacle.h): face features (a sphere's
// centre, a 3D box's corners) against triangles, and a 3D box's edges against
// segments, with their conservative-advancement time of impact; the same for
// every shape (the shapes give the features at rest).
#include <algorithm>
#include <cmath>

#include "contact/obstacle.h"
#include "geometry/conservative_advancement.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"

namespace ipstep {

double Obstacle::FaceDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& c, double t, Eigen::Vector3d* grad,
                              Eigen::Vector3d* weights) const {
  const PointTriangleDistanceResult r = PointTriangleDistance(FaceFeature(feature, t), a, b, c);
  if (grad) {
    grad[0] = r.grad_a;
    grad[1] = r.grad_b;
    grad[2] = r.grad_c;
  }
  if (weights) *weights = r.weights;
  return r.distance - FeatureRadius();
}

double Obstacle::FacePointDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c, const Eigen::Vector3d& w, double t,
                                   Eigen::Vector3d* grad) const {
  Eigen::Vector3d g[3];
  const double d =
      PointTrianglePointDistance(FaceFeature(feature, t), a, b, c, w, &g[0], &g[1], &g[2]);
  if (grad) {
    for (int k = 0; k < 3; ++k) grad[k] = g[k];
  }
  return d - FeatureRadius();
}

double Obstacle::FaceTimeOfImpact(int feature, const Eigen::Vector3d* v0, const Eigen::Vector3d* v1,
                                  double t0, double t1, double margin) const {
  const double r = FeatureRadius();
  if (CurvedPath(t0, t1)) {
    // The rest-frame paths are curved; the bound covers them.
    const Eigen::Vector3d c = RestFeature(feature);
    auto gap = [&](double s) {
      const double t = t0 + s * (t1 - t0);
      Eigen::Vector3d y[3];
      for (int k = 0; k < 3; ++k) y[k] = ToRest(v0[k] + s * (v1[k] - v0[k]), t);
      return PointTriangleDistance(c, y[0], y[1], y[2]).distance - r;
    };
    return Advance(gap, RestPathBound(v0, v1, 3, t0, t1), margin);
  }
  // In the obstacle's frame the feature is fixed and the vertices move
  // linearly: y_i(s) = y_i0 + s dy_i.
  const Eigen::Vector3d c = RestFeature(feature);
  Eigen::Vector3d y[3], dy[3];
  double bound = 0.0;
  for (int k = 0; k < 3; ++k) {
    y[k] = ToRest(v0[k], t0);
    dy[k] = ToRest(v1[k], t1) - y[k];
    bound = std::max(bound, dy[k].norm());
  }
  auto gap = [&](double s) {
    return PointTriangleDistance(c, y[0] + s * dy[0], y[1] + s * dy[1], y[2] + s * dy[2]).distance -
           r;
  };
  return Advance(gap, bound, margin);
}

void Obstacle::BoxEdge(int edge, double t, Eigen::Vector3d* p, Eigen::Vector3d* q) const {
  RestBoxEdge(edge, p, q);
  *p = ToWorld(*p, t);
  *q = ToWorld(*q, t);
}

double Obstacle::BoxEdgeDistance(int edge, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 double t, Eigen::Vector3d* grad_a, Eigen::Vector3d* grad_b,
                                 double* s) const {
  Eigen::Vector3d p, q;
  BoxEdge(edge, t, &p, &q);
  const SegmentSegmentDistanceResult r = SegmentSegmentDistance(a, b, p, q);
  if (grad_a) *grad_a = r.grad_a0;
  if (grad_b) *grad_b = r.grad_a1;
  if (s) *s = r.s;
  return r.distance;
}

double Obstacle::BoxEdgeTimeOfImpact(int edge, const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                                     const Eigen::Vector3d& b0, const Eigen::Vector3d& b1,
                                     double t0, double t1, double margin) const {
  Eigen::Vector3d p, q;
  RestBoxEdge(edge, &p, &q);
  if (CurvedPath(t0, t1)) {
    const Eigen::Vector3d x0[2] = {a0, b0}, x1[2] = {a1, b1};
    auto gap = [&](double s) {
      const double t = t0 + s * (t1 - t0);
      return SegmentSegmentDistance(ToRest(a0 + s * (a1 - a0), t), ToRest(b0 + s * (b1 - b0), t), p,
                                    q)
          .distance;
    };
    return Advance(gap, RestPathBound(x0, x1, 2, t0, t1), margin);
  }
  const Eigen::Vector3d ya = ToRest(a0, t0), da = ToRest(a1, t1) - ya;
  const Eigen::Vector3d yb = ToRest(b0, t0), db = ToRest(b1, t1) - yb;
  auto gap = [&](double s) {
    return SegmentSegmentDistance(ya + s * da, yb + s * db, p, q).distance;
  };
  return Advance(gap, std::max(da.norm(), db.norm()), margin);
}

}  // namespace ipstep
