// Rigid obstacles for contact: the interface every shape implements
// (contact/obstacles/: plane, sphere / circle, axis-aligned box), in 2D or 3D,
// static or moving by the motion law of moving nodes (core/prescribed_motion.h):
// a translation with a constant velocity plus a rotation with a constant
// angular velocity about a centre that moves with it, until an optional stop
// time. The obstacle at time t is its shape at rest carried by that rigid
// motion, x = c + v tau + R(omega tau) (y - c), tau = min(t, until).
//
// The motion is handled here, once: every query at time t maps its points into
// the obstacle's frame at rest (ToRest) or its rest features out of it
// (ToWorld), and the shapes only answer at rest (the protected Rest* methods).
// Continuous collision detection works in that frame. Without rotation a point
// moving linearly while the obstacle translates linearly moves linearly
// relative to it, and the closed forms of the shapes apply; with rotation the
// relative path is curved, and every time of impact is found by conservative
// advancement (geometry/conservative_advancement.h) with the bound of
// RestPathBound. The motion is smooth on either side of the stop time, so a
// time interval [t_a, t_b] passed to the impact queries must not contain it in
// its interior (contact/obstacle_time.h splits there).
//
// Distances are signed (negative inside the obstacle).
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/prescribed_motion.h"
#include "geometry/conservative_advancement.h"

namespace ipstep {

class ObstacleVisitor;

class Obstacle {
 public:
  // Unused trailing components (z in 2D) of every vector are zero.
  Obstacle(int dimension, const Eigen::Vector3d& velocity, std::string name);
  virtual ~Obstacle() = default;

  // "plane", "sphere", "box" (for messages).
  virtual const char* type_name() const = 0;
  // Calls the visitor's overload for the concrete shape (io/ draws them so).
  virtual void Accept(ObstacleVisitor& visitor) const = 0;

  int dimension() const { return dimension_; }
  // The velocity while it moves (before until()).
  const Eigen::Vector3d& velocity() const { return motion_.velocity; }
  // The angular velocity [rad/s] (2D: about z) and the centre it turns about
  // (at time 0; it moves with the velocity).
  const Eigen::Vector3d& angular_velocity() const { return motion_.angular_velocity; }
  const Eigen::Vector3d& rotation_center() const { return motion_.center; }
  bool rotates() const { return !motion_.angular_velocity.isZero(0.0); }
  // Sets the rotation, before the obstacle is shared.
  void set_rotation(const Eigen::Vector3d& angular_velocity, const Eigen::Vector3d& center) {
    motion_.angular_velocity = angular_velocity;
    motion_.center = center;
  }
  // The time it stops at [s] (infinity: never).
  double until() const { return motion_.until; }
  // Sets the stop time (> 0), before the obstacle is shared.
  void set_until(double until) { motion_.until = until; }
  const std::string& name() const { return name_; }  // e.g. "contact.obstacles[0]"
  // Its own friction coefficient (scene key "mu"); none: the friction effect's.
  const std::optional<double>& friction_mu() const { return friction_mu_; }
  void set_friction_mu(double mu) { friction_mu_ = mu; }
  bool is_moving() const { return !motion_.is_still(); }
  // The velocity at time t of the obstacle's material point at x: v + omega x
  // (x - c - v tau) before until(), zero from then on.
  Eigen::Vector3d VelocityAt(const Eigen::Vector3d& x, double t) const {
    return motion_.Velocity(ToRest(x, t), t);
  }
  // The point y of the shape at rest that is at x at time t, and back. Without
  // rotation a shift by velocity * min(t, until).
  Eigen::Vector3d ToRest(const Eigen::Vector3d& x, double t) const {
    return rotates() ? motion_.InitialPosition(x, t) : Eigen::Vector3d(x - Shift(t));
  }
  Eigen::Vector3d ToWorld(const Eigen::Vector3d& y, double t) const {
    return rotates() ? motion_.Position(y, t) : Eigen::Vector3d(y + Shift(t));
  }
  // A bound, per unit of the path fraction s, on how fast the rest-frame
  // images ToRest(x_k(s), t(s)) of n points moving linearly from x0[k] (at
  // obstacle time t0) to x1[k] (t1) move, and so every point of their convex
  // hull: max_k |x1 - x0| + |dtau| (|v| + |omega| max_k max(|x0 - o(t0)|,
  // |x1 - o(t1)|)), o(t) the moving centre (the distance to it is convex
  // along the path, largest at an end). Without rotation the exact
  // max_k |(x1 - x0) - v dtau| of the linear relative paths.
  double RestPathBound(const Eigen::Vector3d* x0, const Eigen::Vector3d* x1, int n, double t0,
                       double t1) const;
  // How much the distance of any point within `radius` of the centre can
  // change from time t0 to t1 (a bound: the rest-frame image of a fixed
  // point moves by at most that much): |v dtau| + |omega dtau| (radius +
  // |v dtau|).
  double DistanceChangeBound(double t0, double t1, double radius) const;
  // The moving centre o(t) = c + v tau.
  Eigen::Vector3d RotationCenterAt(double t) const { return motion_.Center(t); }

