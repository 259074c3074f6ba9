// Analytic Hessians of the contact distances (contact/distance_hessian.h)
// against central differences of the analytic gradients (contact/obstacle.h,
// point_edge.h), case by case and region by region, at random well-conditioned
// configurations, static and moving obstacles, 2D and 3D; the gap terms'
// analytic curvature against the Newton model built from finite differences
// of their Jacobians (core/term_hessian.h); and the terms the contact state
// builds carrying it.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "contact/barrier.h"
#include "contact/contact_filter.h"
#include "contact/contact_terms.h"
#include "contact/distance_hessian.h"
#include "contact/obstacle.h"
#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/plane_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "core/term_hessian.h"
#include "energies/effect_registry.h"
#include "geometry/point_edge.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_parameter.h"
#include "geometry/segment_segment.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"

namespace ipstep {
namespace {

using V = Eigen::Vector3d;
using Gradient = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

constexpr double kStep = 1e-6;
constexpr double kRelativeTolerance = 1e-6;
constexpr int kTrials = 20;

// Central differences of the gradient: column j = (g(x + h e_j) - g(x - h e_j)) / 2h.
Eigen::MatrixXd DifferenceHessian(const Gradient& gradient, Eigen::VectorXd x) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd h(n, n);
  for (int j = 0; j < n; ++j) {
    const double saved = x[j];
    x[j] = saved + kStep;
    const Eigen::VectorXd up = gradient(x);
    x[j] = saved - kStep;
    const Eigen::VectorXd down = gradient(x);
    x[j] = saved;
    h.col(j) = (up - down) / (2.0 * kStep);
  }
  return h;
}

// The analytic Hessian matches the differences within kRelativeTolerance of
// its largest entry, is symmetric, and is nonzero (expect_zero: exactly zero,
// and so are the differences).
void ExpectHessian(const Eigen::MatrixXd& analytic, const Gradient& gradient,
                   const Eigen::VectorXd& x, bool expect_zero, const std::string& what) {
  const Eigen::MatrixXd differences = DifferenceHessian(gradient, x);
  const double scale = analytic.cwiseAbs().maxCoeff();
  if (expect_zero) {
    EXPECT_EQ(scale, 0.0) << what;
    EXPECT_LE(differences.cwiseAbs().maxCoeff(), 1e-8) << what;
    return;
  }
  EXPECT_GT(scale, 1e-2) << what;
  EXPECT_LE((analytic - differences).cwiseAbs().maxCoeff(), kRelativeTolerance * scale)
      << what << "\nanalytic\n"
      << analytic << "\ndifferences\n"
      << differences;
  EXPECT_LE((analytic - analytic.transpose()).cwiseAbs().maxCoeff(), 1e-12 * scale) << what;
}

// Rows and columns of the first `dimension` coordinates of each of n 3D blocks.
Eigen::MatrixXd Restrict(const Eigen::MatrixXd& h, int blocks, int dimension) {
  Eigen::MatrixXd r(blocks * dimension, blocks * dimension);
  for (int bi = 0; bi < blocks; ++bi) {
    for (int ki = 0; ki < dimension; ++ki) {
      for (int bj = 0; bj < blocks; ++bj) {
        for (int kj = 0; kj < dimension; ++kj) {
          r(bi * dimension + ki, bj * dimension + kj) = h(bi * 3 + ki, bj * 3 + kj);
        }
      }
    }
  }
  return r;
}

Eigen::VectorXd Stack(std::initializer_list<V> points, int dimension) {
  Eigen::VectorXd x(static_cast<int>(points.size()) * dimension);
  int k = 0;
  for (const V& p : points) x.segment(dimension * k++, dimension) = p.head(dimension);
  return x;
}

V Block(const Eigen::VectorXd& x, int block, int dimension) {
  V p = V::Zero();
  p.head(dimension) = x.segment(block * dimension, dimension);
  return p;
}

class Random {
 public:
  explicit Random(unsigned seed) : engine_(seed) {}
  double Uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(engine_); }
  // A unit vector in the first `dimension` axes.
  V Direction(int dimension) {
    V v = V::Zero();
    while (v.norm() < 0.1) {
      for (int k = 0; k < dimension; ++k) v[k] = Uniform(-1.0, 1.0);
    }
    return v.normalized();
  }
  // A unit vector orthogonal to the unit vector n.
  V Orthogonal(const V& n, int dimension) {
    if (dimension == 2) return V(-n[1], n[0], 0.0);
    V v = Direction(3);
    while ((v - v.dot(n) * n).norm() < 0.1) v = Direction(3);
    return (v - v.dot(n) * n).normalized();
  }
  int Index(int n) { return std::uniform_int_distribution<>(0, n - 1)(engine_); }

 private:
  std::mt19937 engine_;
};

// Obstacles: static at t = 0 or translating, seen at t = 0.7.
enum class Shape { kPlane, kSphere, kBox };

