// The prescribed (Dirichlet) motion of a constrained node: a rigid motion of
// its initial position, translation plus rotation about a moving centre,
// until an optional stop time after which the node holds still. Moving
// obstacles translate by the same law (contact/obstacle.h: Shift).
//
// With x0 the initial position, c the centre, v the velocity, ω the angular
// velocity (3D vector; in 2D only its z component, a rotation in the plane)
// and τ = min(t, until):
//
//   x(t) = c + v τ + R(ω τ) (x0 − c)
//   ẋ(t) = v + ω × R(ω τ) (x0 − c)   for t < until, else 0
//
// R(ω τ) is the rotation by the angle |ω| τ about ω / |ω| (Rodrigues). A
// pinned node is the zero motion. The position is exact at every time, so a
// node turned through many revolutions keeps its distance from the centre
// (a node moved by its velocity alone, as before, would spiral out).
#pragma once

#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ipstep {

struct PrescribedMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // v [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // ω [rad/s]
  Eigen::Vector3d center = Eigen::Vector3d::Zero();            // c at t = 0 [m]
  double until = std::numeric_limits<double>::infinity();      // stop time [s]

  bool is_still() const { return velocity.isZero(0.0) && angular_velocity.isZero(0.0); }
  // x(t) and ẋ(t) for the initial position x0 (3 components; z = 0 in 2D).
  Eigen::Vector3d Position(const Eigen::Vector3d& x0, double t) const;
  Eigen::Vector3d Velocity(const Eigen::Vector3d& x0, double t) const;
  // R(ω τ) (the identity without rotation).
  Eigen::Matrix3d Rotation(double t) const;
  // The inverse of Position: the initial position x0 whose position at time t
  // is x, x0 = c + R(ω τ)ᵀ (x − c − v τ).
  Eigen::Vector3d InitialPosition(const Eigen::Vector3d& x, double t) const;
  // The centre's position at time t, c + v τ (the rotation is about it).
  Eigen::Vector3d Center(double t) const;
};

}  // namespace ipstep
