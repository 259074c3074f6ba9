// The library names bad options as the library spells them,
// "options: <Struct>.<field>: ..." (docs/architecture.md "Using ipstep as a library"), never
// a program's flag: a program using ipstep as a library has no flags (the
// programs map the names to theirs, apps/flag_names.h).
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "integrators/integrator.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "sim/step_size_controller.h"
#include "solver/optimizer_options.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

// `action` throws an InputError "options: <option>: ..." that names no flag.
void ExpectOptionError(const std::function<void()>& action, const std::string& option) {
  try {
    action();
    ADD_FAILURE() << "no error for " << option;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("options: " + option + ": ", 0), 0u) << message;
    EXPECT_EQ(message.find("--"), std::string::npos) << message;
    EXPECT_EQ(message.find("flag"), std::string::npos) << message;
  }
}

OptimizerOptions With(const std::function<void(OptimizerOptions*)>& change) {
  OptimizerOptions options;
  change(&options);
  return options;
}

TEST(OptionErrors, OptimizerOptionsNameTheirField) {
  ExpectOptionError([] { ParseOptimizer("adam"); }, "OptimizerOptions.optimizer");
  const struct {
    std::function<void(OptimizerOptions*)> change;
    const char* option;
  } cases[] = {
      {[](OptimizerOptions* o) { o->tolerance = 0.0; }, "OptimizerOptions.tolerance"},
      {[](OptimizerOptions* o) { o->max_iterations = -1; }, "OptimizerOptions.max_iterations"},
      {[](OptimizerOptions* o) { o->time_limit = -1.0; }, "OptimizerOptions.time_limit"},
      {[](OptimizerOptions* o) { o->num_threads = -1; }, "OptimizerOptions.num_threads"},
      {[](OptimizerOptions* o) { o->initial_trust_region_radius = 1e300; },
       "OptimizerOptions.initial_trust_region_radius"},
      {[](OptimizerOptions* o) { o->lbfgs_rank = -1; }, "OptimizerOptions.lbfgs_rank"},
  };
  for (const auto& c : cases) {
    const OptimizerOptions options = With(c.change);
    ExpectOptionError([&options] { ValidateOptimizerOptions(options); }, c.option);
  }
  ExpectOptionError(
      [] { MakeTrustRegionOptions(With([](OptimizerOptions* o) { o->linear_solver = "MAGIC"; })); },
      "OptimizerOptions.linear_solver");
  ExpectOptionError(
      [] { MakeTrustRegionOptions(With([](OptimizerOptions* o) { o->sparse_library = "MKL"; })); },
      "OptimizerOptions.sparse_library");
  ExpectOptionError(
      [] {
        MakeTrustRegionOptions(With([](OptimizerOptions* o) { o->optimizer = Optimizer::kLbfgs; }));
      },
      "OptimizerOptions.optimizer");
  ExpectOptionError(
      [] {
        MakeLineSearchOptions(With([](OptimizerOptions* o) {
          o->optimizer = Optimizer::kLbfgs;
          o->line_search = "GOLDEN";
        }));
      },
      "OptimizerOptions.line_search");
  ExpectOptionError(
      [] {
        MakeLineSearchOptions(With([](OptimizerOptions* o) {
          o->optimizer = Optimizer::kNcg;
          o->nonlinear_cg = "DAI_YUAN";
        }));
      },
      "OptimizerOptions.nonlinear_cg");
  // L-BFGS with an Armijo line search: Ceres's own check, named by the field.
  ExpectOptionError(
      [] {
        MakeLineSearchOptions(With([](OptimizerOptions* o) {
          o->optimizer = Optimizer::kLbfgs;
          o->line_search = "ARMIJO";
        }));
      },
      "OptimizerOptions.line_search");
}

TEST(OptionErrors, IntegratorOptionsNameTheirField) {
  ExpectOptionError([] { MakeIntegrator({"rk4", 0.25, 0.5}); }, "IntegratorOptions.name");
  ExpectOptionError(
      [] {
        MakeIntegrator({"newmark", 0.0, 0.5});
      },
      "IntegratorOptions.newmark_beta");
  ExpectOptionError(
      [] {
        MakeIntegrator({"newmark", 0.25, 0.4});
      },
      "IntegratorOptions.newmark_gamma");
  // The explicit alternative is named as a value of the option.
  try {
    MakeIntegrator({"newmark", 0.0, 0.5});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("use the integrator symplectic_euler"), std::string::npos)
        << e.what();
  }
}