struct Scenario {
  ObstaclePtr obstacle;
  Shape shape = Shape::kPlane;
  V point = V::Zero();  // plane: a point on it; sphere: its centre
  double radius = 0.0;
  V lower = V::Zero(), upper = V::Zero();  // box
  double t = 0.0;
  std::string name;
};

// The gradient of the point-obstacle distance of scenario s (positions of
// s.obstacle->dimension() coordinates).
Gradient PointDistanceGradient(const Scenario& s) {
  const int dim = s.obstacle->dimension();
  return [&s, dim](const Eigen::VectorXd& y) {
    V g;
    s.obstacle->Distance(Block(y, 0, dim), s.t, &g);
    return Eigen::VectorXd(g.head(dim));
  };
}

Scenario MakeScenario(Shape shape, int dimension, bool moving) {
  Scenario s;
  s.shape = shape;
  s.point = V(0.1, -0.2, dimension == 3 ? 0.3 : 0.0);
  const V normal = V(0.3, 0.9, dimension == 3 ? 0.2 : 0.0).normalized();
  s.radius = 0.5;
  s.lower = V(-0.5, -0.4, dimension == 3 ? -0.3 : 0.0);
  s.upper = V(0.6, 0.5, dimension == 3 ? 0.4 : 0.0);
  const V velocity = moving ? V(0.3, -0.2, dimension == 3 ? 0.1 : 0.0) : V::Zero();
  switch (shape) {
    case Shape::kPlane:
      s.obstacle = std::make_shared<PlaneObstacle>(dimension, s.point, normal, velocity);
      break;
    case Shape::kSphere:
      s.obstacle = std::make_shared<SphereObstacle>(dimension, s.point, s.radius, velocity);
      break;
    case Shape::kBox:
      s.obstacle = std::make_shared<BoxObstacle>(dimension, s.lower, s.upper, velocity);
      break;
  }
  s.t = moving ? 0.7 : 0.0;
  s.name = std::string(s.obstacle->type_name()) + " " + std::to_string(dimension) + "D" +
           (moving ? " moving" : " static");
  return s;
}

std::vector<Scenario> Scenarios(Shape type, std::initializer_list<int> dimensions) {
  std::vector<Scenario> all;
  for (int dimension : dimensions) {
    for (bool moving : {false, true}) all.push_back(MakeScenario(type, dimension, moving));
  }
  return all;
}

// ---------------------------------------------------------------- points

TEST(DistanceHessian, PointPlaneIsZero) {
  Random random(1);
  for (const Scenario& s : Scenarios(Shape::kPlane, {2, 3})) {
    const int dim = s.obstacle->dimension();
    for (int trial = 0; trial < kTrials; ++trial) {
      const V x = s.point + s.obstacle->velocity() * s.t + 2.0 * random.Direction(dim);
      Eigen::Matrix3d h;
      ASSERT_TRUE(ObstacleDistanceHessian(*s.obstacle, x, s.t, &h));
      const Gradient gradient = PointDistanceGradient(s);
      ExpectHessian(h.topLeftCorner(dim, dim), gradient, Stack({x}, dim), true, s.name);
    }
  }
}

TEST(DistanceHessian, PointSphere) {
  Random random(2);
  for (const Scenario& s : Scenarios(Shape::kSphere, {2, 3})) {
    const int dim = s.obstacle->dimension();
    for (int trial = 0; trial < kTrials; ++trial) {
      const V centre = s.point + s.obstacle->velocity() * s.t;
      const V x = centre + random.Uniform(0.7, 1.5) * random.Direction(dim);
      Eigen::Matrix3d h;
      ASSERT_TRUE(ObstacleDistanceHessian(*s.obstacle, x, s.t, &h));
      const Gradient gradient = PointDistanceGradient(s);
      ExpectHessian(h.topLeftCorner(dim, dim), gradient, Stack({x}, dim), false, s.name);
    }
  }
}

// A point outside the box by [0.2, 0.2 + span] in the axes set in `outside`
// (the others within the slab, 0.1 from its faces at least).
V PointNearBox(const Scenario& s, const bool outside[3], double span, Random* random) {
  const Obstacle& o = *s.obstacle;
  V x = V::Zero();
  for (int k = 0; k < o.dimension(); ++k) {
    if (outside[k]) {
      x[k] = random->Index(2) ? s.upper[k] + random->Uniform(0.2, 0.2 + span)
                              : s.lower[k] - random->Uniform(0.2, 0.2 + span);
    } else {
      x[k] = random->Uniform(s.lower[k] + 0.1, s.upper[k] - 0.1);
    }
  }
  return x + o.velocity() * s.t;
}

