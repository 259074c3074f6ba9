// The error measures (sim/error_measure.h) and the checkpoint recorder behind
// max_position (sim/checkpoint_recorder.h), against exact solutions: the
// built-in oscillator (x = 1 + 0.1 cos t) and a projectile (a parabola, which
// Newmark integrates exactly and the Hermite polynomial reproduces).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "problems/scene_loader.h"
#include "sim/checkpoint_recorder.h"
#include "sim/default_effects.h"
#include "sim/error_measure.h"
#include "sim/reference.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;

Scene Oscillator() {
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  return LoadScene("oscillator", options);
}

// The oscillator's exact solution at its checkpoints (ComputeReference gives
// the exact one for the built-in scene).
ReferenceSolution ExactReference(const Scene& scene, double t_end, int checkpoints) {
  ReferenceOptions options;
  options.checkpoints = checkpoints;
  const ReferenceSolution reference =
      ComputeReference(scene, SimulationOptions{}, options, 0.1, t_end);
  EXPECT_TRUE(reference.exact);
  return reference;
}

double NewmarkError(const Scene& scene, double h, double t_end, ErrorMeasure measure,
                    const ReferenceSolution& reference) {
  SimulationOptions options = Options("newmark", "newton", h);
  options.steps = static_cast<int>(std::lround(t_end / h));
  Simulation sim(scene, options);
  return RunMeasured(sim, RunOptions{}, measure, &reference).error;
}

TEST(ErrorMeasure, NamesRoundTrip) {
  for (ErrorMeasure m :
       {ErrorMeasure::kPosition, ErrorMeasure::kMaxPosition, ErrorMeasure::kEnergy}) {
    ErrorMeasure parsed = ErrorMeasure::kEnergy;
    EXPECT_TRUE(ParseErrorMeasure(ErrorMeasureName(m), &parsed));
    EXPECT_EQ(parsed, m);
  }
  ErrorMeasure unchanged = ErrorMeasure::kPosition;
  EXPECT_FALSE(ParseErrorMeasure("max", &unchanged));
  EXPECT_EQ(unchanged, ErrorMeasure::kPosition);
  EXPECT_STREQ(ErrorMeasureUnit(ErrorMeasure::kMaxPosition), "m");
  EXPECT_FALSE(MeasureNeedsReference(ErrorMeasure::kEnergy));
}

// Checkpoints on step ends (t_j = 0.5 j, h = 0.1): the sampled maximum is the
// error taken directly at those step ends, and it is at least the final error.
TEST(ErrorMeasure, MaxPositionOnStepEndsIsTheDirectMaximum) {
  const Scene scene = Oscillator();
  const ReferenceSolution reference = ExactReference(scene, 10.0, 20);
  ASSERT_EQ(reference.checkpoint_x.size(), 20u);
  const double sampled = NewmarkError(scene, 0.1, 10.0, ErrorMeasure::kMaxPosition, reference);

  SimulationOptions options = Options("newmark", "newton", 0.1);
  options.steps = 100;
  Simulation sim(scene, options);
  double direct = 0.0;
  RunOptions run_options;
  run_options.after_step = [&](const StepReport& report) {
    if (report.step % 5 != 0) return;
    Eigen::VectorXd exact;
    ExactPositions(scene, report.time, &exact);
    direct = std::max(direct, MaxNodeDistance(sim.state().x, exact, {1}, 2));
  };
  const RunSummary run = RunTrajectory(sim, run_options);
  ASSERT_EQ(run.steps_done, 100);
  EXPECT_NEAR(sampled, direct, 1e-13 + 1e-10 * direct);
  const double final_error = NewmarkError(scene, 0.1, 10.0, ErrorMeasure::kPosition, reference);
  EXPECT_GE(sampled, final_error);
  // The phase error grows with t, but |sin t| at t = 8 s is 0.99 and at 10 s 0.54.
  EXPECT_GT(sampled, 1.3 * final_error);
}

// Newmark is second order: the max-position error falls ~4x per halving of h,
// also with checkpoints inside the steps (h = 10/33, 10/66, 10/132 s).
TEST(ErrorMeasure, MaxPositionFallsAtTheIntegratorsOrder) {
  const Scene scene = Oscillator();
  const ReferenceSolution reference = ExactReference(scene, 10.0, 20);
  double previous = NAN;
  for (int steps : {33, 66, 132}) {
    const double error =
        NewmarkError(scene, 10.0 / steps, 10.0, ErrorMeasure::kMaxPosition, reference);
    ASSERT_TRUE(std::isfinite(error)) << steps;
    if (!std::isnan(previous)) {
      EXPECT_GT(previous / error, 3.6) << steps;
      EXPECT_LT(previous / error, 4.4) << steps;
    }
    previous = error;
  }
}

