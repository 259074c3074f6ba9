// 3D self-contact geometry (contact/distance_hessian.h all-moving cases,
// geometry/edge_edge_mollifier.h, contact/self_gap_terms.h, geometry/self_ccd.h,
// geometry/triangle_intersection.h, geometry/bvh.h) against exact references:
// central differences of analytic gradients region by region, the barrier
// formula through ceres::Problem::Evaluate, known impact times, brute force.
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <ceres/problem.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "contact/barrier.h"
#include "contact/distance_hessian.h"
#include "contact/self_gap_terms.h"
#include "core/term_hessian.h"
#include "geometry/bvh.h"
#include "geometry/edge_edge_mollifier.h"
#include "geometry/exact_orientation.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"
#include "geometry/self_ccd.h"
#include "geometry/spatial_hash.h"
#include "geometry/triangle_intersection.h"

namespace ipstep {
namespace {

using V = Eigen::Vector3d;
using Vec = Eigen::VectorXd;
using Gradient = std::function<Vec(const Vec&)>;

V P(const Vec& x, int k) { return x.segment<3>(3 * k); }

Vec Stack(const V& a, const V& b, const V& c, const V& d) {
  Vec x(12);
  x << a, b, c, d;
  return x;
}

Eigen::MatrixXd DifferenceJacobian(const Gradient& g, Vec x, double h) {
  const int n = static_cast<int>(x.size());
  Eigen::MatrixXd out(g(x).size(), n);
  for (int j = 0; j < n; ++j) {
    const double saved = x[j];
    x[j] = saved + h;
    const Vec up = g(x);
    x[j] = saved - h;
    const Vec down = g(x);
    x[j] = saved;
    out.col(j) = (up - down) / (2.0 * h);
  }
  return out;
}

void ExpectClose(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& reference,
                 double tolerance, const std::string& what) {
  const double scale = std::max(analytic.cwiseAbs().maxCoeff(), 1e-300);
  EXPECT_LE((analytic - reference).cwiseAbs().maxCoeff(), tolerance * scale)
      << what << "\nanalytic\n"
      << analytic << "\nreference\n"
      << reference;
}

Vec PointTriangleGradient(const Vec& x) {
  const PointTriangleDistanceResult r = PointTriangleDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3));
  return Stack(r.grad_p, r.grad_a, r.grad_b, r.grad_c);
}

Vec EdgeEdgeGradient(const Vec& x) {
  const SegmentSegmentDistanceResult r = SegmentSegmentDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3));
  return Stack(r.grad_a0, r.grad_a1, r.grad_b0, r.grad_b1);
}

// Number of positive closest-point weights (region: 3 face, 2 edge, 1 vertex).
int PointTriangleRegion(const Vec& x) {
  const V w = PointTriangleDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3)).weights;
  return (w.array() > 0.0).count();
}

void CheckPointTriangle(const Vec& x, int region, double step, double tolerance,
                        const std::string& what) {
  ASSERT_EQ(PointTriangleRegion(x), region) << what;
  Matrix12d h;
  ASSERT_TRUE(PointTriangleDistanceHessian(P(x, 0), P(x, 1), P(x, 2), P(x, 3), &h));
  ExpectClose(h, DifferenceJacobian(PointTriangleGradient, x, step), tolerance, what);
  EXPECT_LE((h - h.transpose()).cwiseAbs().maxCoeff(), 1e-10 * h.cwiseAbs().maxCoeff()) << what;
}

TEST(SelfDistanceHessian, PointTriangleEveryRegion) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const V a(0.0, 0.0, 0.0), b(1.0, 0.0, 0.0), c(0.0, 1.0, 0.0);
  struct Case {
    V p;
    int region;
    const char* name;
  };
  const Case cases[] = {
      {{0.25, 0.3, 0.4}, 3, "face interior"}, {{0.5, -0.4, 0.3}, 2, "edge ab"},
      {{0.7, 0.7, -0.3}, 2, "edge bc"},       {{-0.4, 0.5, 0.2}, 2, "edge ca"},
      {{-0.4, -0.3, 0.3}, 1, "vertex a"},     {{1.5, -0.2, 0.1}, 1, "vertex b"},
      {{-0.2, 1.5, -0.2}, 1, "vertex c"},     {{0.3, 0.3, -0.2}, 3, "face from below"},
  };
  for (const Case& k : cases) {
    for (int trial = 0; trial < 10; ++trial) {
      V j[4];
      for (V& v : j) v = V(jitter(rng), jitter(rng), jitter(rng));
      CheckPointTriangle(Stack(k.p + j[0], a + j[1], b + j[2], c + j[3]), k.region, 1e-6, 1e-6,
                         k.name);
    }
  }
}

