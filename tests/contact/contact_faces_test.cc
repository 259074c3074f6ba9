// 3D faces and box edges: point-triangle and segment-segment distances against
// brute-force sampling, closed forms and finite differences; their continuous
// collision detection against sphere centres, box corners and box edges; the
// face and box-edge barrier terms' Jacobians (lagged and true distances); the
// contact surface's faces.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "contact/collision_mesh.h"
#include "contact/contact_terms.h"
#include "contact/obstacle.h"
#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "core/input_error.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"
#include "problems/scene_loader.h"
#include "tests/support/finite_differences.h"

namespace ipstep {
namespace {

using V = Eigen::Vector3d;

// Smallest distance from p to the points w0 a + w1 b + w2 c on a barycentric
// grid of n intervals per side (includes the vertices and edges).
double SampledPointTriangle(const V& p, const V& a, const V& b, const V& c, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, ((1 - u - v) * a + u * b + v * c - p).norm());
    }
  }
  return best;
}

double SampledSegmentSegment(const V& a0, const V& a1, const V& b0, const V& b1, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) {
      const double s = double(i) / n, t = double(j) / n;
      best = std::min(best, (a0 + s * (a1 - a0) - b0 - t * (b1 - b0)).norm());
    }
  }
  return best;
}

V RandomPoint(std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return V(u(*rng), u(*rng), u(*rng));
}

TEST(PointTriangle, KnownRegions) {
  const V a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Above the interior: the projection.
  PointTriangleDistanceResult r = PointTriangleDistance(V(0.5, 0.5, 0.3), a, b, c);
  EXPECT_NEAR(r.distance, 0.3, 1e-15);
  EXPECT_NEAR(r.weights[1], 0.25, 1e-15);
  EXPECT_NEAR(r.weights[2], 0.25, 1e-15);
  EXPECT_NEAR(r.grad_p[2], 1.0, 1e-15);
  EXPECT_NEAR(r.grad_a[2], -0.5, 1e-15);
  // Beside the hypotenuse (edge region of b-c): closest point (1, 1, 0).
  r = PointTriangleDistance(V(2, 2, 1), a, b, c);
  EXPECT_NEAR(r.distance, std::sqrt(3.0), 1e-15);
  EXPECT_NEAR(r.weights[0], 0.0, 1e-15);
  EXPECT_NEAR(r.weights[1], 0.5, 1e-15);
  // Beyond the vertex a: the vertex.
  r = PointTriangleDistance(V(-1, -2, 2), a, b, c);
  EXPECT_NEAR(r.distance, 3.0, 1e-15);
  EXPECT_NEAR(r.weights[0], 1.0, 1e-15);
  // In the plane, inside: zero, no gradient.
  r = PointTriangleDistance(V(0.2, 0.3, 0), a, b, c);
  EXPECT_EQ(r.distance, 0.0);
  EXPECT_EQ(r.grad_p.norm(), 0.0);
  // Degenerate (collinear) triangle: its longest edge.
  r = PointTriangleDistance(V(1, 1, 0), a, b, V(1, 0, 0));
  EXPECT_NEAR(r.distance, 1.0, 1e-15);
}

TEST(PointTriangle, MatchesSamplingAndFiniteDifferences) {
  std::mt19937 rng(7);
  const int n = 200;
  for (int trial = 0; trial < 200; ++trial) {
    const V a = RandomPoint(&rng), b = RandomPoint(&rng), c = RandomPoint(&rng);
    const V p = 1.5 * RandomPoint(&rng);
    const PointTriangleDistanceResult r = PointTriangleDistance(p, a, b, c);
    const double sampled = SampledPointTriangle(p, a, b, c, n);
    // Exact <= every sample; the grid is within one cell diagonal of every
    // point of the triangle.
    const double cell = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    EXPECT_LE(r.distance, sampled + 1e-14) << trial;
    EXPECT_GE(r.distance, sampled - 2 * cell) << trial;
    EXPECT_NEAR(r.weights.sum(), 1.0, 1e-14);
    EXPECT_GE(r.weights.minCoeff(), 0.0);
    EXPECT_NEAR((r.weights[0] * a + r.weights[1] * b + r.weights[2] * c - p).norm(), r.distance,
                1e-14);
    // Gradients against central differences of the exact distance.
    const double h = 1e-7;
    const V* grads[4] = {&r.grad_p, &r.grad_a, &r.grad_b, &r.grad_c};
    for (int point = 0; point < 4; ++point) {
      for (int k = 0; k < 3; ++k) {
        V q[4] = {p, a, b, c}, m[4] = {p, a, b, c};
        q[point][k] += h;
        m[point][k] -= h;
        const double fd = (PointTriangleDistance(q[0], q[1], q[2], q[3]).distance -
                           PointTriangleDistance(m[0], m[1], m[2], m[3]).distance) /
                          (2 * h);
        EXPECT_NEAR((*grads[point])[k], fd, 1e-6) << trial << " " << point << " " << k;
      }
    }
  }
}

