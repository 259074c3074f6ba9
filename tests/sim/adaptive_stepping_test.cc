// Error-controlled time steps (RunOptions::adaptive, sim/step_size_controller.h):
// the global error follows the requested tolerance, the cost grows as the
// integrator's order predicts, and the contact scenes (drop, squash_square,
// cloth_sphere) take large steps in flight and small ones at the impact
// without a failed step.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/step_size_controller.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;

struct AdaptiveRun {
  RunSummary run;
  Eigen::VectorXd x;
  std::vector<StepReport> steps;
};

// An adaptive run of `scene` to t_end with the solver tolerance tied to the
// error budget, as ipstep --adaptive sets it.
AdaptiveRun RunAdaptive(const Scene& scene, const std::string& integrator, double tolerance,
                        double t_end, double first_dt, const std::string& optimizer = "newton") {
  RunOptions options;
  options.adaptive = true;
  options.adaptive_options.error_tolerance = tolerance;
  options.adaptive_options.t_end = t_end;
  options.adaptive_options.initial_time_step = first_dt;
  SimulationOptions sim_options =
      Options(integrator, optimizer, first_dt, AdaptiveSolverTolerance(options.adaptive_options));
  sim_options.accept_residual = AdaptiveStallResidual(options.adaptive_options);
  Simulation sim(scene, sim_options);
  AdaptiveRun out;
  options.after_step = [&out](const StepReport& r) { out.steps.push_back(r); };
  out.run = RunTrajectory(sim, options);
  out.x = sim.state().x;
  return out;
}

// The oscillator x'' = -(x - 1) from x = 1.1 at rest, to t = 10 s (1.6
// periods), against x = 1 + 0.1 cos t: over three decades of tolerance the
// error stays within a factor of 3 of it, and the steps grow as tol^(-1/p).
TEST(AdaptiveStepping, OscillatorErrorFollowsTheToleranceAndCostTheOrder) {
  const Scene scene = testing::OscillatorScene();
  const double t_end = 10.0;
  const double exact = 1.0 + 0.1 * std::cos(t_end);
  for (const std::string integrator : {"backward_euler", "newmark"}) {
    const int order = integrator == "newmark" ? 2 : 1;
    std::vector<int> steps;
    for (double tolerance : {1e-2, 1e-3, 1e-4, 1e-5}) {
      if (order == 1 && tolerance < 1e-4) break;  // 4.6e5 steps: slow for a test
      const AdaptiveRun r = RunAdaptive(scene, integrator, tolerance, t_end, 0.1);
      ASSERT_EQ(r.run.termination, RunTermination::kCompleted) << r.run.message;
      EXPECT_EQ(r.run.failed, 0);
      EXPECT_EQ(r.run.over_budget, 0);
      EXPECT_NEAR(r.steps.back().time, t_end, 1e-12);
      const double error = std::abs(r.x[2] - exact);
      EXPECT_LE(error, 3.0 * tolerance) << integrator << " tolerance " << tolerance;
      EXPECT_GE(error, tolerance / 10.0)
          << integrator << " tolerance " << tolerance << ": the steps are far smaller than asked";
      steps.push_back(r.run.steps_done);
    }
    // Two decades of tolerance: 100^(1/p) times the steps (within 2x).
    const double predicted = std::pow(100.0, 1.0 / order);
    const double measured = static_cast<double>(steps[2]) / steps[0];
    EXPECT_GT(measured, predicted / 2) << integrator;
    EXPECT_LT(measured, predicted * 2) << integrator;
  }
}

// The stiff spring pendulum (C = 1000, gravity 1) to t = 2 s with Newmark,
// against a fixed-step Newmark run at h = 1e-5 s.
TEST(AdaptiveStepping, SpringPendulumErrorFollowsTheTolerance) {
  const Scene scene = testing::SpringPendulumScene();
  const double t_end = 2.0;
  SimulationOptions fine = Options("newmark", "newton", 1e-5, 1e-12);
  fine.t_end = t_end;
  Simulation reference(scene, fine);
  RunTrajectory(reference);
  for (double tolerance : {1e-3, 1e-4, 1e-5}) {
    const AdaptiveRun r = RunAdaptive(scene, "newmark", tolerance, t_end, 1e-3);
    ASSERT_EQ(r.run.termination, RunTermination::kCompleted) << r.run.message;
    EXPECT_EQ(r.run.failed, 0);
    const double error = MaxNodeDistance(r.x, reference.state().x, {1}, 2);
    EXPECT_LE(error, 3.0 * tolerance) << tolerance;
    EXPECT_GE(error, tolerance / 30.0) << tolerance;
  }
}