TEST(SelfDistanceHessian, PointTriangleNearDegenerate) {
  // A point very close to the face (d = 1e-4): the step 1e-7 stays within
  // the region and far enough above round-off.
  CheckPointTriangle(Stack(V(0.3, 0.2, 1e-4), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)), 3, 1e-7, 1e-5,
                     "close to the face");
  // A sliver triangle (height 1e-3) with the point above its interior.
  CheckPointTriangle(Stack(V(0.5, 2e-4, 0.2), V(0, 0, 0), V(1, 0, 0), V(0.5, 1e-3, 0)), 3, 1e-7,
                     1e-5, "sliver face");
  // Close to an edge, just outside.
  CheckPointTriangle(Stack(V(0.5, -1e-4, 1e-4), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)), 2, 1e-7, 1e-5,
                     "close to an edge");
}

int Free(double v) { return v > 0.0 && v < 1.0; }

void CheckEdgeEdge(const Vec& x, int free_parameters, double step, double tolerance,
                   const std::string& what) {
  const SegmentSegmentDistanceResult r = SegmentSegmentDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3));
  ASSERT_EQ(Free(r.s) + Free(r.t), free_parameters) << what;
  Matrix12d h;
  ASSERT_TRUE(EdgeEdgeDistanceHessian(P(x, 0), P(x, 1), P(x, 2), P(x, 3), &h));
  ExpectClose(h, DifferenceJacobian(EdgeEdgeGradient, x, step), tolerance, what);
}

TEST(SelfDistanceHessian, EdgeEdgeInteriorAndEnds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  struct Case {
    V a0, a1, b0, b1;
    int free;
    const char* name;
  };
  const Case cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {0.5, -0.5, 0.3}, {0.5, 0.5, 0.3}, 2, "crossing interiors"},
      {{0, 0, 0}, {1, 0, 0}, {1.3, -0.5, 0.3}, {1.3, 0.5, 0.3}, 1, "end of a vs interior of b"},
      {{0, 0, 0}, {1, 0, 0}, {0.5, 0.3, 0.2}, {0.5, 1.3, 0.4}, 1, "interior of a vs end of b"},
      {{0, 0, 0}, {1, 0, 0}, {1.4, 0.3, 0.2}, {1.6, 1.3, 0.4}, 0, "end vs end"},
  };
  for (const Case& k : cases) {
    for (int trial = 0; trial < 10; ++trial) {
      V j[4];
      for (V& v : j) v = V(jitter(rng), jitter(rng), jitter(rng));
      CheckEdgeEdge(Stack(k.a0 + j[0], k.a1 + j[1], k.b0 + j[2], k.b1 + j[3]), k.free, 1e-6, 1e-6,
                    k.name);
    }
  }
}

TEST(SelfDistanceHessian, EdgeEdgeNearDegenerate) {
  // Nearly parallel crossing edges (1e-2 rad).
  const double theta = 1e-2, h = 0.05;
  const V dir(std::cos(theta), std::sin(theta), 0.0);
  CheckEdgeEdge(Stack(V(0, 0, 0), V(1, 0, 0), V(0.5, 0, h) - 0.5 * dir, V(0.5, 0, h) + 0.5 * dir),
                2, 1e-7, 1e-5, "nearly parallel");
  // Very close crossing edges.
  CheckEdgeEdge(Stack(V(0, 0, 0), V(1, 0, 0), V(0.4, -0.5, 1e-4), V(0.6, 0.5, 1e-4)), 2, 1e-7, 1e-5,
                "close crossing");
}

