// The 3D self-contact pair kinds (contact/pairs/point_triangle_pairs.h,
// edge_edge_pairs.h) standalone, on two small cloth patches: Extend finds
// exactly the combinations within reach (brute force), the barrier terms of
// an IncrementalPotential sum to the barrier formula with its gradient,
// TimeOfImpact stops a motion that passes through before any penetration
// (FindPenetration before / after), friction terms carry the lagged force.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/pairs/edge_edge_pairs.h"
#include "contact/pairs/point_triangle_pairs.h"
#include "core/incremental_potential.h"
#include "geometry/edge_edge_mollifier.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"
#include "tests/support/cloth_meshes.h"

namespace ipstep {
namespace {

using V = Eigen::Vector3d;
using testing::AddClothGrid;

V At(const std::vector<double>& x, int node) {
  return V(x[3 * node], x[3 * node + 1], x[3 * node + 2]);
}

// Sheet A: 3 x 3 nodes at z = 0 over [0, 1]^2; sheet B: 3 x 3 nodes at
// height h, shifted by `shift` in x and y and turned by `angle` about z.
struct TwoSheets {
  CollisionMesh mesh;
  std::vector<double> x;
  ObstacleList obstacles;
  std::vector<bool> free;
  double time = 0.0;
  double kappa = 5.0;
  IncrementalPotential potential{3, 18};
  PairSetContext context;

