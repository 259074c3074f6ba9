// A half-space: the free side is where the unit normal points. Its distance
// is affine, so it has no edge or face features (a segment or a triangle
// meets a half-space only where one of its vertices does).
#pragma once

#include <string>

#include <Eigen/Core>

#include "contact/obstacle.h"

namespace ipstep {

class PlaneObstacle : public Obstacle {
 public:
  // `point` on the plane, `normal` of unit length.
  PlaneObstacle(int dimension, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(), std::string name = "");

  const char* type_name() const override { return "plane"; }
  void Accept(ObstacleVisitor& visitor) const override;
  bool distance_is_affine() const override { return true; }

  const Eigen::Vector3d& point() const { return point_; }
  const Eigen::Vector3d& normal() const { return normal_; }

 protected:
  double RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const override;
  bool RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const override;
  double RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                          double margin) const override;

 private:
  Eigen::Vector3d point_;
  Eigen::Vector3d normal_;
};

}  // namespace ipstep