// m(c) and its derivatives.
TEST(EdgeEdgeMollifier, DerivativesMatchDifferences) {
  const double eps_x = MollifierThreshold(1.0, 1.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  for (int trial = 0; trial < 20; ++trial) {
    const double theta = 0.005 + 0.02 * trial / 20.0;
    const V dir(std::cos(theta), std::sin(theta), 0.0);
    Vec x = Stack(V(0, 0, 0), V(1, 0, 0), V(0.5, 0, 0.02) - 0.5 * dir, V(0.5, 0, 0.02) + 0.5 * dir);
    for (int k = 0; k < 12; ++k) x[k] += jitter(rng);
    const EdgeEdgeMollifier m = EdgeEdgeMollify(P(x, 0), P(x, 1), P(x, 2), P(x, 3), eps_x);
    ASSERT_TRUE(m.active());
    EXPECT_GT(m.value, 0.0);
    auto value = [&](const Vec& y) {
      Vec v(1);
      v[0] = EdgeEdgeMollify(P(y, 0), P(y, 1), P(y, 2), P(y, 3), eps_x, false).value;
      return v;
    };
    auto gradient = [&](const Vec& y) -> Vec {
      return EdgeEdgeMollify(P(y, 0), P(y, 1), P(y, 2), P(y, 3), eps_x).gradient;
    };
    ExpectClose(m.gradient.transpose(), DifferenceJacobian(value, x, 1e-7), 1e-6, "gradient");
    ExpectClose(m.hessian, DifferenceJacobian(gradient, x, 1e-7), 1e-6, "hessian");
  }
  // Not parallel: m = 1, no derivatives.
  const EdgeEdgeMollifier far =
      EdgeEdgeMollify(V(0, 0, 0), V(1, 0, 0), V(0, 0, 1), V(0, 1, 1), eps_x);
  EXPECT_EQ(far.value, 1.0);
  EXPECT_EQ(far.gradient.norm(), 0.0);
  // Exactly parallel: m = 0.
  EXPECT_EQ(EdgeEdgeMollify(V(0, 0, 0), V(1, 0, 0), V(0, 0, 1), V(1, 0, 1), eps_x).value, 0.0);
}

TEST(EdgeEdgeGap, InverseBarrierGapSolvesTheBarrier) {
  const double d_hat = 0.1;
  for (double d : {1e-4, 1e-3, 0.01, 0.05, 0.099}) {
    for (double m : {1e-12, 1e-6, 0.01, 0.5, 0.99, 1.0}) {
      const double beta = m * Barrier(d, d_hat);
      const double u = InverseBarrierGap(beta, d_hat, d_hat - d);
      EXPECT_LE(u, d_hat - d + 1e-18);
      EXPECT_NEAR(Barrier(d_hat - u, d_hat), beta, 1e-12 * Barrier(d, d_hat)) << d << " " << m;
    }
  }
}

// The mollified barrier kappa w m B(d) of a pair, its gradient (analytic:
// B grad m + m B' grad d) and Hessian by differences of that gradient.
struct Mollified {
  double kappa = 10.0, weight = 0.3, d_hat = 0.05, eps_x = MollifierThreshold(1.0, 1.0);
  double Energy(const Vec& x) const {
    const double d = SegmentSegmentDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3)).distance;
    const double m = EdgeEdgeMollify(P(x, 0), P(x, 1), P(x, 2), P(x, 3), eps_x, false).value;
    return kappa * weight * m * Barrier(d, d_hat);
  }
  Vec Gradient(const Vec& x) const {
    const SegmentSegmentDistanceResult r =
        SegmentSegmentDistance(P(x, 0), P(x, 1), P(x, 2), P(x, 3));
    const EdgeEdgeMollifier m =
        EdgeEdgeMollify(P(x, 0), P(x, 1), P(x, 2), P(x, 3), eps_x, true, false);
    const Vec grad_d = Stack(r.grad_a0, r.grad_a1, r.grad_b0, r.grad_b1);
    return kappa * weight *
           (Barrier(r.distance, d_hat) * Vec(m.gradient) +
            m.value * BarrierDerivative(r.distance, d_hat) * grad_d);
  }
};