TEST(SegmentSegment, KnownConfigurations) {
  // Skew, crossing over each other: 0.5 apart at the middles.
  SegmentSegmentDistanceResult r =
      SegmentSegmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 0.5), V(0, 1, 0.5));
  EXPECT_NEAR(r.distance, 0.5, 1e-15);
  EXPECT_NEAR(r.s, 0.5, 1e-15);
  EXPECT_NEAR(r.t, 0.5, 1e-15);
  EXPECT_NEAR(r.grad_a0[2], -0.5, 1e-15);
  EXPECT_NEAR(r.grad_b1[2], 0.5, 1e-15);
  // Parallel, overlapping: the separation, at an end point of the overlap.
  r = SegmentSegmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 0.3, 0), V(3, 0.3, 0));
  EXPECT_NEAR(r.distance, 0.3, 1e-15);
  EXPECT_NEAR((V(0, 0, 0) + r.s * V(2, 0, 0) - V(1, 0.3, 0) - r.t * V(2, 0, 0)).norm(), 0.3, 1e-15);
  // Parallel, apart along their line: end point to end point.
  r = SegmentSegmentDistance(V(0, 0, 0), V(1, 0, 0), V(2, 0.4, 0), V(3, 0.4, 0));
  EXPECT_NEAR(r.distance, std::sqrt(1.0 + 0.16), 1e-15);
  EXPECT_NEAR(r.s, 1.0, 1e-15);
  EXPECT_NEAR(r.t, 0.0, 1e-15);
  // Collinear and overlapping: zero.
  r = SegmentSegmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 0, 0), V(3, 0, 0));
  EXPECT_EQ(r.distance, 0.0);
  // Nearly parallel (angle 1e-9): no loss of accuracy.
  r = SegmentSegmentDistance(V(0, 0, 0), V(1, 0, 0), V(0.25, 0.2, 0), V(0.75, 0.2, 1e-9));
  EXPECT_NEAR(r.distance, 0.2, 1e-12);
  // An end point against the other's interior (T shape).
  r = SegmentSegmentDistance(V(0, 0, 0), V(0, 1, 0), V(-1, -0.5, 0), V(1, -0.5, 0));
  EXPECT_NEAR(r.distance, 0.5, 1e-15);
  EXPECT_NEAR(r.s, 0.0, 1e-15);
  EXPECT_NEAR(r.t, 0.5, 1e-15);
}

