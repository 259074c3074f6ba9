// The Newton optimisers' Hessian projection (OptimizerOptions::hessian_projection,
// solver/projected_newton_solver.h, solver/trust_region_solver.h): with
// kWhenIndefinite the exact Hessian's step is taken wherever the assembled sum
// is positive definite, and the projected model's otherwise; kProgressive
// projects only terms at nodes whose force imbalance is above the tolerance;
// kAbsolute filters eigenvalues by their magnitude, kTrustRegion picks clamp
// or absolute from the last step's fit.
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/SparseCholesky>

#include "sim/simulation.h"
#include "solver/projected_newton_solver.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;

// n nodes of 0.01 kg on the x axis, `spacing` apart, Hookean springs k = 100
// of rest length 1, both ends pinned: spacing < 1 compresses every spring, whose
// Hessian then has negative curvature k (1 - L/|d|) across it.
Scene PinnedChain(int n, double spacing) {
  Scene scene;
  scene.name = scene.source = "pinned_chain";
  for (int i = 0; i < n; ++i) {
    scene.positions.push_back(spacing * i);
    scene.positions.push_back(0.0);
    scene.masses.push_back(0.01);
  }
  scene.velocities.assign(2 * n, 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    scene.springs.push_back(Spring{i, i + 1, SpringModel::kHookean, 100.0, 1.0});
  }
  scene.pinned = {0, n - 1};
  scene.effects = {"springs"};
  return scene;
}

struct Solve {
  std::vector<double> residuals;
  StepReport report;
  Eigen::VectorXd x;
  long exact = 0, projected = 0, absolute = 0, projected_terms = 0, term_models = 0;
};

Solve StepWith(const Scene& scene, SimulationOptions options, HessianProjection projection) {
  options.optimizer.optimizer = Optimizer::kProjectedNewton;
  options.optimizer.hessian_projection = projection;
  Simulation sim(scene, options);
  ProjectedNewtonSolver* solver = nullptr;
  sim.ReplaceStepSolver([&](IncrementalPotential* p, const State* s) {
    auto made = std::make_unique<ProjectedNewtonSolver>(p, s, options.optimizer);
    solver = made.get();
    return made;
  });
  Solve solve;
  sim.set_iteration_sink([&](const IterationRecord& r) { solve.residuals.push_back(r.residual); });
  solve.report = sim.Step();
  solve.x = sim.state().x;
  solve.exact = solver->exact_directions();
  solve.projected = solver->projected_directions();
  solve.absolute = solver->absolute_directions();
  solve.projected_terms = solver->projected_terms();
  solve.term_models = solver->term_models();
  return solve;
}

// The kicked compressed chain below: every spring indefinite, the sum with
// the inertia definite.
Scene KickedChain(int n) {
  Scene scene = PinnedChain(n, 0.9);
  for (int i = 1; i + 1 < n; ++i) scene.velocities[2 * i + 1] = 3.0 * std::sin(0.7 * i);
  return scene;
}

// A compressed chain kicked sideways, backward Euler: every spring's Hessian
// is indefinite but the sum with the inertia M/h^2 is definite. Projection
// discards the springs' negative curvature and converges linearly; the exact
// steps converge quadratically to the same step.
TEST(HessianProjection, ExactStepsWhereTheSumIsDefiniteConvergeQuadratically) {
  const Scene scene = KickedChain(10);
  const SimulationOptions options = Options("backward_euler", "projected_newton", 0.01, 1e-9);
  const Solve projected = StepWith(scene, options, HessianProjection::kAlways);
  const Solve exact = StepWith(scene, options, HessianProjection::kWhenIndefinite);
  ASSERT_TRUE(projected.report.converged) << projected.report.status;
  ASSERT_TRUE(exact.report.converged) << exact.report.status;
  EXPECT_EQ(projected.exact, 0);
  EXPECT_EQ(exact.projected, 0);  // the sum stays definite here
  EXPECT_EQ(exact.exact, exact.report.iterations);
  EXPECT_LT(exact.report.iterations, projected.report.iterations);
  // The same step: both within the stopping rule (h |f| / m <= 1e-9).
  EXPECT_LT((exact.x - projected.x).lpNorm<Eigen::Infinity>(), 1e-9);
  int quadratic_pairs = 0;
  const std::vector<double>& r = exact.residuals;
  for (size_t k = 0; k + 1 < r.size(); ++k) {
    if (r[k] / r[0] < 1e-2 && r[k + 1] / r[0] > 1e-12) {
      EXPECT_LE(r[k + 1] / r[0], 10.0 * (r[k] / r[0]) * (r[k] / r[0])) << "iteration " << k;
      ++quadratic_pairs;
    }
  }
  EXPECT_GE(quadratic_pairs, 1);
  std::printf("compressed chain: %d iterations projected, %d exact\n", projected.report.iterations,
              exact.report.iterations);
}

