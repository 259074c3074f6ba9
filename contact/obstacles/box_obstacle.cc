#include "contact/obstacles/box_obstacle.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "contact/distance_hessian.h"
#include "contact/obstacles/obstacle_visitor.h"

namespace ipstep {

namespace {

// Entry fraction of the segment y0 -> y1 into the box [lo, hi] (slab method:
// per axis the path is inside the slab between two fractions; it is inside
// the box on the intersection of those intervals).
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

BoxObstacle::BoxObstacle(int dimension, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
                         const Eigen::Vector3d& velocity, std::string name)
    : Obstacle(dimension, velocity, std::move(name)), lower_(lower), upper_(upper) {}

void BoxObstacle::Accept(ObstacleVisitor& visitor) const { visitor.Visit(*this); }

// Outside: the distance to the clamped point, gradient towards y from it.
// Inside: minus the distance to the nearest face, gradient its outer normal.
double BoxObstacle::RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const {
  const int dimension = this->dimension();
  Eigen::Vector3d outside = Eigen::Vector3d::Zero();
  bool inside = true;
  for (int k = 0; k < dimension; ++k) {
    if (y[k] < lower_[k]) {
      outside[k] = y[k] - lower_[k];
      inside = false;
    } else if (y[k] > upper_[k]) {
      outside[k] = y[k] - upper_[k];
      inside = false;
    }
  }
  if (!inside) {
    const double norm = outside.norm();
    if (gradient) *gradient = outside / norm;
    return norm;
  }
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension; ++k) {
    if (y[k] - lower_[k] < best) {
      best = y[k] - lower_[k];
      direction = -Eigen::Vector3d::Unit(k);
    }
    if (upper_[k] - y[k] < best) {
      best = upper_[k] - y[k];
      direction = Eigen::Vector3d::Unit(k);
    }
  }
  if (gradient) *gradient = direction;
  return -best;
}

bool BoxObstacle::RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const {
  return PointBoxDistanceHessian(y, lower_, upper_, dimension(), hessian);
}

// The box grown by the margin as a box (slightly conservative at corners).
double BoxObstacle::RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                                     double margin) const {
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(margin);
  return SegmentBoxEntry(y0, y1, lower_ - grow, upper_ + grow, dimension());
}

Eigen::Vector3d BoxObstacle::RestFeature(int feature) const {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension(); ++k) c[k] = (feature >> k & 1 ? upper_ : lower_)[k];
  return c;
}

// Edge k is parallel to axis k / 4, at the lower or upper bound of the next
// axis (bit 0 of k % 4) and of the one after (bit 1).
void BoxObstacle::RestBoxEdge(int edge, Eigen::Vector3d* p, Eigen::Vector3d* q) const {
  const int axis = edge / 4, bits = edge % 4;
  const int next = (axis + 1) % 3, after = (axis + 2) % 3;
  Eigen::Vector3d corner;
  corner[next] = (bits & 1 ? upper_ : lower_)[next];
  corner[after] = (bits & 2 ? upper_ : lower_)[after];
  corner[axis] = lower_[axis];
  *p = corner;
  corner[axis] = upper_[axis];
  *q = corner;
}

}  // namespace ipstep