TEST(SegmentSegment, MatchesSamplingAndFiniteDifferences) {
  std::mt19937 rng(11);
  const int n = 400;
  for (int trial = 0; trial < 200; ++trial) {
    const V a0 = RandomPoint(&rng), a1 = RandomPoint(&rng);
    V b0 = RandomPoint(&rng), b1 = RandomPoint(&rng);
    if (trial % 4 == 0) b1 = b0 + 0.7 * (a1 - a0);  // parallel
    const SegmentSegmentDistanceResult r = SegmentSegmentDistance(a0, a1, b0, b1);
    const double sampled = SampledSegmentSegment(a0, a1, b0, b1, n);
    const double cell = ((a1 - a0).norm() + (b1 - b0).norm()) / n;
    EXPECT_LE(r.distance, sampled + 1e-14) << trial;
    EXPECT_GE(r.distance, sampled - cell) << trial;
    EXPECT_NEAR((a0 + r.s * (a1 - a0) - b0 - r.t * (b1 - b0)).norm(), r.distance, 1e-14);
    if (trial % 4 == 0) continue;  // parallel: the closest points are not unique
    const double h = 1e-7;
    const V* grads[4] = {&r.grad_a0, &r.grad_a1, &r.grad_b0, &r.grad_b1};
    for (int point = 0; point < 4; ++point) {
      for (int k = 0; k < 3; ++k) {
        V q[4] = {a0, a1, b0, b1}, m[4] = {a0, a1, b0, b1};
        q[point][k] += h;
        m[point][k] -= h;
        const double fd = (SegmentSegmentDistance(q[0], q[1], q[2], q[3]).distance -
                           SegmentSegmentDistance(m[0], m[1], m[2], m[3]).distance) /
                          (2 * h);
        EXPECT_NEAR((*grads[point])[k], fd, 1e-6) << trial << " " << point << " " << k;
      }
    }
  }
  // Parallel: the distance's gradient along the common normal is still exact.
  const SegmentSegmentDistanceResult r =
      SegmentSegmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 0.3, 0), V(3, 0.3, 0));
  EXPECT_NEAR((r.grad_a0 + r.grad_a1)[1], -1.0, 1e-15);
  EXPECT_NEAR((r.grad_b0 + r.grad_b1)[1], 1.0, 1e-15);
}

TEST(PointTriangle, SegmentIntersection) {
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(SegmentIntersectsTriangle(V(0.2, 0.2, -1), V(0.2, 0.2, 1), a, b, c));
  EXPECT_FALSE(SegmentIntersectsTriangle(V(0.8, 0.8, -1), V(0.8, 0.8, 1), a, b, c));
  EXPECT_FALSE(SegmentIntersectsTriangle(V(0.2, 0.2, 0.1), V(0.2, 0.2, 1), a, b, c));
  // In the plane: crossing an edge, inside, beside.
  EXPECT_TRUE(SegmentIntersectsTriangle(V(-1, 0.5, 0), V(0.2, 0.5, 0), a, b, c));
  EXPECT_TRUE(SegmentIntersectsTriangle(V(0.1, 0.1, 0), V(0.2, 0.1, 0), a, b, c));
  EXPECT_FALSE(SegmentIntersectsTriangle(V(-1, 0.5, 0), V(-0.2, 0.5, 0), a, b, c));
}

SphereObstacle Sphere3(double radius, const V& velocity = V::Zero()) {
  return SphereObstacle(3, V::Zero(), radius, velocity);
}

BoxObstacle Box3(int dimension = 3) {
  return BoxObstacle(dimension, V(-0.5, -0.4, dimension == 3 ? -0.3 : 0.0),
                     V(0.5, 0.0, dimension == 3 ? 0.3 : 0.0));
}

TEST(Obstacle, FaceFeaturesAndBoxEdges) {
  EXPECT_EQ(Sphere3(1).NumFaceFeatures(), 1);
  EXPECT_EQ(Sphere3(1).NumBoxEdges(), 0);
  EXPECT_EQ(Box3().NumFaceFeatures(), 8);
  EXPECT_EQ(Box3().NumBoxEdges(), 12);
  EXPECT_EQ(Box3().NumEdgeFeatures(), 0);
  const BoxObstacle box2 = Box3(2);
  EXPECT_EQ(box2.NumFaceFeatures(), 0);
  EXPECT_EQ(box2.NumBoxEdges(), 0);
  EXPECT_EQ(box2.NumEdgeFeatures(), 4);
  // Every corner once; every box edge joins two corners differing in one axis.
  const BoxObstacle box = Box3();
  std::vector<V> corners;
  for (int k = 0; k < 8; ++k) corners.push_back(box.FaceFeature(k, 0.0));
  for (int i = 0; i < 8; ++i) {
    for (int j = i + 1; j < 8; ++j) EXPECT_GT((corners[i] - corners[j]).norm(), 0.1);
  }
  int found[8] = {};
  for (int e = 0; e < 12; ++e) {
    V p, q;
    box.BoxEdge(e, 0.0, &p, &q);
    int differing = 0;
    for (int k = 0; k < 3; ++k) differing += p[k] != q[k];
    EXPECT_EQ(differing, 1);
    for (int k = 0; k < 8; ++k)
      found[k] += (corners[k] - p).norm() == 0 || (corners[k] - q).norm() == 0;
  }
  for (int k = 0; k < 8; ++k) EXPECT_EQ(found[k], 3);  // three edges per corner
}

