// Contact building blocks against finite differences and closed forms: the IPC
// barrier and its loss-function form, the friction mollifier and loss, obstacle
// and point-edge distances and their gradients, continuous collision detection,
// the spatial hash, and the Jacobians of the contact cost functions. Every
// finite-difference probe stays inside the barrier's domain d > 0.
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/friction.h"
#include "contact/obstacle.h"
#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/plane_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "geometry/point_edge.h"
#include "geometry/spatial_hash.h"
#include "tests/support/finite_differences.h"

namespace ipstep {
namespace {

// Central difference of f at x with step h.
template <class F>
double Derivative(const F& f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

TEST(Barrier, DerivativesMatchFiniteDifferences) {
  const double d_hat = 0.01;
  for (double ratio : {1e-4, 1e-3, 0.01, 0.1, 0.3, 0.5, 0.9, 0.99}) {
    const double d = ratio * d_hat;
    const double h = 1e-4 * std::min(d, d_hat - d);  // probes stay in (0, d_hat)
    const double b1 = Derivative([&](double t) { return Barrier(t, d_hat); }, d, h);
    const double b2 = Derivative([&](double t) { return BarrierDerivative(t, d_hat); }, d, h);
    EXPECT_NEAR(BarrierDerivative(d, d_hat), b1, 1e-6 * std::abs(b1) + 1e-9 * d_hat) << ratio;
    EXPECT_NEAR(BarrierSecondDerivative(d, d_hat), b2, 1e-6 * std::abs(b2)) << ratio;
    EXPECT_LT(BarrierDerivative(d, d_hat), 0.0);
    EXPECT_GT(BarrierSecondDerivative(d, d_hat), 0.0);
  }
  EXPECT_EQ(Barrier(d_hat, d_hat), 0.0);
  EXPECT_EQ(Barrier(2 * d_hat, d_hat), 0.0);
  EXPECT_EQ(BarrierDerivative(d_hat, d_hat), 0.0);
  EXPECT_TRUE(std::isinf(Barrier(0.0, d_hat)));
  // C^2 at d_hat: B'' -> 0 from below.
  EXPECT_LT(BarrierSecondDerivative(d_hat * (1 - 1e-6), d_hat), 1e-5);
}

TEST(Barrier, LossGivesTheBarrierAndItsExactCurvature) {
  const double d_hat = 0.01, weight = 0.25, kappa = 1e5;
  const BarrierLoss loss(d_hat, weight, &kappa);
  for (double ratio : {1e-6, 1e-3, 0.05, 0.5, 0.95}) {
    const double d = ratio * d_hat, u = d_hat - d, s = u * u;
    double rho[3];
    loss.Evaluate(s, rho);
    const double b = kappa * weight * Barrier(d, d_hat);
    EXPECT_NEAR(0.5 * rho[0], b, 1e-10 * b) << ratio;
    EXPECT_GT(rho[1], 0.0);
    EXPECT_GT(rho[2], 0.0);
    // Ceres's corrector: rho' + 2 s rho'' = b''(d).
    const double b2 = kappa * weight * BarrierSecondDerivative(d, d_hat);
    EXPECT_NEAR(rho[1] + 2 * s * rho[2], b2, 1e-9 * b2) << ratio;
    // rho' and rho'' against differences in s (probes keep d > 0).
    const double hs = 1e-5 * std::min(s, d_hat * d_hat - s) + 1e-30;
    auto rho0 = [&](double t) {
      double r[3];
      loss.Evaluate(t, r);
      return r[0];
    };
    auto rho1 = [&](double t) {
      double r[3];
      loss.Evaluate(t, r);
      return r[1];
    };
    if (ratio > 1e-3) {
      EXPECT_NEAR(rho[1], Derivative(rho0, s, hs), 1e-5 * rho[1]) << ratio;
      EXPECT_NEAR(rho[2], Derivative(rho1, s, hs), 1e-5 * rho[2]) << ratio;
    }
  }
  double rho[3];
  loss.Evaluate(0.0, rho);
  EXPECT_EQ(rho[0], 0.0);
  EXPECT_EQ(rho[1], 0.0);
  EXPECT_EQ(rho[2], 0.0);
}

TEST(Friction, MollifierAndLossMatchFiniteDifferences) {
  const double eps = 1e-3;
  for (double y : {1e-5, 2e-4, 5e-4, 9e-4, 1.5e-3, 0.1}) {
    const double h = 1e-4 * y;
    EXPECT_NEAR(FrictionF1(y, eps), Derivative([&](double t) { return FrictionF0(t, eps); }, y, h),
                1e-6);
  }
  // C^1 at eps_v and f1 in [0, 1].
  EXPECT_NEAR(FrictionF0(eps * (1 - 1e-9), eps), FrictionF0(eps, eps), 1e-12);
  EXPECT_NEAR(FrictionF1(eps * (1 - 1e-9), eps), 1.0, 1e-8);
  EXPECT_EQ(FrictionF0(0.0, eps), 0.0);

  const double scale = 3.0;
  const FrictionLoss loss(scale);
  double rho[3];
  loss.Evaluate(0.7, rho);
  EXPECT_EQ(rho[0], scale * 0.7);
  EXPECT_EQ(rho[1], scale);
  EXPECT_EQ(rho[2], 0.0);
}

// The friction residual r(v) = psi(|v|) v/|v|: 1/2 |r|^2 = f0(|v|), dr/dv against
// central differences (stick and slip, 1 and 2 components, at 0), and the
// Gauss-Newton curvature along the slip, psi'^2 = f1^2 / (2 f0), never above the
// old split's f1/y and equal to f1'(0) = 2/eps_v at rest.
TEST(Friction, ResidualMatchesDissipationAndFiniteDifferences) {
  const double eps = 1e-3;
  for (int m : {1, 2}) {
    for (double y : {0.0, 1e-6, 2e-4, 5e-4, 9.99e-4, 1e-3, 1.5e-3, 0.1, 3.0}) {
      const double v[2] = {y * (m == 1 ? -1.0 : 0.6), y * 0.8};
      double r[2], jac[4];
      FrictionResidual(v, m, eps, r, jac);
      const double norm = m == 1 ? y : y;  // |v| = y in both cases
      const double s = r[0] * r[0] + (m == 2 ? r[1] * r[1] : 0.0);
      EXPECT_NEAR(0.5 * s, FrictionF0(norm, eps), 1e-12 * (1.0 + FrictionF0(norm, eps)))
          << m << " " << y;
      const double h = 1e-9 + 1e-6 * y;
      for (int j = 0; j < m; ++j) {
        double vp[2] = {v[0], v[1]}, vm[2] = {v[0], v[1]}, rp[2], rm[2];
        vp[j] += h;
        vm[j] -= h;
        FrictionResidual(vp, m, eps, rp, nullptr);
        FrictionResidual(vm, m, eps, rm, nullptr);
        for (int i = 0; i < m; ++i) {
          const double fd = (rp[i] - rm[i]) / (2.0 * h);
          EXPECT_NEAR(jac[i * m + j], fd, 1e-5 * (1.0 + std::abs(fd))) << m << " " << y;
        }
      }
      if (m == 1) {
        const double along = jac[0] * jac[0];
        if (y > 0.0) {
          EXPECT_NEAR(along, FrictionF1(y, eps) * FrictionF1(y, eps) / (2.0 * FrictionF0(y, eps)),
                      1e-9 * along);
          EXPECT_LE(along, FrictionF1(y, eps) / y * (1.0 + 1e-12));
        } else {
          EXPECT_NEAR(along, 2.0 / eps, 1e-9 / eps);
        }
      }
    }
  }
  // Sliding: half the old curvature f1/y, far from eps_v.
  double r, jac;
  const double v = 0.1;
  FrictionResidual(&v, 1, eps, &r, &jac);
  EXPECT_NEAR(jac * jac * v, 0.5, 0.01);
}

// The exact 2D split R = mu lambda (P(v) + P(-v)): the halves add up to
// f0(|v|) + eps_v / 3; P', P'' and the loss's rho', rho'' against central
// differences; and Ceres's model curvature of the pair (rho' + 2 q rho'' along
// the residual where rho'' > 0, rho' otherwise, times (dr/dv)^2) matches IPC's
// f1'(|v|) up to 1 / c: 2 / eps_v at rest, 0 while sliding (the single
// residual psi(|v|) v / |v| gave f1^2 / (2 f0) there).
TEST(Friction, OneSidedSplitHasIpcCurvature) {
  const double eps = 1e-3, c = kFrictionSpeedScale * eps, scale = 2.5;
  const OneSidedFrictionLoss loss(scale, c, eps);
  for (double v : {0.0, 1e-6, -3e-4, 5e-4, -9.9e-4, 1.01e-3, 2e-3, -0.05, 0.3, 4.0, -30.0}) {
    double p1, p2;
    const double p = FrictionHalf(v, eps, &p1, &p2), q = FrictionHalf(-v, eps);
    EXPECT_NEAR(p + q, FrictionF0(std::abs(v), eps) + eps / 3.0, 1e-15 * (1.0 + std::abs(v))) << v;
    EXPECT_GE(p, 0.0);
    const double h = 1e-9;
    EXPECT_NEAR(p1, (FrictionHalf(v + h, eps) - FrictionHalf(v - h, eps)) / (2 * h), 1e-6) << v;
    double d1p, d1m;
    FrictionHalf(v + h, eps, &d1p);
    FrictionHalf(v - h, eps, &d1m);
    EXPECT_NEAR(p2, (d1p - d1m) / (2 * h), 1e-5 / eps) << v;

    double model = 0.0;
    for (int side : {1, -1}) {
      double r, dr_dw;
      OneSidedFrictionResidual(side * v, c, &r, &dr_dw);
      const double qs = r * r;
      double rho[3];
      loss.Evaluate(qs, rho);
      EXPECT_NEAR(0.5 * rho[0], scale * FrictionHalf(side * v, eps), 1e-12 * scale) << v;
      const double hq = 1e-9 * qs;
      double rp[3], rm[3];
      loss.Evaluate(qs + hq, rp);
      loss.Evaluate(qs - hq, rm);
      EXPECT_NEAR(rho[1], (rp[0] - rm[0]) / (2 * hq), 1e-5 * (std::abs(rho[1]) + 1e-3)) << v;
      EXPECT_NEAR(rho[2], (rp[1] - rm[1]) / (2 * hq), 1e-4 * (std::abs(rho[2]) + 1e-3)) << v;
      const double along = rho[2] > 0.0 ? rho[1] + 2.0 * qs * rho[2] : rho[1];
      model += along * dr_dw * dr_dw;
    }
    const double y = std::abs(v);
    const double exact = scale * (y < eps ? 2.0 / eps - 2.0 * y / (eps * eps) : 0.0);
    EXPECT_NEAR(model, exact, scale / c * 1.000001) << v;
  }
}

PlaneObstacle Plane2D() {
  return PlaneObstacle(2, Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(0.1, 1, 0).normalized());
}

SphereObstacle Sphere(int dimension) {
  return SphereObstacle(dimension, Eigen::Vector3d(0.2, -0.1, dimension == 3 ? 0.3 : 0.0), 0.5,
                        Eigen::Vector3d(0.3, -0.2, 0.0));
}

BoxObstacle Box(int dimension) {
  return BoxObstacle(dimension, Eigen::Vector3d(-1, -0.5, dimension == 3 ? -0.2 : 0.0),
                     Eigen::Vector3d(1, 0.5, dimension == 3 ? 0.2 : 0.0));
}

TEST(Obstacle, DistanceGradientsMatchFiniteDifferences) {
  const std::vector<ObstaclePtr> obstacles = {
      std::make_shared<PlaneObstacle>(Plane2D()), std::make_shared<SphereObstacle>(Sphere(2)),
      std::make_shared<SphereObstacle>(Sphere(3)), std::make_shared<BoxObstacle>(Box(2)),
      std::make_shared<BoxObstacle>(Box(3))};
  const std::vector<Eigen::Vector3d> points = {Eigen::Vector3d(0.3, 0.9, 0.0),
                                               Eigen::Vector3d(1.7, 0.8, 0.0),
                                               Eigen::Vector3d(-1.3, -0.7, 0.6)};
  const double t = 0.4;
  for (const ObstaclePtr& obstacle : obstacles) {
    const Obstacle& o = *obstacle;
    for (Eigen::Vector3d p : points) {
      if (o.dimension() == 2) p[2] = 0.0;
      Eigen::Vector3d g;
      const double d = o.Distance(p, t, &g);
      ASSERT_GT(d, 0.0);
      for (int k = 0; k < o.dimension(); ++k) {
        const double h = 1e-6;
        const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(k);
        const double fd = (o.Distance(p + e, t) - o.Distance(p - e, t)) / (2 * h);
        EXPECT_NEAR(g[k], fd, 1e-7) << o.type_name() << " " << k;
      }
    }
  }
  // Closed forms.
  EXPECT_NEAR(Box(2).Distance(Eigen::Vector3d(2, 1.5, 0), 0), std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(Box(2).Distance(Eigen::Vector3d(0.9, 0, 0), 0), -0.1, 1e-15);
  EXPECT_NEAR(Sphere(2).Distance(Eigen::Vector3d(0.2 + 0.3, -0.1 - 0.2 + 1.0, 0), 1.0), 0.5, 1e-15);
}

TEST(Obstacle, ContinuousCollisionDetection) {
  const PlaneObstacle ground(2, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0));
  // From y = 1 to y = -3 crosses y = 0 at s = 0.25.
  EXPECT_NEAR(ground.TimeOfImpact({0, 1, 0}, {0, -3, 0}, 0, 0, 0), 0.25, 1e-15);
  EXPECT_GT(ground.TimeOfImpact({0, 1, 0}, {0, 0.5, 0}, 0, 0, 0), 1.0);
  // A moving ceiling catches a point at rest: y = 1 - 2 t reaches y = 0.5 at t = 0.25.
  const PlaneObstacle ceiling(2, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0),
                              Eigen::Vector3d(0, -2, 0));
  EXPECT_NEAR(ceiling.TimeOfImpact({0, 0.5, 0}, {0, 0.5, 0}, 0.0, 1.0, 0), 0.25, 1e-15);
  // Sphere: a point passing straight through the centre enters at the radius.
  const SphereObstacle sphere(2, Sphere(2).center(), Sphere(2).radius());
  const Eigen::Vector3d c = sphere.center();
  EXPECT_NEAR(
      sphere.TimeOfImpact(c + Eigen::Vector3d(-2, 0, 0), c + Eigen::Vector3d(2, 0, 0), 0, 0, 0),
      1.5 / 4.0, 1e-14);
  // A tangent path that misses.
  EXPECT_GT(
      sphere.TimeOfImpact(c + Eigen::Vector3d(-2, 0.6, 0), c + Eigen::Vector3d(2, 0.6, 0), 0, 0, 0),
      1.0);
  // Box: a fast point through a thin wall (x in [-1e-3, 1e-3]) is caught.
  const BoxObstacle wall(2, Eigen::Vector3d(-1e-3, -1, 0), Eigen::Vector3d(1e-3, 1, 0));
  EXPECT_NEAR(wall.TimeOfImpact({-1, 0, 0}, {1, 0, 0}, 0, 0, 0), (1 - 1e-3) / 2, 1e-15);
  EXPECT_GT(wall.TimeOfImpact({-1, 1.5, 0}, {1, 1.5, 0}, 0, 0, 0), 1.0);
  // The margin grows the obstacle.
  EXPECT_NEAR(ground.TimeOfImpact({0, 1, 0}, {0, -1, 0}, 0, 0, 0.5), 0.25, 1e-15);
}

TEST(PointEdge, DistanceGradientsMatchFiniteDifferences) {
  const Eigen::Vector2d a(0.1, -0.2), b(1.3, 0.4);
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.5, 0.7), Eigen::Vector2d(0.9, -0.5),
                                   Eigen::Vector2d(-0.6, -0.1), Eigen::Vector2d(2.0, 1.0)}) {
    const PointEdgeDistanceResult r = PointEdgeDistance(p, a, b);
    ASSERT_GT(r.distance, 0.0);
    Eigen::Matrix<double, 6, 1> x;
    x << p, a, b;
    Eigen::Matrix<double, 6, 1> g;
    g << r.grad_p, r.grad_a, r.grad_b;
    for (int k = 0; k < 6; ++k) {
      const double h = 1e-7;
      Eigen::Matrix<double, 6, 1> xp = x, xm = x;
      xp[k] += h;
      xm[k] -= h;
      const double fd =
          (PointEdgeDistance(xp.segment<2>(0), xp.segment<2>(2), xp.segment<2>(4)).distance -
           PointEdgeDistance(xm.segment<2>(0), xm.segment<2>(2), xm.segment<2>(4)).distance) /
          (2 * h);
      EXPECT_NEAR(g[k], fd, 1e-7) << k;
    }
  }
}

