#include "contact/obstacles/plane_obstacle.h"

#include <algorithm>
#include <utility>

#include "contact/obstacles/obstacle_visitor.h"

namespace ipstep {

PlaneObstacle::PlaneObstacle(int dimension, const Eigen::Vector3d& point,
                             const Eigen::Vector3d& normal, const Eigen::Vector3d& velocity,
                             std::string name)
    : Obstacle(dimension, velocity, std::move(name)), point_(point), normal_(normal) {}

void PlaneObstacle::Accept(ObstacleVisitor& visitor) const { visitor.Visit(*this); }

// d(y) = n . (y - p), gradient n.
double PlaneObstacle::RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const {
  if (gradient) *gradient = normal_;
  return normal_.dot(y - point_);
}

bool PlaneObstacle::RestDistanceHessian(const Eigen::Vector3d& /*y*/,
                                        Eigen::Matrix3d* hessian) const {
  hessian->setZero();
  return true;
}

// d is affine along the path: d(s) = f0 + s (f1 - f0), with the margin
// subtracted; its root if it changes sign.
double PlaneObstacle::RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                                       double margin) const {
  const double f0 = normal_.dot(y0 - point_) - margin;
  const double f1 = normal_.dot(y1 - point_) - margin;
  if (f0 <= 0.0) return 0.0;
  if (f1 > 0.0) return kNoImpact;
  return std::clamp(f0 / (f0 - f1), 0.0, 1.0);
}

}  // namespace ipstep