TEST(DistanceHessian, PointBoxFaceEdgeCorner) {
  Random random(3);
  for (const Scenario& s : Scenarios(Shape::kBox, {2, 3})) {
    const int dim = s.obstacle->dimension();
    // Number of axes outside the slab: 0 inside, 1 face (2D: side), 2 edge
    // (2D: corner), 3 corner.
    for (int count = 0; count <= dim; ++count) {
      for (int trial = 0; trial < kTrials; ++trial) {
        bool outside[3] = {false, false, false};
        for (int k = 0; k < count;) {
          const int axis = random.Index(dim);
          if (!outside[axis]) {
            outside[axis] = true;
            ++k;
          }
        }
        const V x = PointNearBox(s, outside, 0.6, &random);
        Eigen::Matrix3d h;
        ASSERT_TRUE(ObstacleDistanceHessian(*s.obstacle, x, s.t, &h));
        const Gradient gradient = PointDistanceGradient(s);
        // The distance is affine inside and in the face (side) regions.
        ExpectHessian(h.topLeftCorner(dim, dim), gradient, Stack({x}, dim), count <= 1,
                      s.name + " axes outside " + std::to_string(count));
      }
    }
  }
}

// ---------------------------------------------------------------- segments

// Segment [a, b] near the point c: closest point interior (region 1, alpha in
// [0.2, 0.8]) or an end point (region 0: a, region 2: b), at distance
// [low, low + span] from c.
void SegmentNearPoint(const V& c, int dim, int region, double low, double span, Random* random,
                      V* a, V* b) {
  const V e = random->Direction(dim);
  const double length = random->Uniform(0.5, 1.5), h = random->Uniform(low, low + span);
  if (region == 1) {
    const V n = random->Orthogonal(e, dim);
    *a = c + h * n - random->Uniform(0.2, 0.8) * length * e;
    *b = *a + length * e;
    return;
  }
  // The end point at c + h m with the segment leaving c: m . e >= 0.3.
  V m = random->Direction(dim);
  while (m.dot(e) < 0.3) m = random->Direction(dim);
  const V end = c + h * m;
  if (region == 0) {
    *a = end;
    *b = end + length * e;
  } else {
    *b = end;
    *a = end + length * e;
  }
}

std::vector<Scenario> EdgeScenarios() {
  std::vector<Scenario> all = Scenarios(Shape::kSphere, {2, 3});
  for (const Scenario& s : Scenarios(Shape::kBox, {2})) all.push_back(s);
  return all;
}

TEST(DistanceHessian, SegmentPointFeatureEndsAndInterior) {
  Random random(4);
  for (const Scenario& s : EdgeScenarios()) {
    const Obstacle& o = *s.obstacle;
    const int dim = o.dimension();
    for (int feature = 0; feature < o.NumEdgeFeatures(); ++feature) {
      const V c = o.EdgeFeature(feature, s.t);
      for (int region = 0; region < 3; ++region) {
        for (int trial = 0; trial < kTrials; ++trial) {
          V a, b;
          SegmentNearPoint(c, dim, region, o.FeatureRadius() + 0.2, 0.8, &random, &a, &b);
          const double alpha = ClosestSegmentParameter(c, a, b);
          ASSERT_EQ(region == 1, alpha > 0.1 && alpha < 0.9) << alpha;
          Matrix6d h;
          ASSERT_TRUE(EdgeDistanceHessian(o, feature, a, b, s.t, &h));
          const Gradient gradient = [&](const Eigen::VectorXd& y) {
            V ga, gb;
            o.EdgeDistance(feature, Block(y, 0, dim), Block(y, 1, dim), s.t, &ga, &gb);
            return Eigen::VectorXd(Stack({ga, gb}, dim));
          };
          ExpectHessian(
              Restrict(h, 2, dim), gradient, Stack({a, b}, dim), false,
              s.name + " feature " + std::to_string(feature) + " region " + std::to_string(region));
        }
      }
    }
  }
}

TEST(DistanceHessian, SegmentFixedPoint) {
  Random random(5);
  for (const Scenario& s : EdgeScenarios()) {
    const Obstacle& o = *s.obstacle;
    const int dim = o.dimension();
    for (int feature = 0; feature < o.NumEdgeFeatures(); ++feature) {
      const V c = o.EdgeFeature(feature, s.t);
      for (int trial = 0; trial < kTrials; ++trial) {
        V a, b;
        SegmentNearPoint(c, dim, random.Index(3), o.FeatureRadius() + 0.2, 0.8, &random, &a, &b);
        const double alpha = random.Uniform(0.0, 1.0);
        Matrix6d h;
        ASSERT_TRUE(EdgePointDistanceHessian(o, feature, a, b, alpha, s.t, &h));
        const Gradient gradient = [&](const Eigen::VectorXd& y) {
          V ga, gb;
          o.EdgePointDistance(feature, Block(y, 0, dim), Block(y, 1, dim), alpha, s.t, &ga, &gb);
          return Eigen::VectorXd(Stack({ga, gb}, dim));
        };
        ExpectHessian(Restrict(h, 2, dim), gradient, Stack({a, b}, dim), false, s.name);
      }
    }
  }
}

// ---------------------------------------------------------------- triangles