  // Signed distance of point x (dimension components used) at time t; the unit
  // gradient with respect to x when `gradient` is not null.
  double Distance(const Eigen::Vector3d& x, double t, Eigen::Vector3d* gradient = nullptr) const {
    if (rotates()) return RotatedDistance(x, t, gradient);
    return RestDistance(x - Shift(t), gradient);
  }
  // Its Hessian with respect to x (false where it is not defined).
  bool DistanceHessian(const Eigen::Vector3d& x, double t, Eigen::Matrix3d* hessian) const;
  // True when Distance is affine in x (a plane): its Gauss-Newton model is exact.
  virtual bool distance_is_affine() const { return false; }

  // First fraction s in [0, 1] at which the point moving linearly from a (at
  // obstacle time t_a) to b (at obstacle time t_b) comes within `margin` of the
  // obstacle, i.e. enters the obstacle grown by margin (boxes are grown as boxes,
  // slightly conservative at corners). 0 if it starts there; kNoImpact if never.
  // An obstacle rotating between t_a and t_b answers by conservative
  // advancement (the first fraction not proved to keep the gap above
  // max(margin, kEdgeGapFraction d(0)): earlier than the exact one, never
  // later); at one time (t_a = t_b) the relative path is linear and the
  // answer exact.
  double TimeOfImpact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_a, double t_b,
                      double margin) const {
    if (CurvedPath(t_a, t_b)) return RotatedTimeOfImpact(a, b, t_a, t_b, margin);
    return RestTimeOfImpact(ToRest(a, t_a), ToRest(b, t_b), margin);
  }
  // Whether the rest-frame path of a linear motion from obstacle time t_a to
  // t_b is curved: the obstacle rotates in between.
  bool CurvedPath(double t_a, double t_b) const {
    return rotates() && std::min(t_a, until()) != std::min(t_b, until());
  }

  static constexpr double kNoImpact = 2.0;