// Smallest gap over the path [0, s] of a sampled motion.
template <class Gap>
double SampledMinimum(const Gap& gap, double s, int n = 2000) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i) best = std::min(best, gap(s * i / n));
  return best;
}

TEST(FaceCollision, TriangleIsStoppedBeforeASmallSphere) {
  const SphereObstacle sphere = Sphere3(0.01);
  const double margin = 1e-12;
  // A large triangle falling flat through the sphere: its vertices pass far
  // outside, only the interior meets the sphere.
  const V v0[3] = {V(-1, 0.5, -1), V(1, 0.5, -1), V(0, 0.5, 1)};
  V v1[3];
  for (int k = 0; k < 3; ++k) v1[k] = v0[k] - V(0, 1, 0);
  auto gap = [&](double s) {
    return PointTriangleDistance(V::Zero(), v0[0] + s * (v1[0] - v0[0]),
                                 v0[1] + s * (v1[1] - v0[1]), v0[2] + s * (v1[2] - v0[2]))
               .distance -
           0.01;
  };
  const double s = sphere.FaceTimeOfImpact(0, v0, v1, 0.0, 0.0, margin);
  ASSERT_LE(s, 1.0);
  // Head-on: one advance to the goal 0.1 d(0).
  const double d0 = 0.49, goal = 0.1 * d0;
  EXPECT_NEAR(gap(s), goal, 1e-12);
  EXPECT_GE(SampledMinimum(gap, s), goal - 1e-12);
  // The same triangle moving sideways above the sphere: never within the goal.
  for (int k = 0; k < 3; ++k) v1[k] = v0[k] + V(3, -0.3, 0);
  EXPECT_EQ(sphere.FaceTimeOfImpact(0, v0, v1, 0.0, 0.0, margin), Obstacle::kNoImpact);
  // Oblique through the sphere, the sphere moving too (relative motion counts).
  const SphereObstacle moving = Sphere3(0.01, V(0, 2, 0));
  for (int k = 0; k < 3; ++k) v1[k] = v0[k] + V(0.3, -0.2, 0.1);
  auto moving_gap = [&](double s) {
    V y[3];
    for (int k = 0; k < 3; ++k) y[k] = v0[k] + s * (v1[k] - v0[k]) - moving.velocity() * (0.5 * s);
    return PointTriangleDistance(V::Zero(), y[0], y[1], y[2]).distance - 0.01;
  };
  const double sm = moving.FaceTimeOfImpact(0, v0, v1, 0.0, 0.5, margin);
  ASSERT_LE(sm, 1.0);
  const double goal_m = 0.1 * moving_gap(0.0);
  EXPECT_GE(SampledMinimum(moving_gap, sm), goal_m * (1 - 1e-9));
  EXPECT_LE(moving_gap(sm), goal_m + 0.011 * (moving_gap(0.0) - goal_m));
  EXPECT_LT(SampledMinimum(moving_gap, 1.0), 0.0);  // the full path would penetrate
  // Starting within the margin: 0.
  const V touching[3] = {V(-1, 0.01, -1), V(1, 0.01, -1), V(0, 0.01, 1)};
  EXPECT_EQ(sphere.FaceTimeOfImpact(0, touching, v1, 0.0, 0.0, 1e-9), 0.0);
}

