// The contact effect as an object (contact/contact_effect.h): friction finds
// it whatever the order of the scene's "effects", the simulation hands it to
// the output, and without contact friction is one error naming "effects".
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "contact/contact_effect.h"
#include "core/input_error.h"
#include "energies/effect_order.h"
#include "energies/effect_registry.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"

namespace ipstep {
namespace {

Scene Slope() {
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  return LoadScene("slope", load);
}

Eigen::VectorXd RunSteps(const Scene& scene, int steps, std::vector<std::string>* summaries) {
  Simulation sim(scene, SimulationOptions{});
  for (int i = 0; i < steps; ++i) EXPECT_TRUE(sim.Step().converged) << "step " << i + 1;
  *summaries = sim.effect_summaries();
  return sim.state().x;
}

TEST(ContactEffect, FrictionBeforeContactInTheSceneIsTheSameSimulation) {
  const Scene scene = Slope();
  const auto friction = std::find(scene.effects.begin(), scene.effects.end(), "friction");
  const auto contact = std::find(scene.effects.begin(), scene.effects.end(), "contact");
  ASSERT_NE(friction, scene.effects.end());
  ASSERT_NE(contact, scene.effects.end());
  ASSERT_LT(contact, friction);
  Scene swapped = scene;
  std::iter_swap(swapped.effects.begin() + (contact - scene.effects.begin()),
                 swapped.effects.begin() + (friction - scene.effects.begin()));
  std::vector<std::string> listed, reordered;
  const Eigen::VectorXd x = RunSteps(scene, 20, &listed);
  const Eigen::VectorXd y = RunSteps(swapped, 20, &reordered);
  // Contact is built first either way: the same terms in the same order.
  EXPECT_EQ((x - y).cwiseAbs().maxCoeff(), 0.0);
  // The summaries follow the scene's order.
  ASSERT_EQ(listed.size(), reordered.size());
  const int c = static_cast<int>(contact - scene.effects.begin());
  const int f = static_cast<int>(friction - scene.effects.begin());
  EXPECT_EQ(listed[c], reordered[f]);
  EXPECT_EQ(listed[f], reordered[c]);
  EXPECT_EQ(listed[c].rfind("contact", 0), 0u) << listed[c];
  EXPECT_EQ(listed[f].rfind("friction", 0), 0u) << listed[f];
}

TEST(ContactEffect, TheSimulationFindsItAndItsObstacles) {
  const Scene scene = Slope();
  Simulation sim(scene, SimulationOptions{});
  const ContactEffect* contact = sim.FindEffect<ContactEffect>();
  ASSERT_NE(contact, nullptr);
  EXPECT_FALSE(contact->obstacles().empty());
  EXPECT_TRUE(contact->state().has_friction());
  EXPECT_EQ(sim.effects().Find("contact"), contact);
  EXPECT_EQ(sim.effects().size(), static_cast<int>(scene.effects.size()));
  // No contact: no effect.
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  Simulation oscillator(LoadScene("oscillator", load), SimulationOptions{});
  EXPECT_EQ(oscillator.FindEffect<ContactEffect>(), nullptr);
}

TEST(ContactEffect, FrictionWithoutContactNamesTheEffects) {
  Scene scene = Slope();
  scene.effects.erase(std::find(scene.effects.begin(), scene.effects.end(), "contact"));
  scene.effect_parameters.erase("contact");
  try {
    Simulation sim(scene, SimulationOptions{});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("effects: \"friction\" needs \"contact\""), std::string::npos)
        << message;
  }
}

TEST(EffectBuildOrder, AnEffectComesAfterWhatItNeedsAndACycleIsAnError) {
  const EffectFactory none = [](TermBuilder&, const nlohmann::json&) -> std::unique_ptr<Effect> {
    return std::make_unique<SummaryEffect>("");
  };
  EffectRegistry registry;
  registry.Register("a", "", none, {"b"});
  registry.Register("b", "", none);
  registry.Register("c", "", none, {"a", "unlisted"});
  EXPECT_EQ(EffectBuildOrder(registry, {"c", "a", "b"}, "s.json"),
            (std::vector<size_t>{2, 1, 0}));  // b, a, c
  EXPECT_EQ(EffectBuildOrder(registry, {"b", "c", "a"}, "s.json"),
            (std::vector<size_t>{0, 2, 1}));  // b, a, c
  EXPECT_EQ(EffectBuildOrder(registry, {"a"}, "s.json"), (std::vector<size_t>{0}));
  registry.Register("d", "", none, {"e"});
  registry.Register("e", "", none, {"d"});
  try {
    EffectBuildOrder(registry, {"b", "d", "e"}, "s.json");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("s.json: effects: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace ipstep
