// An axis-aligned box [lower, upper] (2D: a rectangle). Its features against
// edges: in 2D its four corners (radius 0); against faces: in 3D its eight
// corners; and in 3D its twelve edges against contact edges (Obstacle,
// contact/obstacle.h, says why these are the features that can be met
// first).
#pragma once

#include <string>

#include <Eigen/Core>

#include "contact/obstacle.h"

namespace ipstep {

class BoxObstacle : public Obstacle {
 public:
  // upper > lower in every used component.
  BoxObstacle(int dimension, const Eigen::Vector3d& lower, const Eigen::Vector3d& upper,
              const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(), std::string name = "");

  const char* type_name() const override { return "box"; }
  void Accept(ObstacleVisitor& visitor) const override;

  const Eigen::Vector3d& lower() const { return lower_; }
  const Eigen::Vector3d& upper() const { return upper_; }

  int NumEdgeFeatures() const override { return dimension() == 2 ? 4 : 0; }
  int NumFaceFeatures() const override { return dimension() == 3 ? 8 : 0; }
  int NumBoxEdges() const override { return dimension() == 3 ? 12 : 0; }

 protected:
  double RestDistance(const Eigen::Vector3d& y, Eigen::Vector3d* gradient) const override;
  bool RestDistanceHessian(const Eigen::Vector3d& y, Eigen::Matrix3d* hessian) const override;
  double RestTimeOfImpact(const Eigen::Vector3d& y0, const Eigen::Vector3d& y1,
                          double margin) const override;
  // Corner k: the upper bound in axis j where bit j of k is set (unused axes 0).
  Eigen::Vector3d RestFeature(int feature) const override;
  void RestBoxEdge(int edge, Eigen::Vector3d* p, Eigen::Vector3d* q) const override;

 private:
  Eigen::Vector3d lower_;
  Eigen::Vector3d upper_;
};

}  // namespace ipstep
