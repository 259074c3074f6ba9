// A sphere (3D) or circle (2D). Its features, against edges and faces, are
// its centre with radius R: a segment or a triangle enters it with all its
// vertices outside only where its interior comes within R of the centre.
#pragma once

#include <string>

#include <Eigen/Core>

#include "contact/obstacle.h"

namespace ipstep {

class SphereObstacle : public Obstacle {
 public:
  SphereObstacle(int dimension, const Eigen::Vector3d& center, double radius,
                 const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(), std::string name = "");

  const char* type_name() const override { return "sphere"; }
  void Accept(ObstacleVisitor& visitor) const override;

  const Eigen::Vector3d& center() const { return center_; }
  double radius() const { return radius_; }

  int NumEdgeFeatures() const override { return 1; }
  int NumFaceFeatures() const override { return dimension() == 3 ? 1 : 0; }
  double FeatureRadius() const override { return radius_; }

 protected:
  double RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const override;
  bool RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const override;
  double RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                          double margin) const override;
  Eigen::Vector3d RestFeature(int /*feature*/) const override { return center_; }

 private:
  Eigen::Vector3d center_;
  double radius_;
};

}  // namespace ipstep
