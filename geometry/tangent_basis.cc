#include "geometry/tangent_basis.h"

#include <cmath>

#include <Eigen/Geometry>

namespace ipstep {

Eigen::Matrix3d TangentBasis(const Eigen::Vector3d& n, int dimension) {
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  if (dimension == 2) {
    t.col(0) = Eigen::Vector3d(-n[1], n[0], 0.0);
    return t;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
  }
  t.col(0) = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  t.col(1) = n.cross(t.col(0));
  return t;
}

}  // namespace ipstep
