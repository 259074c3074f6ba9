// projected_newton's Hessian projection (OptimizerOptions::hessian_projection,
// solver/projected_newton_solver.h): with kWhenIndefinite the exact Hessian's
// step is taken wherever the assembled sum is positive definite, and the
// projected model's otherwise.
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
  long exact = 0, projected = 0;
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
  return solve;
}

// A compressed chain kicked sideways, backward Euler: every spring's Hessian
// is indefinite but the sum with the inertia M/h^2 is definite. Projection
// discards the springs' negative curvature and converges linearly; the exact
// steps converge quadratically to the same step.
TEST(HessianProjection, ExactStepsWhereTheSumIsDefiniteConvergeQuadratically) {
  const int n = 10;
  Scene scene = PinnedChain(n, 0.9);
  for (int i = 1; i + 1 < n; ++i) scene.velocities[2 * i + 1] = 3.0 * std::sin(0.7 * i);
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

}  // namespace
}  // namespace ipstep