// Ceres sees cost 1/2 rho(u^2) = kappa w m B and its gradient; the Newton
// model's Hessian (Gauss-Newton + analytic curvature) is that of kappa w m B.
TEST(EdgeEdgeGap, CeresValueGradientAndNewtonModelAreTheMollifiedBarrier) {
  const Mollified ref;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  int mollified = 0;
  for (int trial = 0; trial < 24; ++trial) {
    // Angles from nearly parallel (mollified) to well apart (m = 1).
    const double theta = 0.003 + 0.004 * trial;
    const V dir(std::cos(theta), std::sin(theta), 0.0);
    Vec x = Stack(V(0, 0, 0), V(1, 0, 0), V(0.5, 0, 0.02) - 0.5 * dir, V(0.5, 0, 0.02) + 0.5 * dir);
    for (int k = 0; k < 12; ++k) x[k] += jitter(rng);
    mollified += EdgeEdgeMollify(P(x, 0), P(x, 1), P(x, 2), P(x, 3), ref.eps_x, false).active();

    EdgeEdgeGap gap(ref.d_hat, 0.0, ref.eps_x);
    BarrierLoss loss(ref.d_hat, ref.weight, &ref.kappa);
    std::vector<double> blocks(x.data(), x.data() + 12);
    ceres::Problem::Options options;
    options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(options);
    problem.AddResidualBlock(&gap, &loss, &blocks[0], &blocks[3], &blocks[6], &blocks[9]);
    double cost = 0.0;
    std::vector<double> gradient;
    ASSERT_TRUE(
        problem.Evaluate(ceres::Problem::EvaluateOptions(), &cost, nullptr, &gradient, nullptr));
    // Parameter blocks in order of addition.
    const double energy = ref.Energy(x);
    EXPECT_NEAR(cost, energy, 1e-11 * energy) << trial;
    const Vec expected = ref.Gradient(x);
    ExpectClose(Eigen::Map<Vec>(gradient.data(), 12), expected, 1e-9, "ceres gradient");
    auto fd_value = [&](const Vec& y) {
      Vec v(1);
      v[0] = ref.Energy(y);
      return v;
    };
    ExpectClose(expected.transpose(), DifferenceJacobian(fd_value, x, 1e-7), 1e-6,
                "gradient vs differences");

    // Newton model of the term: exact Hessian of kappa w m B.
    Term term;
    term.nodes = {0, 1, 2, 3};
    auto cost_function = std::make_unique<EdgeEdgeGap>(ref.d_hat, 0.0, ref.eps_x);
    const EdgeEdgeGap* g = cost_function.get();
    term.curvature = [g](const double* const* y, const double* c, double* out) {
      return g->Curvature(y, c, out);
    };
    term.cost = std::move(cost_function);
    term.loss = std::make_unique<BarrierLoss>(ref.d_hat, ref.weight, &ref.kappa);
    TermModelEvaluator evaluator;
    TermModel model;
    const double* parameters[4] = {&blocks[0], &blocks[3], &blocks[6], &blocks[9]};
    ASSERT_TRUE(evaluator.Evaluate(term, 3, 1.0, parameters, true, &model));
    EXPECT_NEAR(model.energy, energy, 1e-11 * energy);
    ExpectClose(Vec(model.gradient), expected, 1e-9, "model gradient");
    ExpectClose(Eigen::MatrixXd(model.hessian),
                DifferenceJacobian([&](const Vec& y) { return ref.Gradient(y); }, x, 1e-8), 1e-5,
                "model hessian");
  }
  EXPECT_GT(mollified, 5);
  EXPECT_LT(mollified, 24);
}

