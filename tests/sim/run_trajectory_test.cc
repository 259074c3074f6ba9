// The run loop (sim/run_trajectory.h) and the divergence rule
// (sim/divergence.h): healthy runs of scenes whose initial energy is round-off
// or exactly 0 are not called diverged; a blow-up is, within a few steps of
// its first non-physical energy, and every later step says so.
#include <cmath>
#include <csignal>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/divergence.h"
#include "sim/run_trajectory.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;

Scene LoadBuiltin(const std::string& name) {
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  return LoadScene(name, options);
}

// A rod of n nodes along the x axis, its first two nodes pinned (clamped),
// Hookean springs between neighbours and second neighbours (stiffness k), unit
// total mass, gravity -9.81 y: at rest on y = 0 its initial energy is exactly
// 0 (no stretch, no height). Highest frequency ~ 2 sqrt(k / m_node).
Scene ClampedRod(int n = 11, double k = 1e4) {
  Scene s;
  s.name = s.source = "test_clamped_rod";
  const double spacing = 1.0 / (n - 1);
  for (int i = 0; i < n; ++i) {
    s.positions.push_back(i * spacing);
    s.positions.push_back(0.0);
    s.masses.push_back(1.0 / n);
  }
  s.velocities.assign(s.positions.size(), 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    s.springs.push_back(Spring{i, i + 1, SpringModel::kHookean, k, spacing});
    if (i + 2 < n) s.springs.push_back(Spring{i, i + 2, SpringModel::kHookean, k, 2 * spacing});
  }
  s.pinned = {0, 1};
  s.gravity = {0.0, -9.81};
  s.effects = {"gravity", "springs"};
  s.time_step = 1e-3;
  s.steps = 400;
  return s;
}

TEST(DivergenceRule, ScaleComesFromTheSceneNotFromTheInitialEnergy) {
  Simulation sim(ClampedRod(), Options("symplectic_euler", "newton", 1e-3));
  EXPECT_NEAR(sim.Energies().total(), 0.0, 1e-20);  // round-off of the rest lengths
  const DivergenceRule rule(sim, 1.0);
  // M |g| L with M = 1 kg, L = 1 m (the rod's box): nothing stored, nothing moving.
  EXPECT_NEAR(rule.EnergyScale(0.0), 9.81, 1e-12);
  EXPECT_NEAR(rule.Reach(0.0), 0.5, 1e-12);
  // The fall adds to both: |g| t^2 / 2 after t = 1 s.
  EXPECT_NEAR(rule.Reach(1.0), 0.5 + 0.5 * 9.81, 1e-12);
  EXPECT_GT(rule.EnergyScale(1.0), rule.EnergyScale(0.0));
}

TEST(DivergenceRule, StableExplicitRunOfARodAtRestIsNotDiverged) {
  // h = 1e-3 s: omega_max h ~ 2 sqrt(1e4 / (1/11)) 1e-3 = 0.66 < 2.
  Simulation sim(ClampedRod(), Options("symplectic_euler", "newton", 1e-3));
  const RunSummary run = RunTrajectory(sim);
  EXPECT_EQ(run.termination, RunTermination::kCompleted) << run.message;
  EXPECT_EQ(run.steps_done, 400);
  EXPECT_EQ(run.failed, 0);
  EXPECT_FALSE(run.diverged());
  // The drift is measured in energy scales, also for E_0 = 0, and it is small.
  EXPECT_TRUE(std::isfinite(run.max_energy_drift));
  EXPECT_GT(run.max_energy_drift, 0.0);
  EXPECT_LT(run.max_energy_drift, 1.0);
}