// A triangle (vertices x[0..2]) near the point p, with the closest point in
// `region`: 0 interior, 1..3 the edge from vertex region - 1 to the next, 4..6
// vertex region - 4. The distance is in [low, low + span].
void TriangleNearPoint(const V& p, int region, double low, double span, Random* random, V x[3]) {
  V e0, e1;
  do {
    e0 = random->Uniform(0.6, 1.4) * random->Direction(3);
    e1 = random->Uniform(0.6, 1.4) * random->Direction(3);
  } while (e0.cross(e1).norm() < 0.4 * e0.norm() * e1.norm());
  V y[3] = {V::Zero(), e0, e1};  // the triangle around the origin, shifted below
  const V normal = e0.cross(e1).normalized();
  // Outward in-plane normal of the edge from vertex i to i + 1.
  auto outward = [&](int i) {
    const V edge = y[(i + 1) % 3] - y[i];
    V m = normal.cross(edge).normalized();
    if (m.dot(y[(i + 2) % 3] - y[i]) > 0.0) m = -m;
    return m;
  };
  const double h = random->Uniform(low, low + span);
  V q, offset;
  if (region == 0) {
    V w(random->Uniform(0.2, 1.0), random->Uniform(0.2, 1.0), random->Uniform(0.2, 1.0));
    w /= w.sum();
    q = w[0] * y[0] + w[1] * y[1] + w[2] * y[2];
    offset = (random->Index(2) ? 1.0 : -1.0) * normal;
  } else if (region <= 3) {
    const int i = region - 1;
    q = y[i] + random->Uniform(0.2, 0.8) * (y[(i + 1) % 3] - y[i]);
    const double angle = random->Uniform(-1.2, 1.2);
    offset = std::cos(angle) * outward(i) + std::sin(angle) * normal;
  } else {
    const int i = region - 4;
    q = y[i];
    // Within the normal cone: both adjacent edges' outward normals.
    const V cone = random->Uniform(0.3, 1.0) * outward(i) +
                   random->Uniform(0.3, 1.0) * outward((i + 2) % 3) +
                   random->Uniform(-0.8, 0.8) * normal;
    offset = cone.normalized();
  }
  for (int k = 0; k < 3; ++k) x[k] = y[k] - q + p - h * offset;
}

// The closest point's region from its weights (as TriangleNearPoint numbers it).
int TriangleRegion(const V& w) {
  int count = 0;
  for (int k = 0; k < 3; ++k) count += w[k] > 0.0;
  if (count == 3) return 0;
  for (int k = 0; k < 3; ++k) {
    if (count == 2 && w[(k + 2) % 3] == 0.0) return 1 + k;
    if (count == 1 && w[k] > 0.0) return 4 + k;
  }
  return -1;
}

std::vector<Scenario> FaceScenarios() {
  std::vector<Scenario> all = Scenarios(Shape::kSphere, {3});
  for (const Scenario& s : Scenarios(Shape::kBox, {3})) all.push_back(s);
  return all;
}

TEST(DistanceHessian, TrianglePointFeatureVertexEdgeInterior) {
  Random random(6);
  for (const Scenario& s : FaceScenarios()) {
    const Obstacle& o = *s.obstacle;
    for (int feature = 0; feature < o.NumFaceFeatures(); ++feature) {
      const V p = o.FaceFeature(feature, s.t);
      for (int region = 0; region < 7; ++region) {
        for (int trial = 0; trial < kTrials; ++trial) {
          V x[3];
          TriangleNearPoint(p, region, o.FeatureRadius() + 0.2, 0.8, &random, x);
          ASSERT_EQ(TriangleRegion(PointTriangleDistance(p, x[0], x[1], x[2]).weights), region);
          Matrix9d h;
          ASSERT_TRUE(FaceDistanceHessian(o, feature, x[0], x[1], x[2], s.t, &h));
          const Gradient gradient = [&](const Eigen::VectorXd& y) {
            V g[3];
            o.FaceDistance(feature, y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), s.t, g);
            return Eigen::VectorXd(Stack({g[0], g[1], g[2]}, 3));
          };
          ExpectHessian(
              h, gradient, Stack({x[0], x[1], x[2]}, 3), false,
              s.name + " feature " + std::to_string(feature) + " region " + std::to_string(region));
        }
      }
    }
  }
}

TEST(DistanceHessian, TriangleFixedWeights) {
  Random random(7);
  for (const Scenario& s : FaceScenarios()) {
    const Obstacle& o = *s.obstacle;
    for (int feature = 0; feature < o.NumFaceFeatures(); ++feature) {
      const V p = o.FaceFeature(feature, s.t);
      for (int trial = 0; trial < kTrials; ++trial) {
        V x[3];
        TriangleNearPoint(p, random.Index(7), o.FeatureRadius() + 0.2, 0.8, &random, x);
        V w(random.Uniform(0.0, 1.0), random.Uniform(0.0, 1.0), random.Uniform(0.0, 1.0));
        w /= w.sum();
        Matrix9d h;
        ASSERT_TRUE(FacePointDistanceHessian(o, feature, x[0], x[1], x[2], w, s.t, &h));
        const Gradient gradient = [&](const Eigen::VectorXd& y) {
          V g[3];
          o.FacePointDistance(feature, y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), w, s.t,
                              g);
          return Eigen::VectorXd(Stack({g[0], g[1], g[2]}, 3));
        };
        ExpectHessian(h, gradient, Stack({x[0], x[1], x[2]}, 3), false, s.name);
      }
    }
  }
}