TEST(PointTriangleGap, CeresValueAndNewtonModelAreTheBarrier) {
  const double kappa = 3.0, weight = 0.2, d_hat = 0.1;
  const Vec x = Stack(V(0.3, 0.2, 0.04), V(0, 0, 0), V(1, 0, 0.01), V(0, 1, -0.01));
  auto energy = [&](const Vec& y) {
    return kappa * weight *
           Barrier(PointTriangleDistance(P(y, 0), P(y, 1), P(y, 2), P(y, 3)).distance, d_hat);
  };
  auto gradient = [&](const Vec& y) -> Vec {
    const double d = PointTriangleDistance(P(y, 0), P(y, 1), P(y, 2), P(y, 3)).distance;
    return kappa * weight * BarrierDerivative(d, d_hat) * PointTriangleGradient(y);
  };
  Term term;
  term.nodes = {0, 1, 2, 3};
  auto cost = std::make_unique<PointTriangleGap>(d_hat, 0.0);
  const PointTriangleGap* g = cost.get();
  term.curvature = [g](const double* const* y, const double* c, double* out) {
    return g->Curvature(y, c, out);
  };
  term.cost = std::move(cost);
  term.loss = std::make_unique<BarrierLoss>(d_hat, weight, &kappa);
  TermModelEvaluator evaluator;
  TermModel model;
  const double* parameters[4] = {x.data(), x.data() + 3, x.data() + 6, x.data() + 9};
  ASSERT_TRUE(evaluator.Evaluate(term, 3, 1.0, parameters, true, &model));
  EXPECT_NEAR(model.energy, energy(x), 1e-12 * energy(x));
  ExpectClose(Vec(model.gradient), gradient(x), 1e-10, "gradient");
  ExpectClose(Eigen::MatrixXd(model.hessian), DifferenceJacobian(gradient, x, 1e-7), 1e-6,
              "hessian");
  // At or below the margin the term fails.
  PointTriangleGap strict(d_hat, 0.05);
  double r;
  EXPECT_FALSE(strict.Evaluate(parameters, &r, nullptr));
}

// Continuous collision detection.
double PtDistance(const V* x0, const V* x1, double s) {
  auto at = [&](int k) { return V(x0[k] + s * (x1[k] - x0[k])); };
  return PointTriangleDistance(at(0), at(1), at(2), at(3)).distance;
}

double EeDistance(const V* x0, const V* x1, double s) {
  auto at = [&](int k) { return V(x0[k] + s * (x1[k] - x0[k])); };
  return SegmentSegmentDistance(at(0), at(1), at(2), at(3)).distance;
}

// Returned s: every sampled fraction up to s keeps the gap above the goal;
// s no later than `impact` (the first time the gap reaches the margin) and
// no earlier than `earliest`.
void CheckToi(double s, double impact, double earliest, double margin,
              const std::function<double(double)>& distance, const std::string& what) {
  EXPECT_LE(s, impact) << what;
  EXPECT_GE(s, earliest) << what;
  for (int k = 0; k <= 1000; ++k) {
    const double f = s * k / 1000.0;
    EXPECT_GT(distance(f), margin) << what << " at " << f;
  }
}

