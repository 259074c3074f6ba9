#include "contact/obstacle.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace ipstep