// Quasi-static (no inertia): the compressed chain's exact Hessian is
// indefinite (it would buckle), so every iteration falls back to the
// projected model and the solve is the same as with kAlways, iterate for
// iterate.
TEST(HessianProjection, IndefiniteSumsFallBackToTheProjectedModel) {
  const int n = 10;
  Scene scene = PinnedChain(n, 0.9);
  for (int i = 1; i + 1 < n; ++i) scene.positions[2 * i + 1] = 1e-3 * std::sin(0.7 * i);
  SimulationOptions options = Options("quasi_static", "projected_newton", 0.01, 1e-9);
  options.optimizer.max_iterations = 3;
  const Solve projected = StepWith(scene, options, HessianProjection::kAlways);
  const Solve fallback = StepWith(scene, options, HessianProjection::kWhenIndefinite);
  ASSERT_EQ(fallback.report.iterations, 3) << fallback.report.status;
  EXPECT_EQ(fallback.exact, 0);
  EXPECT_EQ(fallback.projected, 3);
  EXPECT_EQ(fallback.residuals, projected.residuals);
  EXPECT_EQ(fallback.x, projected.x);
}

// Progressive projection on the kicked chain: its first matrix of each
// iteration has no term projected (no node is above the largest share of the
// stopping measure), and the sum is definite here, so it takes the exact
// steps, as when_indefinite, projecting nothing.
TEST(HessianProjection, ProgressiveTakesExactStepsWhereTheSumIsDefinite) {
  const Scene scene = KickedChain(10);
  const SimulationOptions options = Options("backward_euler", "projected_newton", 0.01, 1e-9);
  const Solve exact = StepWith(scene, options, HessianProjection::kWhenIndefinite);
  const Solve progressive = StepWith(scene, options, HessianProjection::kProgressive);
  ASSERT_TRUE(progressive.report.converged) << progressive.report.status;
  EXPECT_EQ(progressive.report.iterations, exact.report.iterations);
  EXPECT_EQ(progressive.projected_terms, 0);
  EXPECT_EQ(progressive.exact, progressive.report.iterations);
  EXPECT_EQ(progressive.x, exact.x);
}

// Quasi-static, the chain would buckle: the exact sum is indefinite, so
// progressive projects terms until the partly projected sum is definite (its
// directions are not the fully projected ones) and reaches the equilibrium
// kAlways reaches, in no more iterations.
TEST(HessianProjection, ProgressiveProjectsUntilTheSumIsDefinite) {
  const int n = 10;
  Scene scene = PinnedChain(n, 0.9);
  for (int i = 1; i + 1 < n; ++i) scene.positions[2 * i + 1] = 1e-3 * std::sin(0.7 * i);
  const SimulationOptions options = Options("quasi_static", "projected_newton", 0.01, 1e-9);
  const Solve projected = StepWith(scene, options, HessianProjection::kAlways);
  const Solve progressive = StepWith(scene, options, HessianProjection::kProgressive);
  ASSERT_TRUE(projected.report.converged) << projected.report.status;
  ASSERT_TRUE(progressive.report.converged) << progressive.report.status;
  EXPECT_GT(progressive.exact, 0);
  EXPECT_GT(progressive.projected_terms, 0);
  EXPECT_LE(progressive.report.iterations, projected.report.iterations);
  EXPECT_LT((progressive.x - projected.x).lpNorm<Eigen::Infinity>(), 1e-8);
  std::printf("buckling chain: %d iterations projected, %d progressive\n",
              projected.report.iterations, progressive.report.iterations);
}