// A projectile under gravity: Newmark's trapezoidal rule is exact for a
// constant force, and the Hermite polynomial through exact ends is the
// parabola itself, at any checkpoint inside a step, fixed or adaptive.
TEST(CheckpointRecorder, ReproducesAParabolaInsideSteps) {
  Scene scene;
  scene.name = scene.source = "test_projectile";
  scene.dimension = 2;
  scene.positions = {0.0, 0.0};
  scene.velocities = {1.0, 2.0};
  scene.masses = {1.0};
  scene.gravity = {0.0, -9.81};
  scene.effects = {"gravity"};
  const std::vector<double> times = CheckpointTimes(0.0, 0.4, 7);  // 0.0571.. s apart
  for (bool adaptive : {false, true}) {
    SimulationOptions options = Options("newmark", "newton", 0.03);
    RunOptions run_options;
    if (adaptive) {
      run_options.adaptive = true;
      run_options.adaptive_options.error_tolerance = 1e-4;
      run_options.adaptive_options.t_end = 0.4;
      ConfigureAdaptiveSimulation(run_options.adaptive_options, true, &options);
    } else {
      options.steps = 13;
      options.time_step = 0.4 / 13;
    }
    Simulation sim(scene, options);
    CheckpointRecorder recorder(times);
    recorder.Attach(sim, &run_options);
    const RunSummary run = RunTrajectory(sim, run_options);
    ASSERT_EQ(run.termination, RunTermination::kCompleted) << run.message;
    ASSERT_TRUE(recorder.complete()) << adaptive;
    for (size_t j = 0; j < times.size(); ++j) {
      const double t = times[j];
      EXPECT_NEAR(recorder.positions()[j][0], t, 1e-9) << adaptive << " " << j;
      EXPECT_NEAR(recorder.positions()[j][1], 2.0 * t - 0.5 * 9.81 * t * t, 1e-9)
          << adaptive << " " << j;
    }
  }
}

// A long fixed run's time, a sum of its steps, ends short of its end by
// round-off (64000 steps of 1/64000 s: 1 - 9e-13 s): the last checkpoint is
// still its end state.
TEST(CheckpointRecorder, TakesTheLastCheckpointAtTheEndOfALongRun) {
  Scene scene;
  scene.name = scene.source = "test_projectile";
  scene.positions = {0.0, 0.0};
  scene.velocities = {1.0, 2.0};
  scene.masses = {1.0};
  scene.gravity = {0.0, -9.81};
  scene.effects = {"gravity"};
  SimulationOptions options = Options("newmark", "projected_newton", 1.0 / 64000);
  options.steps = 64000;
  Simulation sim(scene, options);
  CheckpointRecorder recorder(CheckpointTimes(0.0, 1.0, 4));
  RunOptions run_options;
  recorder.Attach(sim, &run_options);
  RunTrajectory(sim, run_options);
  ASSERT_LT(sim.state().time, 1.0);
  ASSERT_TRUE(recorder.complete());
  EXPECT_EQ(recorder.positions().back(), sim.state().x);
}

// A distance that is not finite makes the largest one NaN, wherever it is.
TEST(ErrorMeasure, MaxNodeDistanceIsNaNForANonFiniteDistance) {
  const Eigen::Vector4d x(0, 0, 1, 1), y(0, 0, 1, 2);
  EXPECT_EQ(MaxNodeDistance(x, y, {0, 1}, 2), 1.0);
  const Eigen::Vector4d nan_first(std::nan(""), 0, 1, 1);
  EXPECT_TRUE(std::isnan(MaxNodeDistance(nan_first, y, {0, 1}, 2)));
  const Eigen::Vector4d nan_last(0, 0, std::nan(""), 1);
  EXPECT_TRUE(std::isnan(MaxNodeDistance(x, nan_last, {0, 1}, 2)));
}

// An adaptive run is measured like a fixed one; the reference's last
// checkpoint is its end, and max_position needs checkpoints.
TEST(ErrorMeasure, AdaptiveRunsAndReferencesWithoutCheckpoints) {
  const Scene scene = Oscillator();
  const ReferenceSolution reference = ExactReference(scene, 10.0, 20);
  SimulationOptions options = Options("newmark", "newton", 0.1);
  RunOptions run_options;
  run_options.adaptive = true;
  run_options.adaptive_options.error_tolerance = 1e-3;
  run_options.adaptive_options.t_end = 10.0;
  ConfigureAdaptiveSimulation(run_options.adaptive_options, false, &options);
  Simulation sim(scene, options);
  const MeasuredRun max = RunMeasured(sim, run_options, ErrorMeasure::kMaxPosition, &reference);
  ASSERT_TRUE(std::isfinite(max.error)) << max.run.message;
  EXPECT_GT(max.error, 0.0);
  EXPECT_LT(max.error, 1e-2);
  EXPECT_EQ(reference.checkpoint_times.back(), 10.0);

  const ReferenceSolution end_only = ExactReference(scene, 10.0, 0);
  Simulation again(scene, Options("newmark", "newton", 0.1));
  EXPECT_THROW(RunMeasured(again, RunOptions{}, ErrorMeasure::kMaxPosition, &end_only), InputError);
  EXPECT_THROW(RunMeasured(again, RunOptions{}, ErrorMeasure::kPosition, nullptr), InputError);
  const MeasuredRun energy = RunMeasured(again, RunOptions{}, ErrorMeasure::kEnergy, nullptr);
  EXPECT_EQ(energy.error, energy.run.max_energy_drift);
}

// A computed reference (no exact solution) records its checkpoints with the
// fine run: the last is its final state, and its own error over the
// checkpoints is at least the one at the end.
TEST(ErrorMeasure, ComputedReferenceRecordsCheckpoints) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  const Scene scene = LoadScene("spring_pendulum", load);
  ReferenceOptions options;
  options.checkpoints = 4;
  options.refinement = 4;
  const ReferenceSolution reference =
      ComputeReference(scene, SimulationOptions{}, options, 1e-3, 0.2);
  ASSERT_TRUE(reference.ok) << reference.description;
  ASSERT_EQ(reference.checkpoint_x.size(), 4u);
  EXPECT_EQ(reference.checkpoint_x.back(), reference.x);
  EXPECT_GE(reference.checkpoint_error, reference.error);
  options.checkpoints = -1;
  EXPECT_THROW(ComputeReference(scene, SimulationOptions{}, options, 1e-3, 0.2), InputError);
}

}  // namespace
}  // namespace ipstep