TEST(FaceCollision, TriangleIsStoppedBeforeABoxCorner) {
  const BoxObstacle box = Box3();
  const V corner = box.FaceFeature(7, 0.0);  // (0.5, 0, 0.3)
  // A triangle tilted over the corner, all vertices outside the box, sliding
  // down and across it: the corner would pierce its interior.
  const V v0[3] = {corner + V(-0.3, 0.2, -0.3), corner + V(0.4, 0.25, -0.2),
                   corner + V(0.0, 0.3, 0.4)};
  V v1[3];
  for (int k = 0; k < 3; ++k) v1[k] = v0[k] + V(0.05, -0.6, 0.02);
  auto gap = [&](double s) {
    return PointTriangleDistance(corner, v0[0] + s * (v1[0] - v0[0]), v0[1] + s * (v1[1] - v0[1]),
                                 v0[2] + s * (v1[2] - v0[2]))
        .distance;
  };
  ASSERT_LT(SampledMinimum(gap, 1.0), 1e-3);  // the full path reaches the corner
  const double s = box.FaceTimeOfImpact(7, v0, v1, 0.0, 0.0, 1e-12);
  ASSERT_LE(s, 1.0);
  const double goal = 0.1 * gap(0.0);
  EXPECT_GE(SampledMinimum(gap, s), goal * (1 - 1e-9));
  EXPECT_LE(gap(s), goal + 0.011 * (gap(0.0) - goal));
  // Every other corner is far: no impact.
  for (int f = 0; f < 7; ++f) {
    if (f == 3 || f == 5 || f == 6) continue;  // share the top face's edges
    EXPECT_EQ(box.FaceTimeOfImpact(f, v0, v1, 0.0, 0.0, 1e-12), Obstacle::kNoImpact) << f;
  }
}

TEST(BoxEdgeCollision, SegmentCrossingABoxEdgeIsStopped) {
  const BoxObstacle box = Box3();
  // Box edge 1 runs along x at y = upper (0), z = lower (-0.3) (bit 0: next
  // axis y upper; bit 1 clear: the axis after, z, lower).
  V p, q;
  box.BoxEdge(1, 0.0, &p, &q);
  ASSERT_EQ(p, V(-0.5, 0.0, -0.3));
  ASSERT_EQ(q, V(0.5, 0.0, -0.3));
  // A segment across the edge (along z), both ends outside the box over the
  // whole path: it slides down over the edge's side, crossing it.
  const V a0(0.1, 0.2, -0.6), b0(0.1, 0.2, -0.35), a1(0.1, -0.2, -0.6), b1(0.1, -0.2, -0.35);
  auto gap = [&](double s) {
    return SegmentSegmentDistance(a0 + s * (a1 - a0), b0 + s * (b1 - b0), p, q).distance;
  };
  // Both end points stay outside the box along the path (z < -0.3).
  EXPECT_LT(SampledMinimum(gap, 1.0), 0.06);
  const V a_mid(0.1, 0.0, -0.6), b_mid(0.1, 0.0, -0.25);  // crossing: distance 0
  EXPECT_EQ(SegmentSegmentDistance(a_mid, b_mid, p, q).distance, 0.0);
  const V b1x(0.1, -0.2, -0.25), b0x(0.1, 0.2, -0.25);
  auto crossing_gap = [&](double s) {
    return SegmentSegmentDistance(a0 + s * (a1 - a0), b0x + s * (b1x - b0x), p, q).distance;
  };
  ASSERT_EQ(crossing_gap(0.5), 0.0);
  const double s = box.BoxEdgeTimeOfImpact(1, a0, a1, b0x, b1x, 0.0, 0.0, 1e-12);
  ASSERT_LE(s, 1.0);
  const double goal = 0.1 * crossing_gap(0.0);
  EXPECT_GE(SampledMinimum(crossing_gap, s), goal * (1 - 1e-9));
  EXPECT_LE(crossing_gap(s), goal + 0.011 * (crossing_gap(0.0) - goal));
  // Parallel to the edge, passing above it: no impact.
  const V c0(-0.2, 0.3, -0.3), d0(0.2, 0.3, -0.3), c1(-0.2, 0.3, -0.1), d1(0.2, 0.3, -0.1);
  EXPECT_EQ(box.BoxEdgeTimeOfImpact(1, c0, c1, d0, d1, 0.0, 0.0, 1e-12), Obstacle::kNoImpact);
  // Parallel, coming down onto the edge: stopped above it.
  const V e1(-0.2, -0.1, -0.3), f1(0.2, -0.1, -0.3);
  const double sp = box.BoxEdgeTimeOfImpact(1, c0, e1, d0, f1, 0.0, 0.0, 1e-12);
  EXPECT_NEAR(sp, 0.9 * 0.3 / 0.4, 1e-12);
}