// The absolute-value filter keeps a negative eigenvalue's magnitude; the
// clamp keeps (almost) nothing of it.
TEST(HessianProjection, AbsoluteFilterKeepsTheMagnitude) {
  TermModel model;
  model.hessian = TermMatrix::Zero(3, 3);
  model.hessian.diagonal() << 4.0, -2.0, 1.0;
  model.gradient = TermVector::Zero(3);
  ProjectedHessian clamped, absolute;
  ProjectHessian(model, &clamped, EigenvalueFilter::kClamp);
  ProjectHessian(model, &absolute, EigenvalueFilter::kAbsolute);
  auto matrix = [](const ProjectedHessian& p) -> TermMatrix {
    return p.vectors * p.values.asDiagonal() * p.vectors.transpose();
  };
  EXPECT_NEAR(matrix(absolute)(1, 1), 2.0, 1e-14);
  EXPECT_NEAR(matrix(clamped)(1, 1), kCurvatureFloor * 4.0, 1e-14);
  EXPECT_NEAR(matrix(absolute)(0, 0), 4.0, 1e-14);
  EXPECT_NEAR(matrix(absolute)(2, 2), 1.0, 1e-14);
}

// A chain pinned at 0.3 of its length, quasi-static, released from a tall
// zig-zag: clamping calls the compressed springs' transverse modes free, and
// some full steps overshoot (the fit is poor), so trust_region switches to
// the absolute filter for some iterations; kAbsolute uses it on every one,
// kAlways on none. All three converge.
TEST(HessianProjection, TrustRegionSwitchesToAbsoluteAfterAPoorFit) {
  const int n = 8;
  Scene scene = PinnedChain(n, 0.3);
  for (int i = 1; i + 1 < n; ++i) {
    scene.positions[2 * i + 1] = (i % 2 ? 1.0 : -1.0) * (1.0 + 0.3 * std::sin(i));
  }
  const SimulationOptions options = Options("quasi_static", "projected_newton", 0.01, 1e-8);
  const Solve clamp = StepWith(scene, options, HessianProjection::kAlways);
  const Solve absolute = StepWith(scene, options, HessianProjection::kAbsolute);
  const Solve adaptive = StepWith(scene, options, HessianProjection::kTrustRegion);
  ASSERT_TRUE(clamp.report.converged) << clamp.report.status;
  ASSERT_TRUE(absolute.report.converged) << absolute.report.status;
  ASSERT_TRUE(adaptive.report.converged) << adaptive.report.status;
  EXPECT_EQ(clamp.absolute, 0);
  EXPECT_EQ(absolute.absolute, absolute.report.iterations);
  EXPECT_GT(adaptive.absolute, 0);
  EXPECT_LT(adaptive.absolute, adaptive.report.iterations);
  std::printf("zig-zag chain: clamp %d, abs %d, trust_region %d iterations (%ld abs)\n",
              clamp.report.iterations, absolute.report.iterations, adaptive.report.iterations,
              adaptive.absolute);
}

// Ceres's newton with the inertia projection (solver/inertia_absorption.h) on
// the kicked chain: the inertia carries every spring's negative curvature, so
// Ceres's model is the exact Hessian and newton takes projected_newton's
// exact (when_indefinite) steps: the same count, quadratic convergence, the
// same step; with the clamp it needs many more.
TEST(HessianProjection, InertiaGivesCeresTheExactHessian) {
  const Scene scene = KickedChain(10);
  SimulationOptions options = Options("backward_euler", "newton", 0.01, 1e-9);
  const Solve exact = StepWith(scene, options, HessianProjection::kWhenIndefinite);
  auto newton = [&](HessianProjection projection) {
    options.optimizer.hessian_projection = projection;
    Simulation sim(scene, options);
    Solve solve;
    sim.set_iteration_sink(
        [&](const IterationRecord& r) { solve.residuals.push_back(r.residual); });
    solve.report = sim.Step();
    solve.x = sim.state().x;
    return solve;
  };
  const Solve clamped = newton(HessianProjection::kAlways);
  const Solve absorbed = newton(HessianProjection::kInertia);
  ASSERT_TRUE(absorbed.report.converged) << absorbed.report.status;
  EXPECT_EQ(absorbed.report.iterations, exact.report.iterations);
  EXPECT_GT(clamped.report.iterations, absorbed.report.iterations);
  EXPECT_LT((absorbed.x - exact.x).lpNorm<Eigen::Infinity>(), 1e-9);
  std::printf(
      "kicked chain, newton: %d iterations clamped, %d inertia (projected_newton exact %d)\n",
      clamped.report.iterations, absorbed.report.iterations, exact.report.iterations);
}

}  // namespace
}  // namespace ipstep