TEST(DivergenceRule, ExplicitBlowUpIsDivergedSoonAfterItsFirstNonPhysicalStep) {
  // h = 5e-3 s: omega_max h ~ 3.3 > 2, symplectic Euler is unstable.
  SimulationOptions options = Options("symplectic_euler", "newton", 5e-3);
  int first_non_physical = 0;
  double scale = 0.0;
  {
    // The same run without the loop: the first step whose energy is 10 energy
    // scales from the start (no physical motion of this rod gets there).
    Simulation sim(ClampedRod(), options);
    const DivergenceRule rule(sim, 2.0);
    scale = rule.EnergyScale(0.0);
    for (int step = 1; step <= 400 && first_non_physical == 0; ++step) {
      const StepReport r = sim.Step();
      if (!(rule.Drift(r.time, r.energies.total()) <= 10.0)) first_non_physical = step;
    }
  }
  ASSERT_GT(first_non_physical, 0);
  Simulation sim(ClampedRod(), options);
  const RunSummary run = RunTrajectory(sim);
  EXPECT_EQ(run.termination, RunTermination::kDiverged) << run.message;
  EXPECT_GT(run.diverged_at, 0);
  EXPECT_GE(run.diverged_at, first_non_physical);
  EXPECT_LE(run.diverged_at, first_non_physical + 10) << "scale " << scale;
  EXPECT_EQ(run.steps_done, run.diverged_at);
  EXPECT_EQ(run.message.rfind("diverged at step " + std::to_string(run.diverged_at), 0), 0u)
      << run.message;
}

TEST(DivergenceRule, EveryStepAfterTheDivergenceCarriesItsStatus) {
  Simulation sim(ClampedRod(), Options("symplectic_euler", "newton", 5e-3));
  RunOptions options;
  options.steps = 120;
  options.stop_on_divergence = false;
  int diverged_steps = 0, converged_after = 0, first = 0;
  options.after_step = [&](const StepReport& r) {
    const bool diverged = r.status.rfind("diverged: ", 0) == 0;
    if (diverged && first == 0) first = r.step;
    if (first > 0) {
      diverged_steps += diverged;
      converged_after += r.converged;
    }
  };
  const RunSummary run = RunTrajectory(sim, options);
  ASSERT_GT(first, 0);
  EXPECT_EQ(run.diverged_at, first);
  EXPECT_EQ(run.termination, RunTermination::kCompleted);
  EXPECT_EQ(run.steps_done, 120);
  EXPECT_EQ(diverged_steps, 120 - first + 1);
  EXPECT_EQ(converged_after, 0);
  EXPECT_EQ(run.failed, 120 - first + 1);
}

// The scenes whose initial energy is round-off (about -5.7e-14 J or 5.8e-14 J)
// were "diverged at step 1" under a rule relative to |E_0|.
TEST(DivergenceRule, RoundOffInitialEnergyIsNotADivergence) {
  for (const char* name : {"hanging_square", "drop", "slope", "squeeze", "cantilever_2d"}) {
    const Scene scene = LoadBuiltin(name);
    for (const std::string integrator : {"backward_euler", "newmark", "symplectic_euler"}) {
      SimulationOptions options = Options(integrator, "newton", 0.0, 1e-6);
      options.max_substeps = 16;
      if (integrator == "symplectic_euler") options.time_step = 1e-4;  // stable
      Simulation sim(scene, options);
      RunOptions run_options;
      run_options.steps = 10;
      const RunSummary run = RunTrajectory(sim, run_options);
      EXPECT_FALSE(run.diverged()) << name << " " << integrator << ": " << run.message;
      EXPECT_LT(run.max_energy_drift, 10.0) << name << " " << integrator;
    }
  }
}

// The built-in twisted bar: its rotating end does 125 J of work on a bar that
// starts with 0.025 J; the scale counts that work, so the drift stays about
// one energy scale.
TEST(DivergenceRule, PrescribedWorkIsPartOfTheScale) {
  SimulationOptions options = Options("backward_euler", "projected_newton", 0.0, 1e-5);
  Simulation sim(LoadBuiltin("twisted_bar_3d"), options);
  const RunSummary run = RunTrajectory(sim);
  EXPECT_EQ(run.termination, RunTermination::kCompleted) << run.message;
  EXPECT_GT(run.final_energies.total(), 1e3 * run.initial_energies.total());
  EXPECT_GT(run.energy_scale, 100.0);
  EXPECT_LT(run.max_energy_drift, 2.0);
}