TEST(PointEdge, ContinuousCollisionDetection) {
  const Eigen::Vector2d a(0, 0), b(1, 0);
  // A point fired through the edge from y = 1 to y = -1 crosses at s = 0.5.
  EXPECT_NEAR(PointEdgeTimeOfImpact({0.5, 1}, {0.5, -1}, a, a, b, b), 0.5, 1e-15);
  // Passing beside the edge: no impact.
  EXPECT_GT(PointEdgeTimeOfImpact({1.5, 1}, {1.5, -1}, a, a, b, b), 1.0);
  // The edge moves up into a resting point.
  EXPECT_NEAR(PointEdgeTimeOfImpact({0.5, 1}, {0.5, 1}, {0, 0}, {0, 4}, {1, 0}, {1, 4}), 0.25,
              1e-15);
  // A rotating edge sweeps a point.
  const double s = PointEdgeTimeOfImpact({0.5, 0.5}, {0.5, 0.5}, {0, 0}, {0, 0}, {1, 0}, {0, 1});
  EXPECT_LE(s, 1.0);
  EXPECT_TRUE(SegmentsIntersect({0, 0}, {1, 1}, {0, 1}, {1, 0}));
  EXPECT_FALSE(SegmentsIntersect({0, 0}, {1, 0}, {0, 1}, {1, 1}));
}

