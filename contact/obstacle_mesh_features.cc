// Obstacle's 3D features (contact/obstacle.h): face features (a sphere's
// centre, a 3D box's corners) against triangles, and a 3D box's edges against
// segments, with their conservative-advancement time of impact; the same for
// every shape (the shapes give the features at rest).
#include <algorithm>
#include <cmath>

#include "contact/obstacle.h"
#include "contact/point_triangle.h"
#include "contact/segment_segment.h"

namespace ipstep {

namespace {

// Conservative advancement (see Obstacle::FaceTimeOfImpact): gap(s) is the
// distance of a primitive whose points move by at most `bound` over the path
// s in [0, 1], relative to the feature.
template <class Gap>
double ConservativeAdvancement(const Gap& gap, double bound, double margin) {
  const double d0 = gap(0.0);
  if (!(d0 > margin)) return 0.0;
  const double goal = std::max(margin, Obstacle::kEdgeGapFraction * d0);
  if (!(bound > 0.0) || d0 - bound > goal) return Obstacle::kNoImpact;
  // Stop once the gap is this close to the goal: the remaining advances would
  // shrink geometrically while the primitive approaches at less than `bound`.
  const double close = goal + 1e-2 * (d0 - goal);
  double s = 0.0, d = d0;
  for (int advance = 0; advance < Obstacle::kMaxAdvancements; ++advance) {
    // From s to s' every point moves by at most bound (s' - s), so the gap
    // stays >= d - bound (s' - s) >= goal.
    s += (d - goal) / bound;
    if (s >= 1.0) return Obstacle::kNoImpact;
    d = gap(s);
    if (d <= close) return s;
  }
  return s;
}

}  // namespace

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
  // In the obstacle's frame the feature is fixed and the vertices move
  // linearly: y_i(s) = y_i0 + s dy_i.
  const Eigen::Vector3d c = FaceFeature(feature, 0.0);
  const double r = FeatureRadius();
  Eigen::Vector3d y[3], dy[3];
  double bound = 0.0;
  for (int k = 0; k < 3; ++k) {
    y[k] = v0[k] - Shift(t0);
    dy[k] = (v1[k] - Shift(t1)) - y[k];
    bound = std::max(bound, dy[k].norm());
  }
  auto gap = [&](double s) {
    return PointTriangleDistance(c, y[0] + s * dy[0], y[1] + s * dy[1], y[2] + s * dy[2]).distance -
           r;
  };
  return ConservativeAdvancement(gap, bound, margin);
}

void Obstacle::BoxEdge(int edge, double t, Eigen::Vector3d* p, Eigen::Vector3d* q) const {
  RestBoxEdge(edge, p, q);
  *p += Shift(t);
  *q += Shift(t);
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
  BoxEdge(edge, 0.0, &p, &q);
  const Eigen::Vector3d ya = a0 - Shift(t0), da = (a1 - Shift(t1)) - ya;
  const Eigen::Vector3d yb = b0 - Shift(t0), db = (b1 - Shift(t1)) - yb;
  auto gap = [&](double s) {
    return SegmentSegmentDistance(ya + s * da, yb + s * db, p, q).distance;
  };
  return ConservativeAdvancement(gap, std::max(da.norm(), db.norm()), margin);
}

}  // namespace ipstep