void CheckJacobian(const ceres::CostFunction& cost, std::vector<std::vector<double>> x) {
  testing::ExpectJacobianMatchesFiniteDifferences(cost, std::move(x), 1e-7, 1e-6);
}

TEST(FaceTerms, JacobiansMatchFiniteDifferencesAndFailInside) {
  const double d_hat = 0.05, time = 0.3;
  const SphereObstacle sphere = Sphere3(0.2, V(0.1, -0.2, 0.3));
  const V centre = sphere.velocity() * time;
  // A triangle 0.03 above the sphere's top, its closest point inside.
  const V a = centre + V(-0.1, 0.23, -0.1), b = centre + V(0.12, 0.235, -0.05),
          c = centre + V(0.0, 0.228, 0.15);
  const Eigen::Vector3d w = sphere.FaceDistance(0, a, b, c, time, nullptr, nullptr) > 0
                                ? PointTriangleDistance(centre, a, b, c).weights
                                : V(1, 0, 0);
  FaceObstacleGap gap(&sphere, 0, &time, d_hat, 0.0, &w);
  CheckJacobian(gap, {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]}});
  double residual = 0.0;
  const double* x[3] = {a.data(), b.data(), c.data()};
  ASSERT_TRUE(gap.Evaluate(x, &residual, nullptr));
  EXPECT_NEAR(residual, d_hat - sphere.FaceDistance(0, a, b, c, time), 1e-14);
  // A lagged point elsewhere on the face: a larger gap, still a valid term.
  const V lagged(0.6, 0.2, 0.2);
  FaceObstacleGap lagged_gap(&sphere, 0, &time, d_hat, 0.0, &lagged);
  CheckJacobian(lagged_gap, {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]}});
  double lagged_residual = 0.0;
  ASSERT_TRUE(lagged_gap.Evaluate(x, &lagged_residual, nullptr));
  EXPECT_LT(lagged_residual, residual);
  // The sphere bulging through the interior (all vertices outside): fails.
  const V a2 = centre + V(-0.5, 0.1, -0.5), b2 = centre + V(0.5, 0.1, -0.5),
          c2 = centre + V(0.0, 0.1, 0.5);
  const double* y[3] = {a2.data(), b2.data(), c2.data()};
  EXPECT_FALSE(gap.Evaluate(y, &residual, nullptr));

  // Box corner 7 (0.5, 0, 0.3) against a face, and a box edge against a segment.
  const BoxObstacle box = Box3();
  const V corner = box.FaceFeature(7, 0.0);
  const V p = corner + V(-0.1, 0.02, -0.1), q = corner + V(0.1, 0.03, -0.05),
          r = corner + V(0.0, 0.025, 0.1);
  // Box features use the true distance (no lag).
  FaceObstacleGap corner_gap(&box, 7, &time, d_hat, 0.0);
  CheckJacobian(corner_gap, {{p[0], p[1], p[2]}, {q[0], q[1], q[2]}, {r[0], r[1], r[2]}});
  const double* t3[3] = {p.data(), q.data(), r.data()};
  ASSERT_TRUE(corner_gap.Evaluate(t3, &residual, nullptr));
  EXPECT_NEAR(residual, d_hat - PointTriangleDistance(corner, p, q, r).distance, 1e-14);
  EdgeBoxEdgeGap edge_gap(&box, 1, &time, d_hat, 0.0);
  const V ea(0.1, 0.02, -0.4), eb(0.15, 0.03, -0.2);
  CheckJacobian(edge_gap, {{ea[0], ea[1], ea[2]}, {eb[0], eb[1], eb[2]}});
  const double* e[2] = {ea.data(), eb.data()};
  ASSERT_TRUE(edge_gap.Evaluate(e, &residual, nullptr));
  EXPECT_NEAR(residual, d_hat - box.BoxEdgeDistance(1, ea, eb, time), 1e-14);
  // Crossing the box edge (both ends outside the box): fails.
  const V fa(0.1, 0.0, -0.4), fb(0.1, 0.0, -0.2);
  const double* f[2] = {fa.data(), fb.data()};
  EXPECT_FALSE(edge_gap.Evaluate(f, &residual, nullptr));
}