// Edge-obstacle distance: |c - closest point of [a, b]| - R, for sphere
// centres (2D, 3D, moving) and 2D box corners, against finite differences with
// probes in d > 0: interior closest points and clamped ones (end points).
TEST(EdgeObstacle, DistanceGradientsMatchFiniteDifferences) {
  const double t = 0.4;
  struct Probe {
    ObstaclePtr obstacle;
    int feature;
    Eigen::Vector3d a, b;
  };
  std::vector<Probe> probes;
  for (int dim : {2, 3}) {
    const auto s = std::make_shared<SphereObstacle>(Sphere(dim));
    const Eigen::Vector3d c = s->EdgeFeature(0, t);
    const Eigen::Vector3d z = dim == 3 ? Eigen::Vector3d(0, 0, 0.1) : Eigen::Vector3d::Zero();
    probes.push_back(
        {s, 0, c + Eigen::Vector3d(-0.8, 0.6, 0) + z, c + Eigen::Vector3d(0.7, 0.5, 0)});
    probes.push_back(
        {s, 0, c + Eigen::Vector3d(0.6, 0.3, 0), c + Eigen::Vector3d(1.5, 0.9, 0) - z});
  }
  const auto box = std::make_shared<BoxObstacle>(Box(2));
  for (int corner = 0; corner < 4; ++corner) {
    const Eigen::Vector3d c = box->EdgeFeature(corner, t);
    probes.push_back(
        {box, corner, c + Eigen::Vector3d(-0.2, 0.05, 0), c + Eigen::Vector3d(0.1, 0.2, 0)});
  }
  for (const Probe& p : probes) {
    Eigen::Vector3d ga, gb;
    const double d = p.obstacle->EdgeDistance(p.feature, p.a, p.b, t, &ga, &gb);
    ASSERT_GT(d, 0.0);
    for (int end = 0; end < 2; ++end) {
      for (int k = 0; k < p.obstacle->dimension(); ++k) {
        const double h = 1e-6;
        Eigen::Vector3d ap = p.a, am = p.a, bp = p.b, bm = p.b;
        (end == 0 ? ap : bp)[k] += h;
        (end == 0 ? am : bm)[k] -= h;
        const double fd = (p.obstacle->EdgeDistance(p.feature, ap, bp, t) -
                           p.obstacle->EdgeDistance(p.feature, am, bm, t)) /
                          (2 * h);
        EXPECT_NEAR((end == 0 ? ga : gb)[k], fd, 1e-7)
            << p.obstacle->type_name() << " feature " << p.feature << " end " << end;
      }
    }
  }
  // Closed forms: a horizontal segment 0.1 above a unit circle's top.
  const SphereObstacle circle(2, Eigen::Vector3d::Zero(), 1.0);
  EXPECT_NEAR(circle.EdgeDistance(0, {-2, 1.1, 0}, {3, 1.1, 0}, 0), 0.1, 1e-15);
  EXPECT_NEAR(circle.EdgeDistance(0, {0, 1.1, 0}, {3, 1.1, 0}, 0), 0.1, 1e-15);
  EXPECT_NEAR(circle.EdgeDistance(0, {1, 1, 0}, {3, 1, 0}, 0), std::sqrt(2.0) - 1.0, 1e-15);
  EXPECT_EQ(Plane2D().NumEdgeFeatures(), 0);
  EXPECT_EQ(Box(3).NumEdgeFeatures(), 0);
  EXPECT_EQ(Box(2).NumEdgeFeatures(), 4);
}