TEST(SelfCcd, PointThroughTriangle) {
  const V x0[4] = {V(0.2, 0.2, 1.0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  const V x1[4] = {V(0.2, 0.2, -1.0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  for (double margin : {0.0, 1e-3}) {
    const double s =
        PointTriangleTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], margin);
    // The gap closes linearly: impact at (1 - margin) / 2, goal reached at
    // (1 - goal) / 2 with goal = margin + 0.1 (1 - margin).
    const double goal = margin + kGapFraction * (1.0 - margin);
    CheckToi(
        s, 0.5 * (1.0 - margin), 0.5 * (1.0 - goal) - 1e-3, margin,
        [&](double f) { return PtDistance(x0, x1, f); }, "point through triangle");
  }
  // The triangle moving onto a fixed point, and both moving.
  const V y0[4] = {V(0.2, 0.2, 0.0), V(0, 0, 1), V(1, 0, 1), V(0, 1, 1)};
  const V y1[4] = {V(0.2, 0.2, 1.0), V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  const double s =
      PointTriangleTimeOfImpact(y0[0], y0[1], y0[2], y0[3], y1[0], y1[1], y1[2], y1[3], 0.0);
  CheckToi(
      s, 0.5, 0.45 * 0.99, 0.0, [&](double f) { return PtDistance(y0, y1, f); }, "both");
}

TEST(SelfCcd, FastPointAndNearlyTouching) {
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const double fast =
      PointTriangleTimeOfImpact(V(0.3, 0.3, 100), a, b, c, V(0.3, 0.3, -100), a, b, c, 0.0);
  EXPECT_LE(fast, 0.5);
  EXPECT_GE(fast, 0.5 * 0.9 - 1e-6);
  const double close =
      PointTriangleTimeOfImpact(V(0.3, 0.3, 1e-8), a, b, c, V(0.3, 0.3, -1.0), a, b, c, 0.0);
  EXPECT_GT(close, 0.0);
  EXPECT_LE(close, 1e-8);
  EXPECT_GE(close, 0.8e-8);
  // Starting within the margin: 0; passing beside the triangle: no impact.
  EXPECT_EQ(PointTriangleTimeOfImpact(V(0.3, 0.3, 1e-4), a, b, c, V(0.3, 0.3, 1), a, b, c, 1e-3),
            0.0);
  EXPECT_EQ(PointTriangleTimeOfImpact(V(2, 2, 1), a, b, c, V(2, 2, -1), a, b, c, 0.0),
            kSelfNoImpact);
  // Sliding along the face at a constant height.
  EXPECT_EQ(PointTriangleTimeOfImpact(V(0.1, 0.1, 0.01), a, b, c, V(0.5, 0.3, 0.01), a, b, c, 0.0),
            kSelfNoImpact);
}

TEST(SelfCcd, EdgeEdgeCrossingParallelAndSliding) {
  {  // Crossing edges.
    const V x0[4] = {V(0, 0, 0), V(1, 0, 0), V(0.5, -0.5, 1), V(0.5, 0.5, 1)};
    const V x1[4] = {V(0, 0, 0), V(1, 0, 0), V(0.5, -0.5, -1), V(0.5, 0.5, -1)};
    const double s =
        EdgeEdgeTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], 0.0);
    CheckToi(
        s, 0.5, 0.45 * 0.99, 0.0, [&](double f) { return EeDistance(x0, x1, f); }, "crossing");
  }
  {  // Parallel edges approaching each other.
    const V x0[4] = {V(0, 0, 0), V(1, 0, 0), V(0.2, 0, 1), V(1.2, 0, 1)};
    const V x1[4] = {V(0, 0, 0), V(1, 0, 0), V(0.2, 0, -1), V(1.2, 0, -1)};
    const double s =
        EdgeEdgeTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], 1e-3);
    CheckToi(
        s, 0.5 * (1 - 1e-3), 0.44, 1e-3, [&](double f) { return EeDistance(x0, x1, f); },
        "parallel");
  }
  {  // Parallel edges sliding past each other at a constant gap.
    const V x0[4] = {V(0, 0, 0), V(1, 0, 0), V(0.2, 0, 0.01), V(1.2, 0, 0.01)};
    const V x1[4] = {V(0, 0, 0), V(1, 0, 0), V(2.2, 0, 0.01), V(3.2, 0, 0.01)};
    EXPECT_EQ(EdgeEdgeTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], 0.0),
              kSelfNoImpact);
  }
  {  // Tilted edge sweeping across another: its middle, at height
     // 0.6 - 1.2 s, meets the fixed edge at s = 0.5.
    const V x0[4] = {V(0, 0, 0), V(1, 0, 0), V(0.5, -0.5, 1.0), V(0.5, 0.5, 0.2)};
    const V x1[4] = {V(0, 0, 0), V(1, 0, 0), V(0.5, -0.5, -0.2), V(0.5, 0.5, -1.0)};
    const double s =
        EdgeEdgeTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2], x1[3], 0.0);
    CheckToi(
        s, 0.5, 0.3, 0.0, [&](double f) { return EeDistance(x0, x1, f); }, "rotating");
  }
}