// The collision mesh is the declared surface: a 3 x 3 grid generator
// declares two triangles per cell; edges are the triangles' (structural and
// one diagonal, no bending or second diagonal), weights are areas.
TEST(CollisionMesh, GridDeclaresTwoTrianglesPerCell) {
  const double a = 0.5;
  const nlohmann::json json = {{"dimension", 3},
                               {"effects", {"springs"}},
                               {"grid",
                                {{"nx", 3},
                                 {"ny", 3},
                                 {"width", 2 * a},
                                 {"height", 2 * a},
                                 {"plane", "xz"},
                                 {"total_mass", 1},
                                 {"structural", {{"model", "hookean"}, {"stiffness", 1}}},
                                 {"shear", {{"model", "hookean"}, {"stiffness", 1}}},
                                 {"bending", {{"model", "hookean"}, {"stiffness", 1}}}}}};
  const Scene scene = ParseScene(json, "grid.json");
  const CollisionMesh mesh = BuildCollisionMesh(scene);
  EXPECT_EQ(mesh.nodes.size(), 9u);
  EXPECT_EQ(mesh.edges.size(), 12u + 4u);  // structural + one diagonal per cell
  ASSERT_EQ(mesh.faces.size(), 8u);
  for (double w : mesh.face_weights) EXPECT_NEAR(w, a * a / 2, 1e-15);
  double total = 0.0;
  for (double w : mesh.weights) total += w;
  EXPECT_NEAR(total, 4 * a * a, 1e-14);        // node weights share the area once
  EXPECT_NEAR(mesh.weights[4], a * a, 1e-15);  // the centre node: six triangles
  // Every interior point of a cell (off its diagonal) lies in exactly one face.
  for (const V& p : {V(0.2, 0.0, -0.1), V(0.1, 0.0, -0.2), V(0.7, 0.0, -0.6)}) {
    int covering = 0;
    for (const auto& t : mesh.faces) {
      const V q(p[0], 0.0, p[2]);
      covering += PointTriangleDistance(q, ToPoint(scene.positions.data() + 3 * t[0], 3),
                                        ToPoint(scene.positions.data() + 3 * t[1], 3),
                                        ToPoint(scene.positions.data() + 3 * t[2], 3))
                      .distance < 1e-15;
    }
    EXPECT_EQ(covering, 1) << p.transpose();
  }
}

// Listed nodes with springs must declare their surface; declared primitives
// must not be degenerate.
TEST(CollisionMesh, UndeclaredOrDegenerateSurfaceIsAnInputError) {
  Scene scene;
  scene.source = "s.json";
  scene.dimension = 3;
  scene.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  scene.masses = {1, 1, 1};
  scene.springs = {Spring{0, 1, SpringModel::kHookean, 1.0, 1.0}};
  EXPECT_THROW(BuildCollisionMesh(scene), InputError);
  scene.surface.declared = true;
  scene.surface.triangles = {{0, 1, 2}};  // collinear
  try {
    BuildCollisionMesh(scene);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json: surface: triangle (0, 1, 2) is degenerate"),
              std::string::npos)
        << e.what();
  }
  scene.surface.triangles.clear();
  scene.surface.edges = {{0, 1}};
  scene.surface.points = {2};
  const CollisionMesh mesh = BuildCollisionMesh(scene);
  ASSERT_EQ(mesh.nodes.size(), 3u);
  EXPECT_DOUBLE_EQ(mesh.weights[0], 0.5);  // half the edge
  EXPECT_DOUBLE_EQ(mesh.weights[2], 1.0);  // a point
  EXPECT_DOUBLE_EQ(mesh.edge_weights[0], 0.25);
  // The node -> slot table every pair kind reads: -1 off the surface.
  scene.surface.edges = {{0, 2}};
  scene.surface.points.clear();
  const CollisionMesh ends = BuildCollisionMesh(scene);
  ASSERT_EQ(ends.nodes, std::vector<int>({0, 2}));
  EXPECT_EQ(ends.node_slots, std::vector<int>({0, -1, 1}));
  EXPECT_EQ(NodeSlot(ends, 2), 1);
}

}  // namespace
}  // namespace ipstep