// Conservative advancement of a moving segment against a circle / box corner.
TEST(EdgeObstacle, ContinuousCollisionDetection) {
  const SphereObstacle circle(2, Eigen::Vector3d::Zero(), 0.01);
  // A 0.2 m bar falling from y = 1 to y = -1, its nodes beside the circle: the
  // gap 1 - 0.01 falls to the goal 0.1 d(0) at s = 0.9 * 0.99 / 2.
  const double s =
      circle.EdgeTimeOfImpact(0, {-0.1, 1, 0}, {-0.1, -1, 0}, {0.1, 1, 0}, {0.1, -1, 0}, 0, 0, 0);
  EXPECT_GE(s, 0.0);
  EXPECT_LE(s, 0.9 * 0.99 / 2.0 + 1e-12);
  EXPECT_GE(s, 0.8 * 0.99 / 2.0 - 1e-12);  // stops with the gap within [goal, 2 goal]
  // Its right end passing 0.015 beside the centre (outside the circle): caught.
  EXPECT_LE(circle.EdgeTimeOfImpact(0, {-0.185, 1, 0}, {-0.185, -1, 0}, {0.015, 1, 0},
                                    {0.015, -1, 0}, 0, 0, 0),
            1.0);
  // 3D: a bar along x at z = 0.1 sweeping down past a sphere of radius 0.2; its
  // nodes' paths stay 0.51 from the centre, only the interior comes close.
  const SphereObstacle sphere(3, Eigen::Vector3d::Zero(), 0.2);
  const double hit = sphere.EdgeTimeOfImpact(0, {-0.5, 1, 0.1}, {-0.5, -1, 0.1}, {0.5, 1, 0.1},
                                             {0.5, -1, 0.1}, 0, 0, 0);
  EXPECT_LE(hit, 1.0);
  // Stopped before the interior enters: the gap at the reported fraction is
  // above the margin, and every node path misses the sphere.
  EXPECT_GT(sphere.EdgeDistance(0, {-0.5, 1 - 2 * hit, 0.1}, {0.5, 1 - 2 * hit, 0.1}, 0), 0.0);
  EXPECT_GT(sphere.TimeOfImpact({-0.5, 1, 0.1}, {-0.5, -1, 0.1}, 0, 0, 0), 1.0);
  // A path that stays 0.24 clear (a quarter of its initial gap): no impact; one
  // that ends 0.05 clear is refused all the same (conservative: below
  // kEdgeGapFraction = 0.1 of the initial gap).
  EXPECT_GT(circle.EdgeTimeOfImpact(0, {-0.1, 1, 0}, {-0.1, 0.25, 0}, {0.1, 1, 0}, {0.1, 0.25, 0},
                                    0, 0, 0),
            1.0);
  EXPECT_LE(circle.EdgeTimeOfImpact(0, {-0.1, 1, 0}, {-0.1, 0.06, 0}, {0.1, 1, 0}, {0.1, 0.06, 0},
                                    0, 0, 0),
            1.0);
  // A moving circle (velocity +y) sweeps into a resting bar: impact from time 0
  // to 1 (the relative path is the falling bar's).
  const SphereObstacle rising(2, Eigen::Vector3d::Zero(), 0.01, Eigen::Vector3d(0, 2, 0));
  EXPECT_LE(
      rising.EdgeTimeOfImpact(0, {-0.1, 1, 0}, {-0.1, 1, 0}, {0.1, 1, 0}, {0.1, 1, 0}, 0, 1, 0),
      0.5);
  // Box corner (2D): a bar sweeping down across the top-right corner of Box(2)
  // at (1, 0.5) (the bar's line x + y from 1.7 to 1.3) with both end points
  // missing the box.
  const BoxObstacle box = Box(2);
  EXPECT_LE(
      box.EdgeTimeOfImpact(3, {0.9, 1, 0}, {1.1, -0.5, 0}, {1.5, 1, 0}, {1.7, -0.5, 0}, 0, 0, 0),
      1.0);
  // Starting within the margin: 0.
  EXPECT_EQ(box.EdgeTimeOfImpact(3, {0, 0.5, 0}, {0, 1, 0}, {2, 0.5, 0}, {2, 1, 0}, 0, 0, 1e-9),
            0.0);
}

