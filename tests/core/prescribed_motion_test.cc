// Prescribed rigid motions of constrained nodes (core/prescribed_motion.h):
// exact rotation, velocity as the derivative of the position, the stop time.
#include "core/prescribed_motion.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/state.h"

namespace ipstep {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(PrescribedMotion, QuarterTurnAboutAnAxisIsExact) {
  PrescribedMotion m;
  m.angular_velocity = {0.0, 0.0, kPi / 2};  // a quarter turn per second about z
  m.center = {1.0, 1.0, 0.0};
  const Eigen::Vector3d x0(2.0, 1.0, 0.5);
  const Eigen::Vector3d x = m.Position(x0, 1.0);
  EXPECT_NEAR(x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[1], 2.0, 1e-15);
  EXPECT_NEAR(x[2], 0.5, 1e-15);
  // Many revolutions later the radius is the initial one (no spiral).
  const Eigen::Vector3d far = m.Position(x0, 1000.3);
  EXPECT_NEAR((far - m.center).head<2>().norm(), 1.0, 1e-12);
  EXPECT_NEAR(far[2], 0.5, 1e-15);
}

TEST(PrescribedMotion, VelocityIsTheDerivativeOfThePosition) {
  PrescribedMotion m;
  m.velocity = {0.3, -0.2, 0.1};
  m.angular_velocity = {1.0, -2.0, 0.5};
  m.center = {0.2, 0.1, -0.3};
  const Eigen::Vector3d x0(0.7, -0.4, 0.9);
  for (double t : {0.0, 0.37, 2.1}) {
    const double h = 1e-6;
    const Eigen::Vector3d fd = (m.Position(x0, t + h) - m.Position(x0, t - h)) / (2 * h);
    EXPECT_LT((m.Velocity(x0, t) - fd).norm(), 1e-8) << "t = " << t;
  }
  // At t = 0: v + ω × (x0 − c).
  const Eigen::Vector3d v0 = m.velocity + m.angular_velocity.cross(x0 - m.center);
  EXPECT_LT((m.Velocity(x0, 0.0) - v0).norm(), 1e-15);
}

TEST(PrescribedMotion, CentreTravelsWithTheVelocityAndStopsAtUntil) {
  PrescribedMotion m;
  m.velocity = {1.0, 0.0, 0.0};
  m.angular_velocity = {0.0, 0.0, kPi};  // half a turn per second
  m.center = {0.0, 0.0, 0.0};
  m.until = 1.0;
  const Eigen::Vector3d x0(0.0, 1.0, 0.0);
  // After 1 s: the centre at (1, 0), the node turned by pi about it.
  const Eigen::Vector3d x1 = m.Position(x0, 1.0);
  EXPECT_NEAR(x1[0], 1.0, 1e-15);
  EXPECT_NEAR(x1[1], -1.0, 1e-15);
  EXPECT_EQ(m.Position(x0, 5.0), x1);  // holds still afterwards
  EXPECT_EQ(m.Velocity(x0, 1.0), Eigen::Vector3d::Zero());
  EXPECT_FALSE(m.is_still());
  EXPECT_TRUE(PrescribedMotion().is_still());
}

TEST(PrescribedMotion, StateMovesOnlyConstrainedNodes) {
  State s;
  s.dimension = 2;
  s.x = Eigen::VectorXd::Zero(4);
  s.x0 = Eigen::Vector4d(1.0, 0.0, 3.0, 4.0);
  s.mass = Eigen::Vector2d(1.0, 1.0);
  s.kind = {NodeKind::kMoving, NodeKind::kFree};
  s.motion.assign(2, PrescribedMotion());
  s.motion[0].angular_velocity = {0.0, 0.0, kPi};  // 2D: about z through the origin
  EXPECT_TRUE(s.has_prescribed_motion());
  Eigen::VectorXd x = Eigen::Vector4d(9.0, 9.0, 9.0, 9.0);
  s.PrescribedPositions(0.5, &x);
  EXPECT_NEAR(x[0], 0.0, 1e-15);
  EXPECT_NEAR(x[1], 1.0, 1e-15);
  EXPECT_EQ(x[2], 9.0);  // the free node is left alone
  Eigen::VectorXd v = Eigen::Vector4d(9.0, 9.0, 9.0, 9.0);
  s.PrescribedVelocities(0.5, &v);
  EXPECT_NEAR(v[0], -kPi, 1e-14);
  EXPECT_NEAR(v[1], 0.0, 1e-14);
  EXPECT_EQ(v[3], 9.0);
}

}  // namespace
}  // namespace ipstep