TEST(RunTrajectory, CountsPerStepTakenAndStopsWhereAsked) {
  Simulation sim(testing::OscillatorScene(), Options("backward_euler", "newton", 0.1, 1e-8));
  RunOptions options;
  options.steps = 7;
  int before = 0, after = 0;
  options.before_step = [&](int step) { EXPECT_EQ(step, ++before); };
  options.after_step = [&](const StepReport& r) { EXPECT_EQ(r.step, ++after); };
  const RunSummary run = RunTrajectory(sim, options);
  EXPECT_EQ(run.steps_planned, 7);
  EXPECT_EQ(run.steps_done, 7);
  EXPECT_EQ(before, 7);
  EXPECT_EQ(after, 7);
  EXPECT_EQ(run.termination, RunTermination::kCompleted);
  EXPECT_GT(run.iterations, 0);
  EXPECT_NEAR(run.ms_per_step(), 1e3 * run.step_seconds / 7, 1e-12);
  EXPECT_NEAR(sim.state().time, 0.7, 1e-12);
  // A time limit stops after the first step (any step takes longer than 1 ns).
  options.steps = 5;
  options.max_wall_seconds = 1e-9;
  options.before_step = nullptr;
  options.after_step = nullptr;
  const RunSummary limited = RunTrajectory(sim, options);
  EXPECT_EQ(limited.termination, RunTermination::kTimeout);
  EXPECT_EQ(limited.steps_done, 1);
  EXPECT_EQ(limited.steps_planned, 5);
  EXPECT_NEAR(limited.ms_per_step(), 1e3 * limited.step_seconds, 1e-12);
  options.steps = -2;
  EXPECT_THROW(RunTrajectory(sim, options), InputError);
}

// An interrupt (a flag a signal handler sets) stops the run after the step in
// progress, its after_step included; a flag set during the last step leaves
// the run completed.
TEST(RunTrajectory, AnInterruptStopsAfterTheStepInProgress) {
  Simulation sim(testing::OscillatorScene(), Options("backward_euler", "newton", 0.1, 1e-8));
  volatile std::sig_atomic_t interrupt = 0;
  RunOptions options;
  options.steps = 10;
  options.interrupt = &interrupt;
  int after = 0;
  options.after_step = [&](const StepReport& r) {
    ++after;
    if (r.step == 3) interrupt = SIGINT;
  };
  const RunSummary run = RunTrajectory(sim, options);
  EXPECT_EQ(run.termination, RunTermination::kInterrupted);
  EXPECT_EQ(run.steps_done, 3);
  EXPECT_EQ(after, 3);
  EXPECT_EQ(run.message, "interrupted at step 3");
  EXPECT_STREQ(RunTerminationName(run.termination), "interrupted");
  EXPECT_NEAR(sim.state().time, 0.3, 1e-12);
  interrupt = 0;
  options.steps = 2;
  options.after_step = [&](const StepReport& r) {
    if (r.step == 2) interrupt = SIGTERM;
  };
  const RunSummary last = RunTrajectory(sim, options);
  EXPECT_EQ(last.termination, RunTermination::kCompleted) << last.message;
  EXPECT_EQ(last.steps_done, 2);
}

TEST(RunTrajectory, StopOnFailureStopsAtTheFirstFailedStep) {
  // Two gradient-descent iterations cannot solve a cloth step: step 1 fails.
  SimulationOptions sim_options = Options("backward_euler", "gradient_descent", 1.0 / 60, 1e-6);
  sim_options.optimizer.max_iterations = 2;
  Simulation sim(testing::ClothScene(6), sim_options);
  RunOptions options;
  options.steps = 5;
  options.stop_on_failure = true;
  const RunSummary run = RunTrajectory(sim, options);
  EXPECT_EQ(run.termination, RunTermination::kStepFailed) << run.message;
  EXPECT_EQ(run.steps_done, 1);
  EXPECT_EQ(run.first_failed_step, 1);
  EXPECT_FALSE(run.diverged());
  EXPECT_EQ(run.message.rfind("step 1 failed: ", 0), 0u) << run.message;
}

}  // namespace
}  // namespace ipstep