// ---------------------------------------------------------------- box edges

// A segment [a, b] near the fixed segment [p, q] with the closest points'
// parameters (s on [a, b], t on [p, q]) free or at a bound: s_free, t_free;
// at distance [0.2, 0.2 + span].
void SegmentNearSegment(const V& p, const V& q, bool s_free, bool t_free, double span,
                        Random* random, V* a, V* b) {
  const V f = (q - p).normalized();
  const double h = random->Uniform(0.2, 0.2 + span), length = random->Uniform(0.5, 1.5);
  // The closest point of [p, q]: interior, or p with the offset beyond it.
  V base, m;
  if (t_free) {
    base = p + random->Uniform(0.2, 0.8) * (q - p);
    m = random->Orthogonal(f, 3);
  } else {
    base = p;
    do m = random->Direction(3);
    while (m.dot(f) > -0.3);
  }
  const V near = base + h * m;  // the closest point of [a, b]
  V e;
  if (s_free) {
    // The segment through `near`, orthogonal to m and not parallel to f.
    do e = random->Orthogonal(m, 3);
    while (std::abs(e.dot(f)) > 0.9);
    *a = near - random->Uniform(0.2, 0.8) * length * e;
  } else {
    do e = random->Direction(3);
    while (e.dot(m) < 0.3);
    *a = near;
  }
  *b = *a + length * e;
}

TEST(DistanceHessian, SegmentBoxEdgeFreeAndBoundParameters) {
  Random random(8);
  for (const Scenario& s : Scenarios(Shape::kBox, {3})) {
    const Obstacle& o = *s.obstacle;
    for (int edge = 0; edge < o.NumBoxEdges(); ++edge) {
      V p, q;
      o.BoxEdge(edge, s.t, &p, &q);
      for (int region = 0; region < 4; ++region) {
        const bool s_free = region & 1, t_free = region & 2;
        for (int trial = 0; trial < kTrials; ++trial) {
          V a, b;
          SegmentNearSegment(p, q, s_free, t_free, 0.8, &random, &a, &b);
          const SegmentSegmentDistanceResult r = SegmentSegmentDistance(a, b, p, q);
          ASSERT_EQ(s_free, r.s > 0.1 && r.s < 0.9) << r.s;
          ASSERT_EQ(t_free, r.t > 0.1 && r.t < 0.9) << r.t;
          Matrix6d h;
          ASSERT_TRUE(BoxEdgeDistanceHessian(o, edge, a, b, s.t, &h));
          const Gradient gradient = [&](const Eigen::VectorXd& y) {
            V ga, gb;
            o.BoxEdgeDistance(edge, y.segment<3>(0), y.segment<3>(3), s.t, &ga, &gb);
            return Eigen::VectorXd(Stack({ga, gb}, 3));
          };
          ExpectHessian(
              h, gradient, Stack({a, b}, 3), false,
              s.name + " edge " + std::to_string(edge) + " region " + std::to_string(region));
        }
      }
    }
  }
}

