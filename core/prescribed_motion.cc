#include "core/prescribed_motion.h"

#include <algorithm>

#include <Eigen/Geometry>

namespace ipstep {
namespace {

// R(ω τ) r: Rodrigues' rotation of r by the angle |ω| τ about ω / |ω|.
Eigen::Vector3d Rotate(const Eigen::Vector3d& omega, double tau, const Eigen::Vector3d& r) {
  const double rate = omega.norm();
  if (rate == 0.0) return r;
  return Eigen::AngleAxisd(rate * tau, omega / rate) * r;
}

}  // namespace

Eigen::Matrix3d PrescribedMotion::Rotation(double t) const {
  const double rate = angular_velocity.norm();
  if (rate == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(rate * std::min(t, until), angular_velocity / rate).toRotationMatrix();
}

Eigen::Vector3d PrescribedMotion::InitialPosition(const Eigen::Vector3d& x, double t) const {
  const double tau = std::min(t, until);
  return center + Rotate(angular_velocity, -tau, x - center - tau * velocity);
}

Eigen::Vector3d PrescribedMotion::Center(double t) const {
  return center + std::min(t, until) * velocity;
}

Eigen::Vector3d PrescribedMotion::Position(const Eigen::Vector3d& x0, double t) const {
  const double tau = std::min(t, until);
  return center + tau * velocity + Rotate(angular_velocity, tau, x0 - center);
}

Eigen::Vector3d PrescribedMotion::Velocity(const Eigen::Vector3d& x0, double t) const {
  if (t >= until) return Eigen::Vector3d::Zero();
  return velocity + angular_velocity.cross(Rotate(angular_velocity, t, x0 - center));
}

}  // namespace ipstep