TEST(OptionErrors, SimulationOptionsNameTheirField) {
  const Scene scene = testing::OscillatorScene();
  SimulationOptions options;
  options.time_step = 1e9;
  ExpectOptionError([&] { Simulation sim(scene, options); }, "SimulationOptions.time_step");
  options = {};
  options.steps = 2000000000;
  ExpectOptionError([&] { Simulation sim(scene, options); }, "SimulationOptions.steps");
  // The optimizer's and integrator's options, checked when the simulation is built.
  options = {};
  options.optimizer.tolerance = -1.0;
  ExpectOptionError([&] { Simulation sim(scene, options); }, "OptimizerOptions.tolerance");
  options = {};
  options.integrator.name = "leapfrog";
  ExpectOptionError([&] { Simulation sim(scene, options); }, "IntegratorOptions.name");
}

// max_substeps is checked by the library itself, in the range its option
// table gives (sim/simulation_option_table.h), not only by --max_substeps.
TEST(OptionErrors, MaxSubstepsIsCheckedByTheLibrary) {
  const Scene scene = testing::OscillatorScene();
  for (const int substeps : {0, -3, limits::kMaxSubsteps + 1}) {
    SimulationOptions options;
    options.max_substeps = substeps;
    ExpectOptionError([&] { Simulation sim(scene, options); }, "SimulationOptions.max_substeps");
  }
  for (const int substeps : {1, limits::kMaxSubsteps}) {
    SimulationOptions options;
    options.max_substeps = substeps;
    EXPECT_NO_THROW(Simulation(scene, options)) << substeps;
  }
}

// A struct's own options are checked by their rows' ranges
// (CheckOptionRanges): a value outside the range is an error naming the field,
// whether or not it is on the sentinel's side (a negative time step is not the
// scene's time step, steps = -5 are not the scene's steps); only the sentinel
// itself means the default.
TEST(OptionErrors, OnlyTheSentinelStandsForTheDefault) {
  const Scene scene = testing::OscillatorScene();
  const struct {
    std::function<void(SimulationOptions*)> change;
    const char* option;
  } cases[] = {
      {[](SimulationOptions* o) { o->time_step = -0.01; }, "SimulationOptions.time_step"},
      {[](SimulationOptions* o) { o->steps = -5; }, "SimulationOptions.steps"},
      {[](SimulationOptions* o) { o->t_end = -1.0; }, "SimulationOptions.t_end"},
      {[](SimulationOptions* o) { o->energy_tolerance = std::nan(""); },
       "SimulationOptions.energy_tolerance"},
      {[](SimulationOptions* o) { o->energy_tolerance = -0.1; },
       "SimulationOptions.energy_tolerance"},
  };
  for (const auto& c : cases) {
    SimulationOptions options;
    c.change(&options);
    ExpectOptionError([&] { Simulation sim(scene, options); }, c.option);
  }
  SimulationOptions defaults;
  defaults.time_step = 0.0;
  defaults.steps = -1;
  defaults.t_end = 0.0;
  EXPECT_NO_THROW(Simulation(scene, defaults));

  Simulation sim(scene, SimulationOptions());
  RunOptions run;
  run.max_wall_seconds = -1.0;
  ExpectOptionError([&] { RunTrajectory(sim, run); }, "RunOptions.max_wall_seconds");

  AdaptiveOptions adaptive;
  adaptive.error_tolerance = 1e-3;
  adaptive.t_end = 1.0;
  EXPECT_NO_THROW(ValidateAdaptiveOptions(adaptive));
  adaptive.min_time_step = 1e-20;  // below the smallest time step
  ExpectOptionError([&] { ValidateAdaptiveOptions(adaptive); }, "AdaptiveOptions.min_time_step");
  adaptive.min_time_step = 0.0;
  adaptive.error_tolerance = 0.0;  // the default: none, which an adaptive run must give
  ExpectOptionError([&] { ValidateAdaptiveOptions(adaptive); }, "AdaptiveOptions.error_tolerance");
}

// Dense BFGS on 100 x 100 nodes in 3D (30,000 free degrees of freedom): the
// option's value is named with it.
TEST(OptionErrors, BfgsTooLargeNamesTheOptimizerValue) {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  load.grid_size = 100;
  const Scene scene = LoadScene("cloth_sphere", load);
  SimulationOptions options;
  options.optimizer.optimizer = Optimizer::kBfgs;
  ExpectOptionError([&] { Simulation sim(scene, options); }, "OptimizerOptions.optimizer=bfgs");
}

TEST(OptionErrors, SceneLoadOptionsNameTheirField) {
  SceneLoadOptions load;
  load.grid_size = 10;
  ExpectOptionError([&] { LoadScene("oscillator", load); }, "SceneLoadOptions.grid_size");
  load.grid_size = 1;
  ExpectOptionError([&] { LoadScene("hanging_square", load); }, "SceneLoadOptions.grid_size");
  load.grid_size = 1001;  // 1001^2 nodes: over the loader's limit
  ExpectOptionError([&] { LoadScene("hanging_square", load); }, "SceneLoadOptions.grid_size");
}

}  // namespace
}  // namespace ipstep