// The built-in drop (a 1000 kg square falling 0.3 m onto the ground) with
// Newmark: free flight is exact for the trapezoidal rule, so the steps grow to
// the largest allowed (T / 10); the impact and the square's vibration take
// small ones; no step fails and none penetrates.
TEST(AdaptiveStepping, DropTakesLargeStepsInFlightAndSmallOnesAtTheImpact) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  const Scene scene = LoadScene("drop", load);
  const AdaptiveRun r = RunAdaptive(scene, "newmark", 1e-3, 1.0, 0.01);
  ASSERT_EQ(r.run.termination, RunTermination::kCompleted) << r.run.message;
  EXPECT_EQ(r.run.failed, 0);
  double flight = 0.0, impact = 1.0;
  for (const StepReport& s : r.steps) {
    EXPECT_TRUE(s.converged) << s.status;
    if (s.time < 0.25) flight = std::max(flight, s.time_step);
    if (s.time > 0.31 && s.time < 0.35) impact = std::min(impact, s.time_step);
  }
  EXPECT_GE(flight, 0.05);
  EXPECT_LE(impact, 1e-3);
  EXPECT_GT(r.run.rejected, 0);
}

// Two more contact scenes, with Newmark x projected_newton
// at E = 1 cm: `squash_square` (a neo-Hookean square on the ground, a ceiling
// descending at 0.5 m/s reaches it at t = 0.19 s; friction on both) steps at
// about 0.01 s before the ceiling touches and at a third of that when it does;
// `cloth_sphere` (a 10 x 10 node cloth falling onto a sphere from rest) takes steps
// of several centiseconds in free fall and of a millisecond or less once it
// lies on the sphere. No step fails in either.
TEST(AdaptiveStepping, SquashAndClothTakeLargeStepsBeforeContactAndSmallOnesIn) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  struct Case {
    const char* scene;
    double t_end, contact_starts, contact_ends, flight_at_least, contact_at_most;
  };
  for (const Case& c : {Case{"squash_square", 0.3, 0.19, 0.25, 6e-3, 4e-3},
                        Case{"cloth_sphere", 0.3, 0.17, 0.3, 2.5e-2, 3e-3}}) {
    const Scene scene = LoadScene(c.scene, load);
    const AdaptiveRun r =
        RunAdaptive(scene, "newmark", 1e-2, c.t_end, scene.time_step, "projected_newton");
    ASSERT_EQ(r.run.termination, RunTermination::kCompleted) << c.scene << ": " << r.run.message;
    EXPECT_EQ(r.run.failed, 0) << c.scene;
    double flight = 0.0, contact = 1.0;
    for (const StepReport& s : r.steps) {
      EXPECT_TRUE(s.converged) << c.scene << " at t = " << s.time << ": " << s.status;
      if (s.time < c.contact_starts - 0.01) flight = std::max(flight, s.time_step);
      if (s.time > c.contact_starts && s.time < c.contact_ends) {
        contact = std::min(contact, s.time_step);
      }
    }
    EXPECT_GE(flight, c.flight_at_least) << c.scene;
    EXPECT_LE(contact, c.contact_at_most) << c.scene;
  }
}

