// Rigid obstacles for contact: half-spaces (planes with any normal), circles /
// spheres and axis-aligned boxes, in 2D or 3D, static or translating with a
// constant velocity: the obstacle at time t is its initial shape shifted by
// velocity * t.
//
// Distances are signed (negative inside the obstacle). Continuous collision
// detection works in the obstacle's frame: a point moving linearly while the
// obstacle translates linearly moves linearly relative to it.
#pragma once

#include <string>

#include <Eigen/Core>

namespace ipstep {

enum class ObstacleType { kPlane, kSphere, kBox };

const char* ObstacleTypeName(ObstacleType type);

struct Obstacle {
  ObstacleType type = ObstacleType::kPlane;
  int dimension = 2;
  // Unused trailing components (z in 2D) are zero.
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // plane: a point on it; sphere: centre
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // plane: unit normal towards the free side
  double radius = 0.0;                               // sphere
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();   // box: min corner
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();   // box: max corner
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  std::string name;  // e.g. "contact.obstacles[0]", for messages

  bool is_moving() const { return velocity.squaredNorm() > 0.0; }

  // Signed distance of point x (dimension components used) at time t; the unit
  // gradient with respect to x when `gradient` is not null.
  double Distance(const Eigen::Vector3d& x, double t, Eigen::Vector3d* gradient = nullptr) const;

  // First fraction s in [0, 1] at which the point moving linearly from a (at
  // obstacle time t_a) to b (at obstacle time t_b) comes within `margin` of the
  // obstacle, i.e. enters the obstacle grown by margin (boxes are grown as boxes,
  // slightly conservative at corners). 0 if it starts there; kNoImpact if never.
  double TimeOfImpact(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t_a, double t_b,
                      double margin) const;

  static constexpr double kNoImpact = 2.0;
};

// Point with `dimension` coordinates -> Vector3d (trailing zeros).
inline Eigen::Vector3d ToPoint(const double* x, int dimension) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension; ++k) p[k] = x[k];
  return p;
}

}  // namespace ipstep