  TwoSheets(double h, double shift, double angle, double d_hat, double margin) {
    AddClothGrid(
        3, 3, 0.5, 0, [](int i, int j) { return V(0.5 * i, 0.5 * j, 0.0); }, &mesh, &x);
    AddClothGrid(
        3, 3, 0.5, 9,
        [&](int i, int j) {
          const double u = 0.5 * i - 0.5, v = 0.5 * j - 0.5;
          return V(0.5 + shift + std::cos(angle) * u - std::sin(angle) * v,
                   0.5 + shift + std::sin(angle) * u + std::cos(angle) * v, h);
        },
        &mesh, &x);
    free.assign(mesh.nodes.size(), true);
    context.dimension = 3;
    context.mesh = &mesh;
    context.obstacles = &obstacles;
    context.node_free = &free;
    context.d_hat = d_hat;
    context.margin = margin;
    context.time = &time;
    context.kappa = &kappa;
    context.step = &potential.context();
    potential.context().Resize(3, 18);
  }
  std::vector<double> Moved(double dz) const {
    std::vector<double> y = x;
    for (int node = 9; node < 18; ++node) y[3 * node + 2] += dz;
    return y;
  }
};

bool SharesNode(const std::array<int, 3>& f, int node) {
  return f[0] == node || f[1] == node || f[2] == node;
}

bool SharesNode(const std::array<int, 2>& e, const std::array<int, 2>& f) {
  return e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1];
}

double BruteForcePointTriangleEnergy(const TwoSheets& s, const std::vector<double>& x, int* count) {
  double energy = 0.0;
  *count = 0;
  for (size_t slot = 0; slot < s.mesh.nodes.size(); ++slot) {
    const int node = s.mesh.nodes[slot];
    for (const auto& f : s.mesh.faces) {
      if (SharesNode(f, node)) continue;
      const double d =
          PointTriangleDistance(At(x, node), At(x, f[0]), At(x, f[1]), At(x, f[2])).distance;
      if (d < s.context.d_hat) {
        energy += s.kappa * s.mesh.weights[slot] * Barrier(d, s.context.d_hat);
        ++*count;
      }
    }
  }
  return energy;
}

double BruteForceEdgeEdgeEnergy(const TwoSheets& s, const EdgeEdgePairs& pairs,
                                const std::vector<double>& x, int* count) {
  double energy = 0.0;
  *count = 0;
  for (size_t e = 0; e < s.mesh.edges.size(); ++e) {
    for (size_t f = e + 1; f < s.mesh.edges.size(); ++f) {
      const auto& u = s.mesh.edges[e];
      const auto& v = s.mesh.edges[f];
      if (SharesNode(u, v)) continue;
      const V a0 = At(x, u[0]), a1 = At(x, u[1]), b0 = At(x, v[0]), b1 = At(x, v[1]);
      const double d = SegmentSegmentDistance(a0, a1, b0, b1).distance;
      if (d < s.context.d_hat) {
        const EdgeEdgePairs::Pair pair{static_cast<int>(e), static_cast<int>(f)};
        const double m =
            EdgeEdgeMollify(a0, a1, b0, b1, pairs.MollifierThreshold(pair), false).value;
        energy += s.kappa * s.mesh.edge_weights[e] * m * Barrier(d, s.context.d_hat);
        ++*count;
      }
    }
  }
  return energy;
}

// Energy and gradient of the potential against the reference energy and
// central differences of the potential's energy.
void ExpectEnergyAndGradient(const IncrementalPotential& potential, std::vector<double> x,
                             double expected) {
  double energy = 0.0;
  std::vector<double> gradient(x.size());
  ASSERT_TRUE(potential.Evaluate(x.data(), &energy, gradient.data()));
  EXPECT_NEAR(energy, expected, 1e-10 * expected);
  const double h = 1e-7;
  double scale = 0.0;
  for (double g : gradient) scale = std::max(scale, std::abs(g));
  for (size_t k = 0; k < x.size(); ++k) {
    const double saved = x[k];
    double up = 0.0, down = 0.0;
    x[k] = saved + h;
    ASSERT_TRUE(potential.Evaluate(x.data(), &up, nullptr));
    x[k] = saved - h;
    ASSERT_TRUE(potential.Evaluate(x.data(), &down, nullptr));
    x[k] = saved;
    EXPECT_NEAR(gradient[k], (up - down) / (2 * h), 1e-6 * scale) << k;
  }
}

TEST(PointTrianglePairs, ExtendFindsTheClosePairsAndTermsAreTheBarrier) {
  TwoSheets s(0.05, 0.2, 0.0, 0.1, 0.0);
  PointTrianglePairs pairs(s.context);
  ASSERT_TRUE(pairs.active());
  CandidateRegion region;
  region.start = region.end = s.x.data();
  EXPECT_TRUE(pairs.Extend(region));
  int count = 0;
  const double expected = BruteForcePointTriangleEnergy(s, s.x, &count);
  ASSERT_GT(count, 0);
  // Every pair found is within d_hat (no reach) and every close one is found.
  EXPECT_EQ(pairs.size(), static_cast<size_t>(count));
  EXPECT_FALSE(pairs.Missing(s.x.data()));
  EXPECT_FALSE(pairs.Extend(region));  // nothing new
  pairs.AddBarrierTerms(&s.potential);
  EXPECT_EQ(s.potential.terms().size(), pairs.size());
  ExpectEnergyAndGradient(s.potential, s.x, expected);
  // Near and the barrier gradient agree with the terms.
  double min_distance = std::numeric_limits<double>::infinity();
  int near = 0;
  pairs.Near(s.x.data(), 0.0, s.context.d_hat, &min_distance, &near);
  EXPECT_EQ(near, count);
  EXPECT_NEAR(min_distance, 0.05, 1e-12);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(s.x.size());
  pairs.AddBarrierGradient(s.x.data(), 0.0, s.kappa, &g);
  std::vector<double> gradient(s.x.size());
  double energy;
  ASSERT_TRUE(s.potential.Evaluate(s.x.data(), &energy, gradient.data()));
  for (size_t k = 0; k < s.x.size(); ++k) EXPECT_NEAR(g[k], gradient[k], 1e-9 * g.norm());

  // Far apart: nothing; with a reach covering the gap: the pairs.
  TwoSheets far(0.5, 0.2, 0.0, 0.1, 0.0);
  PointTrianglePairs far_pairs(far.context);
  region.start = region.end = far.x.data();
  EXPECT_FALSE(far_pairs.Extend(region));
  EXPECT_EQ(far_pairs.size(), 0u);
  std::vector<double> reach(far.mesh.nodes.size(), 0.25);
  region.reach = &reach;
  region.max_reach = 0.25;
  EXPECT_TRUE(far_pairs.Extend(region));
  EXPECT_GT(far_pairs.size(), 0u);
  // Clear remembers the set.
  far_pairs.Clear();
  EXPECT_TRUE(far_pairs.ChangedSinceClear());
}

// The broad phase's last answer is reused only for the same query by value:
// a buffer changed in place is a new query (contact/pairs/candidate_cache.h).
TEST(PointTrianglePairs, RepeatedQueriesAnswerTheirOwnConfiguration) {
  TwoSheets s(0.3, 0.2, 0.0, 0.1, 1e-4);
  PointTrianglePairs pairs(s.context);
  std::vector<double> end = s.Moved(-0.6);
  const double t = pairs.TimeOfImpact(s.x.data(), end.data(), 0.0, 0.0);
  EXPECT_LT(t, 1.0);
  const double seconds = pairs.BroadPhaseSeconds();
  EXPECT_GT(seconds, 0.0);
  EXPECT_EQ(pairs.TimeOfImpact(s.x.data(), end.data(), 0.0, 0.0), t);
  EXPECT_EQ(pairs.BroadPhaseSeconds(), seconds);  // the repeat needed no broad phase
  end = s.Moved(0.5);                             // same buffer, moving away: no impact
  EXPECT_EQ(pairs.TimeOfImpact(s.x.data(), end.data(), 0.0, 0.0), PairSet::kNoImpact);
  EXPECT_GT(pairs.BroadPhaseSeconds(), seconds);
}

TEST(PointTrianglePairs, TimeOfImpactStopsAMotionThroughTheSheet) {
  TwoSheets s(0.3, 0.2, 0.0, 0.1, 1e-4);
  PointTrianglePairs pairs(s.context);
  const std::vector<double> end = s.Moved(-0.6);  // B ends 0.3 below A
  EXPECT_EQ(pairs.FindPenetration(s.x.data(), 0.0), "");
  EXPECT_NE(pairs.FindPenetration(s.Moved(-0.3).data(), 0.0), "");  // coplanar, overlapping
  // B's centre node pushed through A: B's faces cross A's (the exact
  // intersection test; no node is within the margin of a face).
  std::vector<double> pierced = s.Moved(-0.25);
  pierced[3 * 13 + 2] = -0.1;
  EXPECT_NE(pairs.FindPenetration(pierced.data(), 0.0).find("intersect"), std::string::npos)
      << pairs.FindPenetration(pierced.data(), 0.0);
  const double t = pairs.TimeOfImpact(s.x.data(), end.data(), 0.0, 0.0);
  // First contact at dz = -0.3 + margin: t = (0.3 - 1e-4) / 0.6; the goal is
  // 10 % of the gap above the margin.
  EXPECT_LE(t, (0.3 - 1e-4) / 0.6);
  EXPECT_GE(t, 0.9 * 0.3 / 0.6 - 1e-3);
  EXPECT_EQ(pairs.FindPenetration(s.Moved(-0.6 * t).data(), 0.0), "");
  EXPECT_EQ(pairs.TimeOfImpact(s.x.data(), s.Moved(0.5).data(), 0.0, 0.0), PairSet::kNoImpact);
  // Starting within the margin: 0.
  EXPECT_EQ(pairs.TimeOfImpact(s.Moved(-0.3).data(), end.data(), 0.0, 0.0), 0.0);
}

TEST(EdgeEdgePairs, CrossingEdgesExtendTermsAndTimeOfImpact) {
  // B turned by 45 degrees: its edges cross A's, 0.04 above them.
  TwoSheets s(0.04, 0.0, 0.7853981633974483, 0.1, 1e-4);
  EdgeEdgePairs pairs(s.context);
  ASSERT_TRUE(pairs.active());
  CandidateRegion region;
  region.start = region.end = s.x.data();
  EXPECT_TRUE(pairs.Extend(region));
  int count = 0;
  const double expected = BruteForceEdgeEdgeEnergy(s, pairs, s.x, &count);
  ASSERT_GT(count, 0);
  EXPECT_EQ(pairs.size(), static_cast<size_t>(count));
  EXPECT_FALSE(pairs.Missing(s.x.data()));
  pairs.AddBarrierTerms(&s.potential);
  ExpectEnergyAndGradient(s.potential, s.x, expected);

  const std::vector<double> end = s.Moved(-0.2);
  const double t = pairs.TimeOfImpact(s.x.data(), end.data(), 0.0, 0.0);
  EXPECT_LE(t, (0.04 - 1e-4) / 0.2);
  EXPECT_GE(t, 0.9 * 0.04 / 0.2 - 1e-3);
  EXPECT_EQ(pairs.FindPenetration(s.Moved(-0.2 * t).data(), 0.0), "");
  EXPECT_NE(pairs.FindPenetration(s.Moved(-0.04).data(), 0.0), "");
}

TEST(EdgeEdgePairs, ParallelEdgesAreMollified) {
  // B straight above A (no turn, no shift): many parallel edge pairs, whose
  // mollifier is 0 (exactly parallel): their terms add nothing.
  TwoSheets s(0.05, 0.0, 0.0, 0.1, 0.0);
  EdgeEdgePairs pairs(s.context);
  CandidateRegion region;
  region.start = region.end = s.x.data();
  pairs.Extend(region);
  int count = 0;
  const double expected = BruteForceEdgeEdgeEnergy(s, pairs, s.x, &count);
  ASSERT_GT(count, 0);
  pairs.AddBarrierTerms(&s.potential);
  double energy = 0.0;
  ASSERT_TRUE(s.potential.Evaluate(s.x.data(), &energy, nullptr));
  EXPECT_NEAR(energy, expected, 1e-12 + 1e-10 * expected);
  // Unmollified, the same pairs would have a barrier.
  double plain = 0.0;
  for (const auto& p : pairs.pairs()) {
    plain += Barrier(pairs.Distance(s.x.data(), p), 0.1);
  }
  EXPECT_GT(plain, 0.0);
  EXPECT_LT(energy, s.kappa * 0.125 * plain);
}

TEST(SelfContactFriction, TermsCarryTheLaggedNormalForce) {
  TwoSheets s(0.05, 0.2, 0.0, 0.1, 0.0);
  PointTrianglePairs pairs(s.context);
  CandidateRegion region;
  region.start = region.end = s.x.data();
  pairs.Extend(region);
  pairs.LagFriction(s.x.data(), 0.0);
  StepContext& step = s.potential.context();
  step.velocity_slope = 1.0;
  step.x_base = Eigen::Map<const Eigen::VectorXd>(s.x.data(), s.x.size());
  step.v_base.setZero();
  FrictionSettings friction;
  friction.mu = 0.5;
  friction.epsilon_v = 1e-3;
  const int contacts = pairs.AddFrictionTerms(friction, &s.potential);
  EXPECT_EQ(contacts, static_cast<int>(pairs.size()));
  // Slide B by (0.01, 0) (velocity 0.01 m/s with slope 1): every contact
  // slides at 0.01 > eps_v in the tangent plane (normal along z), so the
  // dissipation is mu lambda f0(0.01) per contact.
  std::vector<double> y = s.x;
  for (int node = 9; node < 18; ++node) y[3 * node] += 0.01;
  double expected = 0.0;
  for (const auto& p : pairs.pairs()) {
    const auto& f = s.mesh.faces[p.face];
    const double d =
        PointTriangleDistance(At(s.x, p.node), At(s.x, f[0]), At(s.x, f[1]), At(s.x, f[2]))
            .distance;
    const double lambda = -s.kappa * 0.25 * BarrierDerivative(d, 0.1);  // node weight a^2
    // One of the two primitives is on B, the other on A: relative speed 0.01.
    expected += friction.mu * lambda * FrictionF0(0.01, 1e-3);
  }
  double energy = 0.0;
  ASSERT_TRUE(s.potential.EvaluateUnweighted(
      [](const Term& t) { return t.kind == TermKind::kDissipation; }, y.data(), &energy, nullptr));
  EXPECT_NEAR(energy, expected, 1e-9 * expected);
}

}  // namespace
}  // namespace ipstep