// Random motions: never late against a dense sampling of the distance.
TEST(SelfCcd, RandomMotionsAreNeverLate) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&]() { return V(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 200; ++trial) {
    V x0[4], x1[4];
    for (int k = 0; k < 4; ++k) {
      x0[k] = random();
      x1[k] = x0[k] + 1.5 * random();
    }
    const bool point = trial % 2 == 0;
    auto distance = [&](double f) { return point ? PtDistance(x0, x1, f) : EeDistance(x0, x1, f); };
    const double margin = 1e-3;
    const double s = point ? PointTriangleTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1],
                                                       x1[2], x1[3], margin)
                           : EdgeEdgeTimeOfImpact(x0[0], x0[1], x0[2], x0[3], x1[0], x1[1], x1[2],
                                                  x1[3], margin);
    double first = kSelfNoImpact;
    for (int k = 0; k <= 4000; ++k) {
      if (distance(k / 4000.0) <= margin) {
        first = k / 4000.0;
        break;
      }
    }
    EXPECT_LE(s, first) << trial;
    const double end = std::min(s, 1.0);
    for (int k = 0; k <= 200; ++k) EXPECT_GT(distance(end * k / 200.0), margin) << trial;
  }
}

// Intersection predicates.
TEST(TriangleIntersection, KnownConfigurations) {
  const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_TRUE(SegmentTriangleIntersect(V(0.2, 0.2, 1), V(0.2, 0.2, -1), a, b, c));
  EXPECT_FALSE(SegmentTriangleIntersect(V(0.8, 0.8, 1), V(0.8, 0.8, -1), a, b, c));
  EXPECT_FALSE(SegmentTriangleIntersect(V(0.2, 0.2, 1), V(0.2, 0.2, 0.1), a, b, c));
  EXPECT_TRUE(SegmentTriangleIntersect(V(0.2, 0.2, 1), V(0.2, 0.2, 0.0), a, b, c));  // touches
  EXPECT_TRUE(SegmentTriangleIntersect(V(-1, 0.2, 0), V(2, 0.2, 0), a, b, c));       // coplanar
  EXPECT_FALSE(SegmentTriangleIntersect(V(-1, 2, 0), V(2, 2, 0), a, b, c));
  EXPECT_TRUE(SegmentTriangleIntersect(V(0.1, 0.1, 0), V(0.2, 0.1, 0), a, b, c));  // inside
  // Triangle piercing another through its interior (no vertex or edge-edge
  // contact: distances of vertices and edge pairs are all positive).
  EXPECT_TRUE(TrianglesIntersect(a, b, c, V(0.2, 0.2, -1), V(0.3, 0.2, 1), V(0.25, 0.5, 1)));
  EXPECT_FALSE(TrianglesIntersect(a, b, c, V(0.2, 0.2, 0.1), V(0.3, 0.2, 1), V(0.25, 0.5, 1)));
  // Coplanar: overlapping, nested, apart.
  EXPECT_TRUE(TrianglesIntersect(a, b, c, V(0.5, 0.5, 0), V(-0.5, 0.2, 0), V(0.2, -0.5, 0)));
  EXPECT_TRUE(TrianglesIntersect(a, b, c, V(0.1, 0.1, 0), V(0.2, 0.1, 0), V(0.1, 0.2, 0)));
  EXPECT_FALSE(TrianglesIntersect(a, b, c, V(2, 2, 0), V(3, 2, 0), V(2, 3, 0)));
  // Parallel planes.
  EXPECT_FALSE(TrianglesIntersect(a, b, c, V(0, 0, 1e-9), V(1, 0, 1e-9), V(0, 1, 1e-9)));
}