TEST(SpatialHash, FindsOverlapsOnly) {
  SpatialHash hash(2, 0.1);
  hash.Insert(0, {0, 0, 0}, {0.05, 0.05, 0});
  hash.Insert(1, {1, 1, 0}, {1.05, 1.05, 0});
  hash.Insert(2, {-1e9, 0, 0}, {1e9, 0.01, 0});  // oversized: always a candidate
  std::vector<int> ids;
  hash.Query({0.01, 0.01, 0}, {0.02, 0.02, 0}, &ids);
  EXPECT_EQ(ids, (std::vector<int>{0, 2}));
  hash.Query({0.5, 0.5, 0}, {0.52, 0.52, 0}, &ids);
  EXPECT_EQ(ids, (std::vector<int>{2}));
}

// Jacobian of a cost function against central differences, block by block.
void CheckJacobian(const ceres::CostFunction& cost, std::vector<std::vector<double>> x,
                   double h = 1e-7, double tolerance = 1e-6) {
  testing::ExpectJacobianMatchesFiniteDifferences(cost, std::move(x), h, tolerance);
}

TEST(ContactTerms, JacobiansMatchFiniteDifferences) {
  const double d_hat = 0.05, time = 0.3;
  const SphereObstacle sphere = Sphere(3);
  // A point 0.02 from the moving sphere's surface: inside the barrier's reach.
  const Eigen::Vector3d centre = sphere.center() + sphere.velocity() * time;
  const Eigen::Vector3d p = centre + (sphere.radius() + 0.02) * Eigen::Vector3d(0.6, 0.0, 0.8);
  PointObstacleGap gap(3, &sphere, &time, d_hat, 0.0);
  CheckJacobian(gap, {{p[0], p[1], p[2]}});
  double residual;
  const double* x[1] = {p.data()};
  ASSERT_TRUE(gap.Evaluate(x, &residual, nullptr));
  EXPECT_NEAR(residual, d_hat - 0.02, 1e-14);
  // Inside the obstacle: the evaluation fails.
  const Eigen::Vector3d inside = centre;
  const double* y[1] = {inside.data()};
  EXPECT_FALSE(gap.Evaluate(y, &residual, nullptr));

  // Edge against the sphere's centre: the closest point 0.03 outside, interior.
  const Eigen::Vector3d n(0.0, 0.6, 0.8), tangent(1, 0, 0);
  const Eigen::Vector3d ea = centre + (sphere.radius() + 0.03) * n - 0.2 * tangent;
  const Eigen::Vector3d eb = centre + (sphere.radius() + 0.03) * n + 0.3 * tangent;
  EdgeObstacleGap edge_obstacle(3, &sphere, 0, &time, d_hat, 0.0);
  CheckJacobian(edge_obstacle, {{ea[0], ea[1], ea[2]}, {eb[0], eb[1], eb[2]}});
  const double* e[2] = {ea.data(), eb.data()};
  ASSERT_TRUE(edge_obstacle.Evaluate(e, &residual, nullptr));
  EXPECT_NEAR(residual, d_hat - 0.03, 1e-14);
  // A segment through the sphere with both end points outside: infeasible.
  const Eigen::Vector3d fa = centre - 2.0 * tangent, fb = centre + 2.0 * tangent;
  const double* f[2] = {fa.data(), fb.data()};
  EXPECT_FALSE(edge_obstacle.Evaluate(f, &residual, nullptr));
  // 2D box corner (lower left of Box(2) at (-1, -0.5)) against an edge.
  const BoxObstacle box = Box(2);
  EdgeObstacleGap corner_gap(2, &box, 0, &time, d_hat, 0.0);
  CheckJacobian(corner_gap, {{-1.3, -0.47}, {-0.8, -0.53}});

  PointEdgeGap edge_gap(d_hat, 0.0);
  CheckJacobian(edge_gap, {{0.4, 0.03}, {0.0, 0.0}, {1.0, 0.01}});

  StepContext context;
  context.Resize(2, 3);
  context.velocity_slope = 50.0;
  context.x_base << 0.1, 0.2, 0.3, 0.4, 0.5, 0.6;
  context.v_base << 1, 2, 3, 4, 5, 6;
  Eigen::Matrix3d tangents = Eigen::Matrix3d::Zero();
  tangents.col(0) = Eigen::Vector3d(0.6, 0.8, 0);
  ObstacleFriction friction(&context, 1, tangents, Eigen::Vector3d(0.5, 0, 0), 1e-3);
  CheckJacobian(friction, {{0.31, 0.42}});
  for (int side : {1, -1}) {
    // Speed scales below and above the tangential speed (both residual branches).
    for (double c : {0.05, 20.0}) {
      EdgeFriction edge_friction(&context, 0, 1, 2, Eigen::Vector2d(1, 0), 0.3, side, c);
      CheckJacobian(edge_friction, {{0.11, 0.2}, {0.3, 0.41}, {0.52, 0.6}});
      ObstacleFriction one_sided(&context, 1, tangents, Eigen::Vector3d(0.5, 0, 0), 1e-3, side, c);
      CheckJacobian(one_sided, {{0.31, 0.42}});
    }
  }
  // Sticking (|v_t| < eps_v): node 1 at x_base - v_base / slope + a small slip.
  ObstacleFriction sticking(&context, 1, tangents, Eigen::Vector3d(0, 0, 0), 1.0);
  CheckJacobian(sticking, {{0.3 - 3.0 / 50 + 0.002, 0.4 - 4.0 / 50 + 0.001}});

  // 3D, two tangent residuals.
  StepContext context3;
  context3.Resize(3, 1);
  context3.velocity_slope = 20.0;
  context3.v_base << 0.3, -0.2, 0.1;
  Eigen::Matrix3d tangents3 = Eigen::Matrix3d::Zero();
  tangents3.col(0) = Eigen::Vector3d(1, 0, 0);
  tangents3.col(1) = Eigen::Vector3d(0, 0, 1);
  for (double eps_v : {1e-3, 10.0}) {  // sliding, sticking
    ObstacleFriction friction3(&context3, 0, tangents3, Eigen::Vector3d::Zero(), eps_v);
    CheckJacobian(friction3, {{0.01, 0.02, -0.03}});
  }
}

}  // namespace
}  // namespace ipstep