// The run reports the barrier stiffness it ended with. An adaptive kappa
// (contact/adaptive_kappa.h) follows the step, kappa_min ~ m / h^2: the drop
// without its fixed kappa = 1e5 ends at different stiffnesses for h = 0.01 s
// and 0.0025 s, so two runs at different steps simulate different barriers
// (why accuracy comparisons on contact scenes fix kappa: docs/benchmarks.md
// "Contact accuracy"); with kappa given, every run has that one.
TEST(AdaptiveStepping, ContactStiffnessIsReportedAndAnAdaptiveOneFollowsTheStep) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  Scene fixed = LoadScene("drop", load);
  Scene adaptive = fixed;
  ASSERT_EQ(adaptive.effect_parameters.at("contact").erase("kappa"), 1u);
  std::vector<double> kappas;
  for (double h : {0.01, 0.0025}) {
    for (const Scene* scene : {&fixed, &adaptive}) {
      SimulationOptions options = Options("newmark", "newton", h, 1e-5);
      options.steps = static_cast<int>(std::lround(0.4 / h));  // through the impact at 0.33 s
      Simulation sim(*scene, options);
      const RunSummary run = RunTrajectory(sim);
      ASSERT_EQ(run.termination, RunTermination::kCompleted) << run.message;
      EXPECT_EQ(run.contact_kappa_adaptive, scene == &adaptive);
      if (scene == &fixed) {
        EXPECT_EQ(run.contact_kappa, 1e5);
      } else {
        kappas.push_back(run.contact_kappa);
      }
    }
  }
  ASSERT_EQ(kappas.size(), 2u);
  EXPECT_GT(kappas[1], 4.0 * kappas[0]) << kappas[0] << " at h = 0.01 s, " << kappas[1];
  // Without contact there is no stiffness to report.
  Simulation free_fall(testing::OscillatorScene(), Options("newmark", "newton", 0.1, 1e-5));
  const RunSummary none = RunTrajectory(free_fall);
  EXPECT_EQ(none.contact_kappa, 0.0);
  EXPECT_FALSE(none.contact_kappa_adaptive);
}

TEST(StepSizeController, AcceptsWithinBudgetRejectsAndShrinksOverIt) {
  AdaptiveOptions options;
  options.error_tolerance = 1e-3;
  options.t_end = 1.0;
  StepSizeController controller(options, 2);
  EXPECT_DOUBLE_EQ(controller.Budget(0.01), 1e-5);
  EXPECT_DOUBLE_EQ(controller.ImpactBudget(), 1.25e-4);
  const auto within = controller.Judge(0.01, 0.5e-5);
  EXPECT_TRUE(within.accept);
  EXPECT_GT(within.next_time_step, 0.01);
  const auto over = controller.Judge(0.01, 4e-5);
  EXPECT_FALSE(over.accept);
  EXPECT_NEAR(over.next_time_step, 0.01 * 0.9 * std::pow(4.0, -0.5), 1e-15);
  // Right after a rejection the step does not grow.
  EXPECT_LE(controller.Judge(0.005, 1e-12).next_time_step, 0.005);
  // An impact's share gets the absolute budget: 1e-4 m in one step of 0.01 s.
  EXPECT_TRUE(controller.Judge(0.01, 1e-4, 1e-4, 1e-4).accept);
  EXPECT_FALSE(controller.Judge(0.01, 1e-4, 0.0, 0.0).accept);
  // A failed solve: a quarter of the step, until the smallest is reached.
  EXPECT_DOUBLE_EQ(controller.Failed(0.01).next_time_step, 0.0025);
  EXPECT_TRUE(controller.Failed(controller.min_time_step()).accept);
  EXPECT_DOUBLE_EQ(controller.max_time_step(), 0.1);
}

TEST(StepSizeController, InvalidOptionsAndIntegratorsAreInputErrors) {
  AdaptiveOptions options;
  options.t_end = 1.0;
  EXPECT_THROW(ValidateAdaptiveOptions(options), InputError);  // no tolerance
  options.error_tolerance = 1e-3;
  ValidateAdaptiveOptions(options);
  options.min_time_step = 1.0;
  options.max_time_step = 0.1;
  EXPECT_THROW(ValidateAdaptiveOptions(options), InputError);
  options.min_time_step = 0.0;
  options.max_time_step = 0.0;
  // quasi_static has no time error to control; steps are the controller's.
  Simulation sim(testing::OscillatorScene(), Options("quasi_static", "newton", 0.1));
  RunOptions run;
  run.adaptive = true;
  run.adaptive_options = options;
  EXPECT_THROW(RunTrajectory(sim, run), InputError);
  Simulation dynamic(testing::OscillatorScene(), Options("newmark", "newton", 0.1));
  run.steps = 5;
  EXPECT_THROW(RunTrajectory(dynamic, run), InputError);
}

}  // namespace
}  // namespace ipstep
