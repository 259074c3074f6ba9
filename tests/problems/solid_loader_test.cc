// A scene's "solid" (problems/solid_loader.h): the "masses" key (lumped by
// default, uniform on request: equal masses, the same total) and the limits
// the solid's node masses keep.
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "problems/scene.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"

namespace ipstep {
namespace {

// The course code's section 6 square: 1 m², density 1000, 4 x 4 cells (25 nodes).
std::string Square(const std::string& extra) {
  return R"({"dimension": 2, "effects": ["elasticity"], "solid": {
    "mesh": {"shape": "rectangle", "size": [1, 1], "cells": [4, 4]},
    "youngs_modulus": 1e5, "poisson_ratio": 0.4, "density": 1000)" +
         extra + "}}";
}

// "elasticity" is a registered effect (sim/default_effects.h).
Scene Parse(const std::string& text) {
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  return ParseScene(text, "square.json", options);
}

double Total(const Scene& scene) {
  double total = 0.0;
  for (double m : scene.masses) total += m;
  return total;
}

TEST(SolidMasses, UniformGivesEveryNodeTheTotalOverTheNodeCount) {
  const Scene uniform = Parse(Square(R"(, "masses": "uniform")"));
  ASSERT_EQ(uniform.num_nodes(), 25);
  for (double m : uniform.masses) EXPECT_DOUBLE_EQ(m, 40.0);
  EXPECT_NEAR(Total(uniform), 1000.0, 1e-9);
}

TEST(SolidMasses, LumpedIsTheDefaultAndKeepsTheTotal) {
  const Scene by_default = Parse(Square(""));
  const Scene lumped = Parse(Square(R"(, "masses": "lumped")"));
  EXPECT_EQ(by_default.masses, lumped.masses);
  EXPECT_NEAR(Total(lumped), 1000.0, 1e-9);
  // Corner nodes carry less than interior ones: not uniform.
  EXPECT_LT(lumped.masses.front(), lumped.masses[12]);
}

std::string ErrorOf(const std::string& text) {
  try {
    Parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SolidMasses, BadValuesAndMassesOutsideTheLimitsAreErrors) {
  EXPECT_EQ(ErrorOf(Square(R"(, "masses": "consistent")")).rfind("square.json: solid.masses: ", 0),
            0u);
  EXPECT_EQ(ErrorOf(Square(R"(, "masses": 3)")).rfind("square.json: solid.masses: ", 0), 0u);
  const std::string tiny = ErrorOf(R"({"dimension": 2, "effects": ["elasticity"], "solid": {
    "mesh": {"shape": "rectangle", "size": [1, 1], "cells": [4, 4]},
    "youngs_modulus": 1e5, "poisson_ratio": 0.4, "density": 1e-300, "masses": "uniform"}})");
  EXPECT_EQ(tiny.rfind("square.json: solid.density: gives node 0 a mass of 4e-302 kg", 0), 0u)
      << tiny;
  const std::string huge = ErrorOf(R"({"dimension": 2, "effects": ["elasticity"], "solid": {
    "mesh": {"shape": "rectangle", "size": [1e3, 1e3], "cells": [1, 1]},
    "youngs_modulus": 1e5, "poisson_ratio": 0.4, "density": 1e11}})");
  EXPECT_NE(huge.find("solid.density: gives node 0 a mass of"), std::string::npos) << huge;
}

}  // namespace
}  // namespace ipstep
