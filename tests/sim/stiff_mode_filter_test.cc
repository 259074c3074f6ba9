// The filtered local error estimate (sim/stiff_mode_filter.h): on a linear
// spring it is the raw estimate times m / (m + c k), the step matrix's
// amplification, and in an adaptive run a stiff mode of small amplitude no
// longer sets the steps while the error at the end still follows the
// tolerance (against the exact solution of the linear two-mass chain).
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Eigenvalues>

#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "sim/step_size_controller.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

// One step of h on the oscillator of stiffness k (unit mass, released from
// a stretch of 0.1; a rest length of 10 keeps the large steps' predictor on
// the spring's side of the anchor, where the spring is linear): the filtered
// estimate is the raw one over 1 + c k, with c = h^2 (backward Euler) or
// h^2 / 4 (Newmark), to round-off; with newton through a matrix assembled
// for the estimate, with projected_newton through the solver's own
// factorisation (StepSolver::SolveWithLastStepMatrix).
TEST(StiffModeFilter, OnALinearSpringItIsTheStepMatrixsAmplification) {
  const double k = 1e4;
  for (const std::string optimizer : {"newton", "projected_newton"}) {
    for (const std::string integrator : {"backward_euler", "newmark"}) {
      for (double h : {1e-3, 1e-2, 1e-1}) {
        Simulation sim(testing::OscillatorScene(0.1, k, 1.0, 10.0),
                       testing::Options(integrator, optimizer, h));
        const State before = sim.state();
        const StepReport report = sim.Step(h, /*retry_as_substeps=*/false);
        ASSERT_TRUE(report.converged)
            << optimizer << " " << integrator << " " << h << ": " << report.status;
        const double raw = sim.LocalError(before, h, /*filter_stiff_modes=*/false);
        const double filtered = sim.LocalError(before, h, /*filter_stiff_modes=*/true);
        const double c = integrator == "newmark" ? 0.25 * h * h : h * h;
        ASSERT_GT(raw, 0.0);
        EXPECT_NEAR(filtered, raw / (1.0 + c * k), 1e-9 * raw)
            << optimizer << " " << integrator << " h=" << h;
      }
    }
  }
}

// A soft spring (k = 1) from a pinned anchor to mass 1, a stiff one (K = 1e6)
// from it to mass 2, the stiff mode excited by 1e-6 m: its acceleration,
// 1 m/s^2, dominates the raw estimate while its amplitude is far below the
// tolerance. Newmark keeps the stiff mode's amplitude: with the filter its run
// takes a fifth of the steps or fewer (41 against 678 when written). Backward
// Euler damps the mode in its first steps, so the filter saves it little
// (never costs it steps). Both stay within 3 tol of the exact solution
// u(t) = V cos(Omega t) V^T u(0).
TEST(StiffModeFilter, AStiffModeOfSmallAmplitudeDoesNotSetTheSteps) {
  const double k = 1.0, stiff = 1e6, t_end = 2.0, tolerance = 1e-3;
  const Eigen::Vector2d u0(0.1, 0.1 + 1e-6);  // displacements from rest
  Scene scene = testing::OscillatorScene(u0[0], k);
  scene.positions.insert(scene.positions.end(), {2.0 + u0[1], 0.0});
  scene.velocities.insert(scene.velocities.end(), {0.0, 0.0});
  scene.masses.push_back(1.0);
  scene.springs.push_back(Spring{1, 2, SpringModel::kHookean, stiff, 1.0});
  Eigen::Matrix2d stiffness;
  stiffness << k + stiff, -stiff, -stiff, stiff;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> modes(stiffness);
  const Eigen::Vector2d omega = modes.eigenvalues().cwiseSqrt();
  const Eigen::Vector2d exact = modes.eigenvectors() *
                                (omega * t_end).array().cos().matrix().asDiagonal() *
                                modes.eigenvectors().transpose() * u0;
  for (const std::string integrator : {"backward_euler", "newmark"}) {
    int steps[2] = {0, 0};
    for (const bool filter : {false, true}) {
      RunOptions options;
      options.adaptive = true;
      options.adaptive_options.error_tolerance = tolerance;
      options.adaptive_options.t_end = t_end;
      options.adaptive_options.filter_stiff_modes = filter;
      SimulationOptions sim_options = testing::Options(integrator, "newton", 1e-3);
      ConfigureAdaptiveSimulation(options.adaptive_options, /*keep_tolerance=*/false, &sim_options);
      Simulation sim(scene, sim_options);
      const RunSummary run = RunTrajectory(sim, options);
      ASSERT_EQ(run.termination, RunTermination::kCompleted) << integrator;
      EXPECT_EQ(run.failed, 0) << integrator;
      steps[filter] = run.steps_done;
      if (!filter) continue;
      const Eigen::Vector2d u(sim.state().x[2] - 1.0, sim.state().x[4] - 2.0);
      EXPECT_LT((u - exact).lpNorm<Eigen::Infinity>(), 3.0 * tolerance) << integrator;
    }
    if (integrator == "newmark") {
      EXPECT_LT(5 * steps[1], steps[0]) << steps[1] << " filtered against " << steps[0] << " raw";
    } else {
      EXPECT_LE(steps[1], steps[0]) << steps[1] << " filtered against " << steps[0] << " raw";
    }
  }
}

}  // namespace
}  // namespace ipstep