// Parallel segments: the distance code puts the closest points at an end point
// (a bound), so f_ll stays regular; the Hessian is finite and symmetric.
TEST(DistanceHessian, ParallelSegmentsStayFinite) {
  const V p(0.0, 0.0, 0.0), q(1.0, 0.0, 0.0);
  const V a(0.2, 0.3, 0.0), b(0.7, 0.3, 0.0);
  Matrix6d h;
  ASSERT_TRUE(SegmentSegmentDistanceHessian(a, b, p, q, &h));
  EXPECT_TRUE(h.allFinite());
  EXPECT_LE((h - h.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  // Zero-length edge against a point: the end point's Hessian.
  Matrix6d point;
  ASSERT_TRUE(SegmentPointDistanceHessian(V(0.0, 1.0, 0.0), a, a, &point));
  EXPECT_TRUE(point.allFinite());
  Eigen::Matrix3d end;
  ASSERT_TRUE(PointPointDistanceHessian(a, V(0.0, 1.0, 0.0), &end));
  EXPECT_LE((point.topLeftCorner<3, 3>() - end).cwiseAbs().maxCoeff(), 1e-15);
  // No direction at zero distance.
  EXPECT_FALSE(PointPointDistanceHessian(a, a, &end));
}

// ---------------------------------------------------------------- 2D point-edge

TEST(DistanceHessian, PointEdge2dEndsAndInterior) {
  Random random(9);
  for (int region = 0; region < 3; ++region) {
    for (int trial = 0; trial < kTrials; ++trial) {
      const V p(random.Uniform(-1.0, 1.0), random.Uniform(-1.0, 1.0), 0.0);
      V a, b;
      SegmentNearPoint(p, 2, region, 0.2, 0.8, &random, &a, &b);
      const Eigen::Vector2d p2 = p.head<2>(), a2 = a.head<2>(), b2 = b.head<2>();
      const double alpha = PointEdgeDistance(p2, a2, b2).alpha;
      ASSERT_EQ(region == 1, alpha > 0.1 && alpha < 0.9) << alpha;
      Matrix6d h;
      ASSERT_TRUE(PointEdgeDistanceHessian(p2, a2, b2, &h));
      const Gradient gradient = [](const Eigen::VectorXd& y) {
        const PointEdgeDistanceResult r =
            PointEdgeDistance(y.segment<2>(0), y.segment<2>(2), y.segment<2>(4));
        Eigen::VectorXd g(6);
        g << r.grad_p, r.grad_a, r.grad_b;
        return g;
      };
      ExpectHessian(h, gradient, Stack({p, a, b}, 2), false, "region " + std::to_string(region));
    }
  }
}

// ---------------------------------------------------------------- gap terms

// The term's Newton model with its analytic curvature against the same term
// with curvature empty (central differences of its Jacobian), at a gap far
// above the difference step; and the curvature part is a sizeable share of the
// model (against the Gauss-Newton model).
void ExpectTermCurvature(std::unique_ptr<ceres::CostFunction> cost,
                         const ResidualCurvature& curvature, std::vector<V> points, int dimension,
                         const std::string& what) {
  static const double kappa = 1.0;
  const int blocks = static_cast<int>(points.size());
  std::vector<double> storage(blocks * dimension);
  std::vector<const double*> x(blocks);
  for (int b = 0; b < blocks; ++b) {
    for (int k = 0; k < dimension; ++k) storage[b * dimension + k] = points[b][k];
  }
  for (int b = 0; b < blocks; ++b) x[b] = storage.data() + b * dimension;
  Term term;
  term.nodes.resize(blocks);
  term.cost = std::move(cost);
  term.loss = std::make_unique<BarrierLoss>(1.0, 1.0, &kappa);
  TermModelEvaluator evaluator;
  TermModel differences, analytic, gauss_newton;
  ASSERT_TRUE(evaluator.Evaluate(term, dimension, 1.0, x.data(), true, &differences)) << what;
  term.curvature = curvature;
  ASSERT_TRUE(evaluator.Evaluate(term, dimension, 1.0, x.data(), true, &analytic)) << what;
  term.gauss_newton_model = true;
  ASSERT_TRUE(evaluator.Evaluate(term, dimension, 1.0, x.data(), true, &gauss_newton)) << what;
  EXPECT_FALSE(differences.curvature_dropped) << what;
  EXPECT_FALSE(analytic.curvature_dropped) << what;
  const double scale = analytic.hessian.cwiseAbs().maxCoeff();
  EXPECT_LE((analytic.hessian - differences.hessian).cwiseAbs().maxCoeff(),
            kRelativeTolerance * scale)
      << what << "\nanalytic\n"
      << analytic.hessian << "\ndifferences\n"
      << differences.hessian;
  EXPECT_GT((analytic.hessian - gauss_newton.hessian).cwiseAbs().maxCoeff(), 1e-3 * scale) << what;
}

// d_hat = 1 in every term below, gaps in [0.2, 0.6]: well inside the barrier's
// reach, where its curvature part is a sizeable share of the model.
constexpr double kDHat = 1.0;
constexpr double kMinDistance = 1e-9;

TEST(GapCurvature, PointObstacleGapMatchesDifferences) {
  Random random(10);
  std::vector<Scenario> all = Scenarios(Shape::kSphere, {2, 3});
  for (const Scenario& s : Scenarios(Shape::kBox, {2, 3})) all.push_back(s);
  for (const Scenario& s : all) {
    const int dim = s.obstacle->dimension();
    for (int trial = 0; trial < 5; ++trial) {
      V x;
      if (s.shape == Shape::kSphere) {
        x = s.point + s.obstacle->velocity() * s.t +
            random.Uniform(0.7, 1.2) * random.Direction(dim);
      } else {
        // Corner regions (2D and 3D) and a 3D edge region.
        const bool outside[3] = {true, true, trial % 2 == 0};
        x = PointNearBox(s, outside, 0.1, &random);
      }
      auto gap =
          std::make_unique<PointObstacleGap>(dim, s.obstacle.get(), &s.t, kDHat, kMinDistance);
      const ResidualCurvature curvature = GapCurvature(gap.get());
      ExpectTermCurvature(std::move(gap), curvature, {x}, dim, s.name);
    }
  }
}

TEST(GapCurvature, EdgeObstacleGapMatchesDifferences) {
  Random random(11);
  for (const Scenario& s : EdgeScenarios()) {
    const Obstacle& o = *s.obstacle;
    const int dim = o.dimension();
    for (int feature = 0; feature < o.NumEdgeFeatures(); ++feature) {
      for (bool lagged : {false, true}) {
        for (int region = 0; region < 3; ++region) {
          V a, b;
          SegmentNearPoint(o.EdgeFeature(feature, s.t), dim, region, o.FeatureRadius() + 0.2, 0.4,
                           &random, &a, &b);
          // The lagged point is the true closest point's parameter, moved a little.
          double alpha = ClosestSegmentParameter(o.EdgeFeature(feature, s.t), a, b);
          alpha = std::clamp(alpha + 0.05, 0.0, 1.0);
          auto gap = std::make_unique<EdgeObstacleGap>(dim, &o, feature, &s.t, kDHat, kMinDistance,
                                                       lagged ? &alpha : nullptr);
          const ResidualCurvature curvature = GapCurvature(gap.get());
          ExpectTermCurvature(
              std::move(gap), curvature, {a, b}, dim,
              s.name + (lagged ? " lagged" : "") + " region " + std::to_string(region));
        }
      }
    }
  }
}

TEST(GapCurvature, FaceObstacleGapMatchesDifferences) {
  Random random(12);
  for (const Scenario& s : FaceScenarios()) {
    const Obstacle& o = *s.obstacle;
    for (int feature = 0; feature < o.NumFaceFeatures(); ++feature) {
      for (bool lagged : {false, true}) {
        for (int region = 0; region < 7; ++region) {
          V x[3];
          TriangleNearPoint(o.FaceFeature(feature, s.t), region, o.FeatureRadius() + 0.2, 0.4,
                            &random, x);
          // Lagged weights: the closest point's, moved a little towards the centroid.
          const Eigen::Vector3d weights =
              0.9 * PointTriangleDistance(o.FaceFeature(feature, s.t), x[0], x[1], x[2]).weights +
              Eigen::Vector3d::Constant(0.1 / 3.0);
          auto gap = std::make_unique<FaceObstacleGap>(&o, feature, &s.t, kDHat, kMinDistance,
                                                       lagged ? &weights : nullptr);
          const ResidualCurvature curvature = GapCurvature(gap.get());
          ExpectTermCurvature(
              std::move(gap), curvature, {x[0], x[1], x[2]}, 3,
              s.name + (lagged ? " lagged" : "") + " region " + std::to_string(region));
        }
      }
    }
  }
}

TEST(GapCurvature, EdgeBoxEdgeGapMatchesDifferences) {
  Random random(13);
  for (const Scenario& s : Scenarios(Shape::kBox, {3})) {
    for (int edge = 0; edge < s.obstacle->NumBoxEdges(); edge += 5) {
      V p, q;
      s.obstacle->BoxEdge(edge, s.t, &p, &q);
      for (int region = 0; region < 4; ++region) {
        V a, b;
        SegmentNearSegment(p, q, region & 1, region & 2, 0.4, &random, &a, &b);
        auto gap =
            std::make_unique<EdgeBoxEdgeGap>(s.obstacle.get(), edge, &s.t, kDHat, kMinDistance);
        const ResidualCurvature curvature = GapCurvature(gap.get());
        ExpectTermCurvature(std::move(gap), curvature, {a, b}, 3,
                            s.name + " region " + std::to_string(region));
      }
    }
  }
}

TEST(GapCurvature, PointEdgeGapMatchesDifferences) {
  Random random(14);
  for (int region = 0; region < 3; ++region) {
    for (int trial = 0; trial < 5; ++trial) {
      const V p(random.Uniform(-1.0, 1.0), random.Uniform(-1.0, 1.0), 0.0);
      V a, b;
      SegmentNearPoint(p, 2, region, 0.2, 0.4, &random, &a, &b);
      auto gap = std::make_unique<PointEdgeGap>(kDHat, kMinDistance);
      const ResidualCurvature curvature = GapCurvature(gap.get());
      ExpectTermCurvature(std::move(gap), curvature, {p, a, b}, 2,
                          "region " + std::to_string(region));
    }
  }
}

// At a gap of 1e-8 (d_hat 1e-3), finite differences with their 1e-6 step
// leave the domain and drop the curvature; the analytic one is the closed form
// of a sphere, Hess d = (I - n n^T) / (R + d), times -w rho' u (to round-off
// of the gap, 1e-8 relative, and of the Gauss-Newton part it is taken from).
TEST(GapCurvature, TinyGapKeepsTheCurvature) {
  const Scenario s = MakeScenario(Shape::kSphere, 3, true);
  const double d_hat = 1e-3, gap = 1e-8, kappa = 1e4, weight = 2.0;
  const V n = V(1.0, -2.0, 0.5).normalized();
  const V x = s.point + s.obstacle->velocity() * s.t + (s.radius + gap) * n;
  const double* parameters[1] = {x.data()};
  Term term;
  term.nodes = {0};
  auto cost = std::make_unique<PointObstacleGap>(3, s.obstacle.get(), &s.t, d_hat, 0.0);
  const ResidualCurvature curvature = GapCurvature(cost.get());
  term.cost = std::move(cost);
  term.loss = std::make_unique<BarrierLoss>(d_hat, 1.0, &kappa);
  TermModelEvaluator evaluator;
  TermModel differences, analytic, gauss_newton;
  ASSERT_TRUE(evaluator.Evaluate(term, 3, weight, parameters, true, &differences));
  EXPECT_TRUE(differences.curvature_dropped);
  term.curvature = curvature;
  ASSERT_TRUE(evaluator.Evaluate(term, 3, weight, parameters, true, &analytic));
  EXPECT_FALSE(analytic.curvature_dropped);
  term.gauss_newton_model = true;
  ASSERT_TRUE(evaluator.Evaluate(term, 3, weight, parameters, true, &gauss_newton));
  const double u = d_hat - gap;
  double rho[3];
  BarrierLoss(d_hat, 1.0, &kappa).Evaluate(u * u, rho);
  const Eigen::Matrix3d expected =
      -weight * rho[1] * u * (Eigen::Matrix3d::Identity() - n * n.transpose()) / (s.radius + gap);
  const Eigen::MatrixXd part = analytic.hessian - gauss_newton.hessian;
  EXPECT_LE((part - expected).cwiseAbs().maxCoeff(), 1e-6 * expected.cwiseAbs().maxCoeff())
      << part << "\n"
      << expected;
  EXPECT_GT(expected.cwiseAbs().maxCoeff(), 0.0);
}

// Out of reach (d >= d_hat) the curvature is zero; inside the obstacle the
// callback fails as the cost function does.
TEST(GapCurvature, InactiveIsZeroAndInfeasibleFails) {
  const Scenario s = MakeScenario(Shape::kSphere, 3, true);
  const PointObstacleGap gap(3, s.obstacle.get(), &s.t, kDHat, kMinDistance);
  const V centre = s.point + s.obstacle->velocity() * s.t;
  const double c = 0.7;
  double curvature[9];
  const V far = centre + V(2.0, 0.0, 0.0);
  const double* x[1] = {far.data()};
  ASSERT_TRUE(gap.Curvature(x, &c, curvature));
  for (double v : curvature) EXPECT_EQ(v, 0.0);
  const V inside = centre + V(0.1, 0.0, 0.0);
  x[0] = inside.data();
  EXPECT_FALSE(gap.Curvature(x, &c, curvature));
}

// Every gap term the contact state builds carries its second-order model:
// analytic curvature, or Gauss-Newton for plane gaps (affine distance).
TEST(GapCurvature, ContactFilterTermsCarryCurvature) {
  // Term types: 0 plane point, 1 other point, 2 edge, 3 face, 4 box edge,
  // 5 2D point-edge; the scenes and the types each one builds.
  const std::pair<const char*, std::vector<int>> scenes[] = {
      {"drop", {0}}, {"cloth_box", {1, 3, 4}}, {"cloth_sphere", {2, 3}}, {"two_squares", {0, 5}}};
  for (const auto& [scene, expected] : scenes) {
    SimulationOptions options;
    options.integrator.name = "backward_euler";
    options.optimizer.optimizer = Optimizer::kNewton;
    SceneLoadOptions load;
    load.extra_effects = DefaultEffects().UserNames();  // contact, friction
    Simulation sim(LoadScene(scene, load), options);
    int counts[6] = {0, 0, 0, 0, 0, 0};
    auto all_seen = [&] {
      return std::all_of(expected.begin(), expected.end(), [&](int k) { return counts[k] > 0; });
    };
    for (int step = 0; step < sim.steps() && !all_seen(); ++step) {
      sim.Step();
      for (const Term& term : sim.potential().terms()) {
        if (term.family != ContactFilter::kContactFamily) continue;
        const ceres::CostFunction* cost = term.cost.get();
        if (dynamic_cast<const PointObstacleGap*>(cost) != nullptr) {
          // Plane gaps (the only affine distance) are Gauss-Newton models.
          const bool plane = term.gauss_newton_model;
          ++counts[plane ? 0 : 1];
          EXPECT_NE(plane, static_cast<bool>(term.curvature)) << scene;
          continue;
        }
        EXPECT_FALSE(term.gauss_newton_model) << scene;
        EXPECT_TRUE(static_cast<bool>(term.curvature)) << scene;
        if (dynamic_cast<const EdgeObstacleGap*>(cost) != nullptr) ++counts[2];
        if (dynamic_cast<const FaceObstacleGap*>(cost) != nullptr) ++counts[3];
        if (dynamic_cast<const EdgeBoxEdgeGap*>(cost) != nullptr) ++counts[4];
        if (dynamic_cast<const PointEdgeGap*>(cost) != nullptr) ++counts[5];
      }
    }
    EXPECT_TRUE(all_seen()) << scene << ": " << counts[0] << " " << counts[1] << " " << counts[2]
                            << " " << counts[3] << " " << counts[4] << " " << counts[5];
  }
}

}  // namespace
}  // namespace ipstep
