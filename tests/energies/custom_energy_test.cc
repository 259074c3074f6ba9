// A user-defined energy, written outside the library as one templated functor
// plus one registration, runs with every optimiser without touching the core.
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "energies/effect_registry.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"

namespace {

// Tether: e = k/2 |x_i - p|^2 pulls every free node towards a point p.
template <int kDim>
struct Tether {
  Tether(double stiffness, const std::array<double, 3>& point)
      : sqrt_k(std::sqrt(stiffness)), point(point) {}

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int k = 0; k < kDim; ++k) residual[k] = sqrt_k * (x[k] - point[k]);
    return true;
  }

  double sqrt_k;
  std::array<double, 3> point;
};

std::string BuildTether(ipstep::TermBuilder& builder, const nlohmann::json& parameters) {
  const std::string where = builder.scene().source;
  if (!parameters.is_object() || !parameters.contains("stiffness") ||
      !parameters["stiffness"].is_number() || parameters["stiffness"].get<double>() <= 0.0) {
    throw ipstep::InputError(where, "tether.stiffness", "must be a number > 0");
  }
  const double k = parameters["stiffness"].get<double>();
  std::array<double, 3> point = {0.0, 0.0, 0.0};
  int count = 0;
  for (int i = 0; i < builder.state().num_nodes(); ++i) {
    if (!builder.state().is_free(i)) continue;
    builder.AddAutoDiff<Tether, ipstep::kOneResidualPerCoordinate, 1>(ipstep::TermKind::kPotential,
                                                                      {i}, k, point);
    ++count;
  }
  return "tether: " + std::to_string(count) + " terms";
}

// The program's own registry: the defaults plus the tether (the default
// registry itself is immutable).
const ipstep::EffectRegistry& Effects() {
  static const ipstep::EffectRegistry* const effects = [] {
    auto* registry = new ipstep::EffectRegistry(ipstep::MakeDefaultEffects());
    registry->Register("tether", "pull free nodes to the origin", BuildTether);
    return registry;
  }();
  return *effects;
}

ipstep::Scene TetheredParticle(int dimension) {
  ipstep::Scene s;
  s.name = s.source = "tethered_particle";
  s.dimension = dimension;
  s.positions.assign(dimension, 0.0);
  s.positions[0] = 0.3;
  s.velocities.assign(dimension, 0.0);
  s.masses = {2.0};
  s.effects = {"tether"};
  s.effect_parameters["tether"] = {{"stiffness", 8.0}};  // omega = 2
  return s;
}

TEST(CustomEnergy, RegisteredEnergyRunsWithEveryOptimizer) {
  for (int dimension : {2, 3}) {
    for (const char* optimizer : {"newton", "dogleg", "lbfgs", "bfgs", "ncg", "gradient_descent"}) {
      ipstep::SimulationOptions options;
      options.effects = &Effects();
      options.integrator.name = "backward_euler";
      options.optimizer.optimizer = ipstep::ParseOptimizer(optimizer);
      // Newton's first step is exact on this quadratic; the others need a tolerance
      // above the precision floor of their cost-based acceptance tests.
      options.optimizer.tolerance = std::string(optimizer) == "newton" ? 1e-12 : 1e-8;
      const double h = 0.1, omega_h = 2.0 * h;
      options.time_step = h;
      ipstep::Simulation sim(TetheredParticle(dimension), options);
      ASSERT_EQ(sim.effect_summaries().size(), 1u);
      EXPECT_EQ(sim.effect_summaries()[0], "tether: 1 terms");
      double previous = sim.Energies().total();
      EXPECT_NEAR(previous, 0.5 * 8.0 * 0.09, 1e-15);
      for (int step = 0; step < 10; ++step) {
        const ipstep::StepReport r = sim.Step();
        ASSERT_TRUE(r.converged) << optimizer << ": " << r.status;
        // The backward Euler law of a harmonic oscillator.
        EXPECT_NEAR(r.energies.total() / previous, 1.0 / (1.0 + omega_h * omega_h), 1e-6)
            << optimizer;
        previous = r.energies.total();
      }
    }
  }
}

TEST(CustomEnergy, TheSceneOfDocsNewEnergyLoadsAndRuns) {
  // The scene printed in docs/new_energy.md, verbatim.
  const char* text = R"({
  "effects": ["tether"],
  "tether": {"stiffness": 8.0},
  "particle": {"position": [0.3, 0.0], "mass": 2.0}
})";
  ipstep::SceneLoadOptions load;
  load.extra_effects = Effects().UserNames();
  const ipstep::Scene scene = ipstep::ParseScene(std::string(text), "docs/new_energy.md", load);
  ipstep::SimulationOptions options;
  options.effects = &Effects();
  options.time_step = 0.1;
  ipstep::Simulation sim(scene, options);
  EXPECT_NEAR(sim.Energies().total(), 0.5 * 8.0 * 0.09, 1e-15);
  EXPECT_TRUE(sim.Step().converged);
  // Without the effect listed, the parameters are an error.
  const std::string unlisted =
      R"({"tether": {"stiffness": 8.0}, "particle": {"position": [0, 0], "mass": 1}})";
  EXPECT_THROW(ipstep::ParseScene(unlisted, "unlisted", load), ipstep::InputError);
}

TEST(CustomEnergy, ItsParameterErrorsAreInputErrors) {
  ipstep::Scene scene = TetheredParticle(2);
  scene.effect_parameters["tether"] = {{"stiffness", -1.0}};
  ipstep::SimulationOptions options;
  options.effects = &Effects();
  options.time_step = 0.1;
  EXPECT_THROW({ ipstep::Simulation sim(scene, options); }, ipstep::InputError);
}

}  // namespace