// Exact signs where the double evaluation cannot tell: points on the plane
// z = x + y (exactly representable sums) and the next double above.
TEST(ExactOrientation, CoplanarAndOneUlpOff) {
  std::mt19937 rng(31);
  std::uniform_int_distribution<int> k(-1000, 1000);
  auto on_plane = [&]() {
    const double x = k(rng) / 64.0, y = k(rng) / 64.0;
    return V(x, y, x + y);
  };
  for (int trial = 0; trial < 200; ++trial) {
    const V a = on_plane(), b = on_plane(), c = on_plane();
    V d = on_plane();
    if (ExactOrient2d(a, b, c, 0, 1) == 0) continue;  // collinear in the projection
    EXPECT_EQ(ExactOrient3d(a, b, c, d), 0);
    const int below = ExactOrient3d(a, b, c, V(d[0], d[1], std::nextafter(d[2], -1e9)));
    const int above = ExactOrient3d(a, b, c, V(d[0], d[1], std::nextafter(d[2], 1e9)));
    EXPECT_NE(below, 0);
    EXPECT_EQ(below, -above);
  }
  // Far from the origin, tiny offsets: the filter must defer to the exact sum.
  const V a(1e6 + 0.1, 1e6, 1e6), b(1e6 + 0.2, 1e6 + 0.1, 1e6), c(1e6 + 0.1, 1e6 + 0.3, 1e6);
  EXPECT_EQ(ExactOrient3d(a, b, c, V(1e6 + 0.15, 1e6 + 0.1, 1e6)), 0);
  EXPECT_NE(ExactOrient3d(a, b, c, V(1e6 + 0.15, 1e6 + 0.1, std::nextafter(1e6, 2e6))), 0);
}

// A slanted strip of a rounded grid: faces of different rows meet at most at
// one point each and do not intersect, although nearly coplanar.
TEST(TriangleIntersection, NearlyCoplanarStripHasNoFalseIntersections) {
  const double a = 1.2 / 15.0;
  auto p = [&](int i, int j) {
    const double x = i == 0 ? 7 * a - 0.45 : 7.5 * a - 0.45;
    return V(std::round(x * 1e12) / 1e12, i == 0 ? 0.3 : 0.34,
             std::round((j * a - 0.6) * 1e12) / 1e12);
  };
  // Face (0, j) (1, j) (1, j + 1) against face (0, k) (0, k + 1) (1, k + 1),
  // k > j: no common node, disjoint (the configuration that a long double
  // evaluation reported as intersecting).
  for (int j = 0; j + 1 < 16; ++j) {
    for (int k = j + 1; k + 1 < 16; ++k) {
      EXPECT_FALSE(
          TrianglesIntersect(p(0, j), p(1, j), p(1, j + 1), p(0, k), p(0, k + 1), p(1, k + 1)))
          << j << " " << k;
    }
  }
}

TEST(TriangleIntersection, AgreesWithTheSegmentTestOfPointTriangle) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&]() { return V(u(rng), u(rng), u(rng)); };
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const V p = random(), q = random(), a = random(), b = random(), c = random();
    const bool ours = SegmentTriangleIntersect(p, q, a, b, c);
    EXPECT_EQ(ours, SegmentIntersectsTriangle(p, q, a, b, c)) << trial;
    hits += ours;
  }
  EXPECT_GT(hits, 100);
}

TEST(Bvh, QueriesMatchBruteForceAndTheSpatialHash) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(0.0, 10.0), size(0.0, 0.5);
  std::vector<V> lower, upper;
  for (int i = 0; i < 500; ++i) {
    const V lo(u(rng), u(rng), u(rng));
    lower.push_back(lo);
    upper.push_back(lo + V(size(rng), size(rng), size(rng)));
  }
  Bvh bvh;
  bvh.Build(lower, upper);
  SpatialHash hash(3, 0.5);
  for (int i = 0; i < 500; ++i) hash.Insert(i, lower[i], upper[i]);
  std::vector<int> ids, hashed;
  for (int k = 0; k < 200; ++k) {
    const V lo(u(rng), u(rng), u(rng));
    const V hi = lo + V(size(rng), size(rng), size(rng)) * 3.0;
    bvh.Query(lo, hi, &ids);
    std::sort(ids.begin(), ids.end());
    std::vector<int> expected;
    for (int i = 0; i < 500; ++i) {
      if ((lower[i].array() <= hi.array()).all() && (lo.array() <= upper[i].array()).all()) {
        expected.push_back(i);
      }
    }
    EXPECT_EQ(ids, expected);
    hash.Query(lo, hi, &hashed);
    // The hash returns a superset (boxes sharing a cell).
    EXPECT_TRUE(std::includes(hashed.begin(), hashed.end(), expected.begin(), expected.end()));
  }
}

}  // namespace
}  // namespace ipstep
