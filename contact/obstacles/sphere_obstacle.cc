#include "contact/obstacles/sphere_obstacle.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "contact/distance_hessian.h"
#include "contact/obstacles/obstacle_visitor.h"

namespace ipstep {

SphereObstacle::SphereObstacle(int dimension, const Eigen::Vector3d& center, double radius,
                               const Eigen::Vector3d& velocity, std::string name)
    : Obstacle(dimension, velocity, std::move(name)), center_(center), radius_(radius) {}

void SphereObstacle::Accept(ObstacleVisitor& visitor) const { visitor.Visit(*this); }

// d(y) = |y - c| - R, gradient (y - c) / |y - c|.
double SphereObstacle::RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const {
  const Eigen::Vector3d r = y - center_;
  const double norm = r.norm();
  if (gradient) {
    *gradient = Eigen::Vector3d::Zero();
    if (norm > 0.0) {
      *gradient = r / norm;
    } else {
      (*gradient)[0] = 1.0;  // any direction at the centre
    }
  }
  return norm - radius_;
}

bool SphereObstacle::RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const {
  return PointPointDistanceHessian(y, center_, hessian);
}

// |y0 - c + s (y1 - y0)|^2 = R'^2, R' = radius + margin: the smaller root of
// a2 s^2 + 2 b2 s + c = 0 with a2 = |e|^2, b2 = q . e, c = |q|^2 - R'^2
// (q = y0 - c, e = y1 - y0).
double SphereObstacle::RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                                        double margin) const {
  const double reach = radius_ + margin;
  const Eigen::Vector3d q = y0 - center_, e = y1 - y0;
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

}  // namespace ipstep