  // Edges (segments [a, b] between two contact nodes) against the obstacle.
  // A segment can enter a sphere / circle with both end points outside only
  // through its interior coming too close to the centre, and a 2D box only
  // where a corner crosses it; the end points are contact nodes with pairs of
  // their own. So an edge's pairs are with the obstacle's "edge features":
  // sphere: its centre (radius R), 2D box: its four corners (radius 0); planes
  // (a segment meets a half-space only where an end point does) and 3D boxes
  // (their corners are ends of box edges: segments meet 3D boxes through the
  // box edges, NumBoxEdges below) have none.
  virtual int NumEdgeFeatures() const { return 0; }
  // World position of a feature at time t.
  Eigen::Vector3d EdgeFeature(int feature, double t) const {
    return ToWorld(RestFeature(feature), t);
  }
  // d = |c - closest point of [a, b]| - R for feature c at time t (negative:
  // the segment is inside the sphere); gradients with respect to a and b when
  // not null: (1 - alpha) n and alpha n, n the unit direction from c to the
  // closest point a + alpha (b - a) (alpha is the minimiser, so it does not
  // contribute; zero when the segment passes through c).
  double EdgeDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t,
                      Eigen::Vector3d* grad_a = nullptr, Eigen::Vector3d* grad_b = nullptr) const;
  // The same for the fixed point a + alpha (b - a) of the segment (>= the
  // segment's distance): |a + alpha (b - a) - c| - R, gradients (1 - alpha) n
  // and alpha n.
  double EdgePointDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           double alpha, double t, Eigen::Vector3d* grad_a = nullptr,
                           Eigen::Vector3d* grad_b = nullptr) const;
  // Continuous collision detection of the segment moving linearly from
  // [a0, b0] (obstacle time t0) to [a1, b1] (obstacle time t1) against a
  // feature. Conservative target, as IPC's advancement: returns the first
  // fraction s at which the gap d(s) falls to the goal max(margin,
  // kEdgeGapFraction d(0)) (a path is refused once its gap falls below a tenth
  // of the gap it started with; the gap never reaches 0 before s), 0 if
  // d(0) <= margin, kNoImpact if d stays above the goal over the whole path.
  // Computed from the roots of the polynomials whose sign changes mark the
  // events (end point at distance R + goal, line at distance R + goal, closest
  // point changing piece), with a quick rejection when d(0) exceeds the goal by
  // more than the largest end-point motion (every point of the segment moves by
  // at most that much).
  double EdgeTimeOfImpact(int feature, const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                          const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, double t0,
                          double t1, double margin) const;

  static constexpr double kEdgeGapFraction = 0.1;

  // 3D faces (triangles [a, b, c] of contact edges, contact/collision_mesh.h)
  // and 3D box edges. Both convex, a triangle and an obstacle touch first, in
  // a continuous motion, where a vertex meets the obstacle (node pairs), a
  // triangle edge meets it (edge pairs, and below against box edges) or the
  // triangle's interior meets an extreme point of the obstacle: for a sphere
  // its centre comes within R, for a box one of its corners touches the face
  // (an edge or a face of the box touching the triangle's interior first also
  // touches it at a corner or along a triangle edge). So a face's pairs are
  // with the obstacle's "face features": 3D sphere: its centre (radius R);
  // 3D box: its 8 corners (radius 0; corner k has the upper bound in axis j
  // where bit j of k is set); planes, and everything in 2D, have none.
  virtual int NumFaceFeatures() const { return 0; }
  // World position of a face feature at time t.
  Eigen::Vector3d FaceFeature(int feature, double t) const {
    return ToWorld(RestFeature(feature), t);
  }
  // R of the features (edge and face): the sphere's radius, 0 for box corners.
  virtual double FeatureRadius() const { return 0.0; }
  // d = |c - closest point of the triangle| - R (geometry/point_triangle.h);
  // gradients with respect to the vertices (w_i n) into grad[0..2] and the
  // closest point's barycentric weights when not null.
  double FaceDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      const Eigen::Vector3d& c, double t, Eigen::Vector3d* grad = nullptr,
                      Eigen::Vector3d* weights = nullptr) const;
  // The same for the fixed point w[0] a + w[1] b + w[2] c (>= FaceDistance):
  // convex in the vertices (the distance of an affine function of them to a
  // fixed point).
  double FacePointDistance(int feature, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& c, const Eigen::Vector3d& w, double t,
                           Eigen::Vector3d* grad = nullptr) const;
  // Continuous collision detection of the triangle moving linearly from
  // v0[0..2] (obstacle time t0) to v1[0..2] (time t1) against a face feature,
  // with the target of EdgeTimeOfImpact (the goal max(margin,
  // kEdgeGapFraction d(0))) by conservative advancement: relative to the
  // obstacle no point of the triangle moves farther than the largest vertex
  // displacement D over the path, so from s the gap stays above the goal up to
  // s + (d(s) - goal) / D; s advances by that until the gap is within 1 % of
  // d(0) - goal above the goal (returns s: the first fraction that is not
  // proved safe; every fraction below is) or the path is covered (kNoImpact).
  // 0 if d(0) <= margin. At most kMaxAdvancements advances (then returns s).
  double FaceTimeOfImpact(int feature, const Eigen::Vector3d* v0, const Eigen::Vector3d* v1,
                          double t0, double t1, double margin) const;

  // 3D box edges (12; edge k is parallel to axis k / 4, at the lower or upper
  // bound of the next axis (bit 0 of k % 4) and of the one after (bit 1)),
  // against contact edges (segment-segment, geometry/segment_segment.h). Other
  // shapes have none.
  virtual int NumBoxEdges() const { return 0; }
  // End points (lower and upper in the edge's axis) at time t.
  void BoxEdge(int edge, double t, Eigen::Vector3d* p, Eigen::Vector3d* q) const;
  // Distance between the segment [a, b] and box edge `edge` at time t;
  // gradients with respect to a and b ((1 - s) n and s n), and the closest
  // point's parameter s on [a, b], when not null.
  double BoxEdgeDistance(int edge, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t,
                         Eigen::Vector3d* grad_a = nullptr, Eigen::Vector3d* grad_b = nullptr,
                         double* s = nullptr) const;
  // Continuous collision detection of the segment moving linearly from
  // [a0, b0] (obstacle time t0) to [a1, b1] (time t1) against a box edge:
  // conservative advancement as FaceTimeOfImpact.
  double BoxEdgeTimeOfImpact(int edge, const Eigen::Vector3d& a0, const Eigen::Vector3d& a1,
                             const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, double t0,
                             double t1, double margin) const;

  static constexpr int kMaxAdvancements = 200;

 protected:
  // Shapes copy as themselves; an Obstacle& does not copy (no slicing).
  Obstacle(const Obstacle&) = default;
  Obstacle& operator=(const Obstacle&) = default;

  // The shape at rest (time 0), y in its frame.
  virtual double RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const = 0;
  virtual bool RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const = 0;
  virtual double RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                                  double margin) const = 0;
  // Edge / face feature k at rest (only called for k below their counts).
  virtual Eigen::Vector3d RestFeature(int /*feature*/) const { return Eigen::Vector3d::Zero(); }
  // Box edge k at rest (only called for k < NumBoxEdges()).
  virtual void RestBoxEdge(int /*edge*/, Eigen::Vector3d* p, Eigen::Vector3d* q) const {
    p->setZero();
    q->setZero();
  }

  // Conservative advancement with the obstacle's constants.
  template <class Gap>
  static double Advance(const Gap& gap, double bound, double margin) {
    return ConservativeAdvancement(gap, bound, margin, kEdgeGapFraction, kMaxAdvancements,
                                   kNoImpact);
  }
  // The translation at time t, velocity * min(t, until) (what maps the rest
  // frame to the world without rotation).
  Eigen::Vector3d Shift(double t) const { return motion_.Position(Eigen::Vector3d::Zero(), t); }

 private:
  double RotatedDistance(const Eigen::Vector3d& x, double t, Eigen::Vector3d* gradient) const;
  double RotatedTimeOfImpact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_a,
                             double t_b, double margin) const;

  int dimension_;
  PrescribedMotion motion_;
  std::optional<double> friction_mu_;
  std::string name_;
};

// Obstacles are immutable once built and shared (the contact options, the
// contact state and the frame writer hold the same ones).
using ObstaclePtr = std::shared_ptr<const Obstacle>;
using ObstacleList = std::vector<ObstaclePtr>;

// Distance from point c to the segment [a, b]; alpha of the closest point
// a + alpha (b - a) when not null.
double PointSegmentDistance(const Eigen::Vector3d& c, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double* alpha = nullptr);

// Point with `dimension` coordinates -> Vector3d (trailing zeros).
inline Eigen::Vector3d ToPoint(const double* x, int dimension) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension; ++k) p[k] = x[k];
  return p;
}

}  // namespace ipstep
