#include "problems/scene_loader.h"
#include "energies/effect_registry.h"
#include "sim/default_effects.h"

#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "core/input_error.h"

namespace ipstep {
namespace {

using nlohmann::json;

constexpr char kSource[] = "test_scene.json";

// Runs `load` and returns the InputError's message ("" and a test failure if
// nothing or something else was thrown).
std::string InputErrorOf(const std::function<void()>& load) {
  try {
    load();
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    ADD_FAILURE() << "expected InputError, got: " << error.what();
    return "";
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return "";
}

std::string ErrorOfText(const std::string& text, const SceneLoadOptions& options = {}) {
  return InputErrorOf([&] { ParseScene(text, kSource, options); });
}

std::string ErrorOf(const json& scene, const SceneLoadOptions& options = {}) {
  return ErrorOfText(scene.dump(), options);
}

// The message names the source and the key path, and says what is wrong.
void ExpectMessage(const std::string& message, const std::string& key, const std::string& what) {
  EXPECT_NE(message.find(std::string(kSource) + ": "), std::string::npos) << message;
  EXPECT_NE(message.find(key), std::string::npos) << "no \"" << key << "\" in: " << message;
  EXPECT_NE(message.find(what), std::string::npos) << "no \"" << what << "\" in: " << message;
}

// A small valid scene: two nodes joined by a spring, under gravity.
json TwoNodes() {
  return json::parse(R"({
    "effects": ["gravity", "springs"],
    "gravity": [0, -9.81],
    "nodes": {
      "positions": [[0, 0], [2, 0]],
      "velocities": [[0, 0], [0, 1]],
      "masses": [1, 0.5]
    },
    "springs": [{"nodes": [0, 1], "model": "hookean", "stiffness": 10}],
    "pinned": [0]
  })");
}

// A grid with only the spring families in `families`.
json Grid(int nx, int ny, const std::vector<std::string>& families) {
  json scene = {{"effects", json::array()},
                {"grid", {{"nx", nx}, {"ny", ny}, {"width", 3}, {"height", 2}, {"mass", 1}}}};
  if (!families.empty()) scene["effects"] = {"springs"};
  for (const std::string& family : families) {
    scene["grid"][family] = {{"model", "hookean"}, {"stiffness", 5}};
  }
  return scene;
}

std::vector<double> PositionOf(const Scene& scene, int node) {
  return std::vector<double>(scene.positions.begin() + scene.dimension * node,
                             scene.positions.begin() + scene.dimension * (node + 1));
}

std::vector<double> VelocityOf(const Scene& scene, int node) {
  return std::vector<double>(scene.velocities.begin() + scene.dimension * node,
                             scene.velocities.begin() + scene.dimension * (node + 1));
}

// ---- Built-in scenes ------------------------------------------------------

TEST(BuiltinScenesTest, NamesAndTexts) {
  EXPECT_EQ(
      BuiltinSceneNames(),
      (std::set<std::string>{
          "cloth", "cloth_box", "cloth_sphere", "drop", "fpu", "hanging_square", "impact",
          "oscillator", "slope", "spring_pendulum", "squeeze", "two_squares",
          // elastic solids (tests/energies/elasticity_test.cc)
          "ball_drop_3d", "ball_impact_3d", "cantilever_2d", "squash_square", "twisted_bar_3d"}));
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();  // contact, friction
  for (const std::string& name : BuiltinSceneNames()) {
    EXPECT_TRUE(IsBuiltinScene(name));
    EXPECT_FALSE(BuiltinSceneText(name).empty());
    const Scene scene = LoadScene(name, options);
    EXPECT_EQ(scene.name, name);
    EXPECT_EQ(scene.source, "problems/" + name + ".json");
    EXPECT_EQ(scene.positions.size(), scene.velocities.size());
    EXPECT_EQ(scene.positions.size(), scene.masses.size() * scene.dimension);
  }
  EXPECT_FALSE(IsBuiltinScene("no_such_scene"));
}

TEST(BuiltinScenesTest, Oscillator) {
  const Scene scene = LoadScene("oscillator");
  EXPECT_EQ(scene.dimension, 2);
  ASSERT_EQ(scene.num_nodes(), 2);
  EXPECT_EQ(scene.positions, (std::vector<double>{0, 0, 1.1, 0}));
  EXPECT_EQ(scene.velocities, (std::vector<double>{0, 0, 0, 0}));
  EXPECT_EQ(scene.masses, (std::vector<double>{1, 1}));
  ASSERT_EQ(scene.springs.size(), 1u);
  EXPECT_EQ(scene.springs[0].i, 0);
  EXPECT_EQ(scene.springs[0].j, 1);
  EXPECT_EQ(scene.springs[0].model, SpringModel::kHookean);
  EXPECT_EQ(scene.springs[0].stiffness, 1.0);
  EXPECT_EQ(scene.springs[0].rest_length, 1.0);
  EXPECT_EQ(scene.pinned, (std::vector<int>{0}));
  EXPECT_TRUE(scene.moving.empty());
  EXPECT_TRUE(scene.gravity.empty());
  EXPECT_EQ(scene.effects, (std::vector<std::string>{"springs"}));
  EXPECT_EQ(scene.time_step, 0.1);
  EXPECT_EQ(scene.steps, 100);
}

TEST(BuiltinScenesTest, SpringPendulum) {
  const Scene scene = LoadScene("spring_pendulum");
  ASSERT_EQ(scene.num_nodes(), 2);
  EXPECT_EQ(scene.positions, (std::vector<double>{0, 0, 0.9, 0.1}));
  EXPECT_EQ(scene.velocities, (std::vector<double>{0, 0, 0, 0}));
  EXPECT_EQ(scene.masses[1], 1.0);
  ASSERT_EQ(scene.springs.size(), 1u);
  EXPECT_EQ(scene.springs[0].model, SpringModel::kHookean);
  EXPECT_EQ(scene.springs[0].stiffness, 1000.0);
  EXPECT_EQ(scene.springs[0].rest_length, 1.0);
  EXPECT_EQ(scene.pinned, (std::vector<int>{0}));
  EXPECT_EQ(scene.gravity, (std::vector<double>{0, -1}));
  EXPECT_EQ(scene.effects, (std::vector<std::string>{"gravity", "springs"}));
  EXPECT_EQ(scene.time_step, 0.001);
  EXPECT_EQ(scene.steps, 1000);
}

TEST(BuiltinScenesTest, Cloth) {
  const Scene scene = LoadScene("cloth");
  EXPECT_EQ(scene.dimension, 2);
  ASSERT_EQ(scene.num_nodes(), 400);
  for (double mass : scene.masses) EXPECT_DOUBLE_EQ(mass, 1.0 / 400);
  // Structural (2 * 19 * 20) + shear (2 * 19 * 19) springs.
  EXPECT_EQ(scene.springs.size(), 760u + 722u);
  for (const Spring& spring : scene.springs) {
    EXPECT_EQ(spring.model, SpringModel::kHookean);
    EXPECT_EQ(spring.stiffness, 1e4);
  }
  EXPECT_EQ(scene.pinned, (std::vector<int>{0, 19}));
  EXPECT_EQ(PositionOf(scene, 0), (std::vector<double>{-0.5, 0}));
  EXPECT_EQ(PositionOf(scene, 19), (std::vector<double>{0.5, 0}));
  EXPECT_EQ(PositionOf(scene, 399), (std::vector<double>{0.5, -1}));
  for (double v : scene.velocities) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(scene.gravity, (std::vector<double>{0, -9.81}));
  EXPECT_EQ(scene.effects, (std::vector<std::string>{"gravity", "springs"}));
  EXPECT_EQ(scene.time_step, 1.0 / 60);
  EXPECT_EQ(scene.steps, 60);
}

// The course code's section 2 square: n_seg = 4 (5 x 5 nodes), rho = 1000 kg/m^2
// spread evenly (m = rho side^2 / (n_seg + 1)^2), k = 1e3 on edges and both
// diagonals, the top corners pinned, h = 0.02.
TEST(BuiltinScenesTest, HangingSquare) {
  for (int n : {0, 41}) {
    SceneLoadOptions options;
    options.grid_size = n;
    const Scene scene = LoadScene("hanging_square", options);
    const int nodes = n == 0 ? 5 : n;
    ASSERT_EQ(scene.num_nodes(), nodes * nodes);
    for (double mass : scene.masses) EXPECT_DOUBLE_EQ(mass, 1000.0 / (nodes * nodes));
    // Structural 2 (n - 1) n + shear 2 (n - 1)^2.
    EXPECT_EQ(static_cast<int>(scene.springs.size()),
              2 * (nodes - 1) * nodes + 2 * (nodes - 1) * (nodes - 1));
    for (const Spring& spring : scene.springs) {
      EXPECT_EQ(spring.model, SpringModel::kSquaredStrain);
      EXPECT_EQ(spring.stiffness, 1e3);
    }
    EXPECT_EQ(scene.pinned, (std::vector<int>{0, nodes - 1}));
    EXPECT_EQ(PositionOf(scene, 0), (std::vector<double>{-0.5, 0.5}));
    EXPECT_EQ(PositionOf(scene, nodes * nodes - 1), (std::vector<double>{0.5, -0.5}));
    EXPECT_EQ(scene.time_step, 0.02);
    EXPECT_EQ(scene.gravity, (std::vector<double>{0, -9.81}));
  }
}

// Hairer, Lubich & Wanner, GNI I.5.1: x0_i = (q_2i + q_2i-1) / sqrt 2,
// x1_i = (q_2i - q_2i-1) / sqrt 2 (momenta y likewise), with x0_1 = y0_1 = 1,
// x1_1 = 1 / omega, y1_1 = 1 and all others 0; omega = 50.
TEST(BuiltinScenesTest, FermiPastaUlam) {
  const Scene scene = LoadScene("fpu");
  const double omega = 50;
  ASSERT_EQ(scene.num_nodes(), 8);
  EXPECT_EQ(scene.pinned, (std::vector<int>{0, 7}));
  for (double mass : scene.masses) EXPECT_EQ(mass, 1.0);
  ASSERT_EQ(scene.springs.size(), 7u);
  for (int s = 0; s < 7; ++s) {
    const Spring& spring = scene.springs[s];
    EXPECT_EQ(spring.i, s);
    EXPECT_EQ(spring.j, s + 1);
    EXPECT_EQ(spring.rest_length, 10.0);
    if (s % 2 == 0) {
      EXPECT_EQ(spring.model, SpringModel::kQuartic);
      EXPECT_EQ(spring.stiffness, 1.0);
    } else {
      EXPECT_EQ(spring.model, SpringModel::kHookean);
      EXPECT_EQ(spring.stiffness, omega * omega / 2);
    }
  }
  std::vector<double> q(8), p(8);
  for (int i = 0; i < 8; ++i) {
    q[i] = scene.positions[2 * i] - 10.0 * i;
    p[i] = scene.velocities[2 * i];
    EXPECT_EQ(scene.positions[2 * i + 1], 0.0);
    EXPECT_EQ(scene.velocities[2 * i + 1], 0.0);
  }
  EXPECT_EQ(q[0], 0.0);
  EXPECT_EQ(q[7], 0.0);
  const double sqrt2 = std::sqrt(2.0);
  for (int i = 1; i <= 3; ++i) {
    const double x0 = (q[2 * i] + q[2 * i - 1]) / sqrt2;
    const double x1 = (q[2 * i] - q[2 * i - 1]) / sqrt2;
    const double y0 = (p[2 * i] + p[2 * i - 1]) / sqrt2;
    const double y1 = (p[2 * i] - p[2 * i - 1]) / sqrt2;
    EXPECT_NEAR(x0, i == 1 ? 1.0 : 0.0, 1e-14) << i;
    EXPECT_NEAR(x1, i == 1 ? 1.0 / omega : 0.0, 1e-14) << i;
    EXPECT_NEAR(y0, i == 1 ? 1.0 : 0.0, 1e-15) << i;
    EXPECT_NEAR(y1, i == 1 ? 1.0 : 0.0, 1e-15) << i;
  }
  EXPECT_EQ(scene.effects, (std::vector<std::string>{"springs"}));
  EXPECT_NEAR(scene.time_step * scene.steps, 10.0, 1e-12);
}

// ---- Generators -----------------------------------------------------------

TEST(GridTest, SpringFamilyCounts) {
  for (const auto& [nx, ny] : std::vector<std::pair<int, int>>{{2, 2}, {3, 4}, {5, 2}, {6, 7}}) {
    SCOPED_TRACE(std::to_string(nx) + " x " + std::to_string(ny));
    const size_t structural = (nx - 1) * ny + nx * (ny - 1);
    const size_t shear = 2 * (nx - 1) * (ny - 1);
    const size_t bending = (nx - 2) * ny + nx * (ny - 2);
    EXPECT_EQ(ParseScene(Grid(nx, ny, {"structural"}), kSource).springs.size(), structural);
    EXPECT_EQ(ParseScene(Grid(nx, ny, {"shear"}), kSource).springs.size(), shear);
    if (bending > 0) {
      EXPECT_EQ(ParseScene(Grid(nx, ny, {"bending"}), kSource).springs.size(), bending);
    }
    const Scene all = ParseScene(Grid(nx, ny, {"structural", "shear", "bending"}), kSource);
    EXPECT_EQ(all.springs.size(), structural + shear + bending);
    EXPECT_EQ(all.num_nodes(), nx * ny);
  }
}

TEST(GridTest, LayoutAndRestLengths) {
  const Scene scene = ParseScene(Grid(4, 3, {"structural", "shear", "bending"}), kSource);
  // Row 0 is the top row at the origin; columns go along +x, rows along -y.
  EXPECT_EQ(PositionOf(scene, 0), (std::vector<double>{0, 0}));
  EXPECT_EQ(PositionOf(scene, 3), (std::vector<double>{3, 0}));
  EXPECT_EQ(PositionOf(scene, 4), (std::vector<double>{0, -1}));
  EXPECT_EQ(PositionOf(scene, 11), (std::vector<double>{3, -2}));
  for (const Spring& spring : scene.springs) {
    const std::vector<double> a = PositionOf(scene, spring.i);
    const std::vector<double> b = PositionOf(scene, spring.j);
    EXPECT_DOUBLE_EQ(spring.rest_length, std::hypot(b[0] - a[0], b[1] - a[1]));
    EXPECT_EQ(spring.stiffness, 5.0);
  }
}

TEST(GridTest, PlanesIn3d) {
  json scene = Grid(2, 2, {});
  scene["dimension"] = 3;
  scene["effects"] = json::array();
  scene["grid"]["origin"] = {1, 2, 3};
  scene["grid"]["plane"] = "xz";
  Scene xz = ParseScene(scene, kSource);
  EXPECT_EQ(PositionOf(xz, 3), (std::vector<double>{4, 2, 1}));
  scene["grid"]["plane"] = "yz";
  EXPECT_EQ(PositionOf(ParseScene(scene, kSource), 3), (std::vector<double>{1, 5, 1}));
  scene["grid"].erase("plane");
  EXPECT_EQ(PositionOf(ParseScene(scene, kSource), 3), (std::vector<double>{4, 0, 3}));
}

TEST(GridTest, GridSizeOverrideKeepsSymbolicPinsAtCorners) {
  SceneLoadOptions options;
  options.grid_size = 5;
  const Scene scene = LoadScene("cloth", options);
  ASSERT_EQ(scene.num_nodes(), 25);
  EXPECT_EQ(scene.pinned, (std::vector<int>{0, 4}));
  EXPECT_EQ(PositionOf(scene, 0), (std::vector<double>{-0.5, 0}));
  EXPECT_EQ(PositionOf(scene, 4), (std::vector<double>{0.5, 0}));
  EXPECT_EQ(PositionOf(scene, 24), (std::vector<double>{0.5, -1}));
  for (double mass : scene.masses) EXPECT_DOUBLE_EQ(mass, 1.0 / 25);  // total_mass 1
  EXPECT_EQ(scene.springs.size(), 2u * 4 * 5 + 2u * 4 * 4);
  for (const Spring& spring : scene.springs) EXPECT_GT(spring.rest_length, 0.24);
}

TEST(GridTest, SymbolicRowsAndColumns) {
  json scene = Grid(3, 4, {"structural"});
  scene["pinned"] = {"right_column", "bottom_left"};
  scene["moving"] = {{{"node", "top_left"}, {"velocity", {1, 0}}}};
  Scene parsed = ParseScene(scene, kSource);
  EXPECT_EQ(parsed.pinned, (std::vector<int>{2, 5, 8, 11, 9}));
  ASSERT_EQ(parsed.moving.size(), 1u);
  EXPECT_EQ(parsed.moving[0].node, 0);

  scene["pinned"] = {"top_row"};
  scene["moving"] = {{{"node", "bottom_row"}, {"velocity", {0, -1}}}};
  parsed = ParseScene(scene, kSource);
  EXPECT_EQ(parsed.pinned, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(parsed.moving.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(parsed.moving[k].node, 9 + k);
    EXPECT_EQ(VelocityOf(parsed, 9 + k), (std::vector<double>{0, -1}));
  }

  scene["pinned"] = {"left_column", "bottom_right"};
  scene.erase("moving");
  EXPECT_EQ(ParseScene(scene, kSource).pinned, (std::vector<int>{0, 3, 6, 9, 11}));
}

// A rotating moving entry (core/prescribed_motion.h): its motion, the nodes'
// initial velocity v + ω × (x0 − c), and its errors.
TEST(GridTest, RotatingMovingNodes) {
  json scene = Grid(3, 3, {"structural"});
  scene["moving"] = {{{"node", "top_right"},
                      {"velocity", {0.5, 0}},
                      {"angular_velocity", 2.0},
                      {"center", {0, 0}},
                      {"until", 1.5}}};
  Scene parsed = ParseScene(scene, kSource);
  ASSERT_EQ(parsed.moving.size(), 1u);
  const MovingNode& m = parsed.moving[0];
  EXPECT_EQ(m.angular_velocity, (std::vector<double>{2.0}));
  EXPECT_EQ(m.center, (std::vector<double>{0, 0}));
  EXPECT_EQ(m.until, 1.5);
  const std::vector<double> x0 = PositionOf(parsed, m.node);
  // ω ẑ × (x, y) = ω (−y, x).
  EXPECT_EQ(VelocityOf(parsed, m.node), (std::vector<double>{0.5 - 2.0 * x0[1], 2.0 * x0[0]}));

  scene["moving"] = {{{"node", 0}, {"angular_velocity", 1.0}}};
  ExpectMessage(ErrorOf(scene), "moving[0].center", "required key is missing");
  scene["moving"] = {{{"node", 0}, {"velocity", {1, 0}}, {"center", {0, 0}}}};
  ExpectMessage(ErrorOf(scene), "moving[0].center", "has no effect");
  scene["moving"] = {{{"node", 0}, {"until", 1.0}}};
  ExpectMessage(ErrorOf(scene), "moving[0]", "needs \"velocity\", \"angular_velocity\"");
  scene["moving"] = {{{"node", 0}, {"velocity", {1, 0}}, {"until", 0.0}}};
  ExpectMessage(ErrorOf(scene), "moving[0].until", "must be in (0");
  scene["moving"] = {{{"node", 0}, {"angular_velocity", {1, 0, 0}}, {"center", {0, 0}}}};
  ExpectMessage(ErrorOf(scene), "moving[0].angular_velocity", "");
}

TEST(GridTest, MassFromDensityAndTotalMass) {
  json scene = Grid(3, 3, {});
  scene["effects"] = json::array();
  scene["grid"].erase("mass");
  scene["grid"]["density"] = 2;  // kg/m^2 over 3 m x 2 m
  for (double mass : ParseScene(scene, kSource).masses) EXPECT_DOUBLE_EQ(mass, 2.0 * 6 / 9);
  scene["grid"].erase("density");
  scene["grid"]["total_mass"] = 4.5;
  for (double mass : ParseScene(scene, kSource).masses) EXPECT_DOUBLE_EQ(mass, 0.5);
}

TEST(ChainTest, NodesSpringsAndMass) {
  const json scene = json::parse(R"({
    "dimension": 3,
    "effects": ["springs"],
    "chain": {"count": 5, "from": [0, 0, 0], "to": [0, 0, -2], "density": 3,
              "spring": {"model": "squared_strain", "stiffness": 7}},
    "pinned": ["first"],
    "moving": [{"node": "last", "velocity": [0, 0, 1]}]
  })");
  const Scene chain = ParseScene(scene, kSource);
  ASSERT_EQ(chain.num_nodes(), 5);
  EXPECT_EQ(PositionOf(chain, 2), (std::vector<double>{0, 0, -1}));
  for (double mass : chain.masses) EXPECT_DOUBLE_EQ(mass, 3.0 * 2 / 5);
  ASSERT_EQ(chain.springs.size(), 4u);
  for (const Spring& spring : chain.springs) {
    EXPECT_EQ(spring.j, spring.i + 1);
    EXPECT_EQ(spring.model, SpringModel::kSquaredStrain);
    EXPECT_DOUBLE_EQ(spring.rest_length, 0.5);
  }
  EXPECT_EQ(chain.pinned, (std::vector<int>{0}));
  ASSERT_EQ(chain.moving.size(), 1u);
  EXPECT_EQ(chain.moving[0].node, 4);
  EXPECT_EQ(chain.moving[0].velocity, (std::vector<double>{0, 0, 1}));
  EXPECT_EQ(VelocityOf(chain, 4), (std::vector<double>{0, 0, 1}));
}

TEST(ParticleTest, SingleNode) {
  const std::string text =
      R"({"particle": {"position": [1, 2], "mass": 3, "velocity": [4, 5]}, "steps": 0})";
  const Scene scene = ParseScene(text, kSource);
  EXPECT_EQ(scene.name, "test_scene");
  EXPECT_EQ(scene.positions, (std::vector<double>{1, 2}));
  EXPECT_EQ(scene.velocities, (std::vector<double>{4, 5}));
  EXPECT_EQ(scene.masses, (std::vector<double>{3}));
  EXPECT_EQ(scene.steps, 0);
  EXPECT_TRUE(scene.effects.empty());
}

// ---- Explicit nodes, springs and conditions --------------------------------

TEST(SceneTest, ExplicitNodesAndDefaults) {
  const Scene scene = ParseScene(TwoNodes(), kSource);
  EXPECT_EQ(scene.name, "test_scene");  // the source's file stem
  EXPECT_EQ(scene.source, kSource);
  EXPECT_EQ(scene.dimension, 2);
  EXPECT_EQ(scene.time_step, 0.01);
  EXPECT_EQ(scene.steps, 100);
  EXPECT_EQ(scene.masses, (std::vector<double>{1, 0.5}));
  EXPECT_EQ(scene.velocities, (std::vector<double>{0, 0, 0, 1}));
  ASSERT_EQ(scene.springs.size(), 1u);
  EXPECT_EQ(scene.springs[0].rest_length, 2.0);  // the initial length
  EXPECT_EQ(scene.damping.mass_proportional, 0.0);
  EXPECT_EQ(scene.damping.stiffness_proportional, 0.0);
}

TEST(SceneTest, ExplicitRestLengthAndName) {
  json scene = TwoNodes();
  scene["name"] = "custom";
  scene["springs"][0]["rest_length"] = 1.5;
  const Scene parsed = ParseScene(scene, kSource);
  EXPECT_EQ(parsed.name, "custom");
  EXPECT_EQ(parsed.springs[0].rest_length, 1.5);
}

TEST(SceneTest, ExplicitMassesFromMassOrTotalMass) {
  json scene = TwoNodes();
  scene["nodes"].erase("masses");
  scene["nodes"]["mass"] = 2;
  EXPECT_EQ(ParseScene(scene, kSource).masses, (std::vector<double>{2, 2}));
  scene["nodes"].erase("mass");
  scene["nodes"]["total_mass"] = 3;
  EXPECT_EQ(ParseScene(scene, kSource).masses, (std::vector<double>{1.5, 1.5}));
}

TEST(SceneTest, InitialVelocityAndBoundaryConditions) {
  json scene = TwoNodes();
  scene["nodes"] = {{"positions", {{0, 0}, {2, 0}, {4, 0}, {6, 0}}}, {"mass", 1}};
  scene["springs"].push_back({{"nodes", {2, 3}}, {"model", "quartic"}, {"stiffness", 2}});
  scene["initial_velocity"] = {3, 0};
  scene["moving"] = {{{"node", 3}, {"velocity", {0, -1}}}};
  const Scene parsed = ParseScene(scene, kSource);
  EXPECT_EQ(VelocityOf(parsed, 0), (std::vector<double>{0, 0}));   // pinned
  EXPECT_EQ(VelocityOf(parsed, 1), (std::vector<double>{3, 0}));   // uniform
  EXPECT_EQ(VelocityOf(parsed, 2), (std::vector<double>{3, 0}));   // uniform
  EXPECT_EQ(VelocityOf(parsed, 3), (std::vector<double>{0, -1}));  // prescribed
  ASSERT_EQ(parsed.moving.size(), 1u);
  EXPECT_EQ(parsed.moving[0].node, 3);
  EXPECT_EQ(parsed.springs[1].model, SpringModel::kQuartic);
  EXPECT_EQ(parsed.springs[1].rest_length, 2.0);
}

TEST(SceneTest, DampingAndExtraEffects) {
  json scene = TwoNodes();
  scene["effects"] = {"gravity", "springs", "damping", "wind"};
  scene["damping"] = {{"mass_proportional", 0.1}, {"stiffness_proportional", 0.01}};
  scene["wind"] = {{"speed", 3}};
  SceneLoadOptions options;
  options.extra_effects = {"wind", "drag"};
  const Scene parsed = ParseScene(scene, kSource, options);
  EXPECT_EQ(parsed.effects, (std::vector<std::string>{"gravity", "springs", "damping", "wind"}));
  EXPECT_EQ(parsed.damping.mass_proportional, 0.1);
  EXPECT_EQ(parsed.damping.stiffness_proportional, 0.01);
  ASSERT_EQ(parsed.effect_parameters.count("wind"), 1u);
  EXPECT_EQ(parsed.effect_parameters.at("wind").at("speed"), 3);
  EXPECT_EQ(parsed.effect_parameters.count("drag"), 0u);
}

TEST(SceneTest, RegisteredEffectNamesMustNotClashWithSceneKeys) {
  SceneLoadOptions options;
  options.extra_effects = {"grid"};
  ExpectMessage(ErrorOf(TwoNodes(), options), "effects", "clashes with a scene key");
}

TEST(SceneTest, LoadsFilesByPath) {
  const std::string path = ::testing::TempDir() + "/scene_loader_test_scene.json";
  {
    std::ofstream file(path);
    file << TwoNodes().dump(2);
  }
  const Scene scene = LoadScene(path);
  EXPECT_EQ(scene.name, "scene_loader_test_scene");
  EXPECT_EQ(scene.source, path);
  EXPECT_EQ(LoadSceneFile(path).num_nodes(), 2);
  std::remove(path.c_str());
}

// ---- Bad input: one InputError naming the source and the key ----------------

TEST(BadInputTest, UnknownKeys) {
  json scene = TwoNodes();
  scene["gravty"] = 1;
  ExpectMessage(ErrorOf(scene), "gravty", "unknown key");

  scene = Grid(3, 3, {"structural"});
  scene["grid"]["widht"] = 1;
  ExpectMessage(ErrorOf(scene), "grid.widht", "unknown key");

  scene = Grid(3, 3, {"structural"});
  scene["grid"]["structural"]["k"] = 1;
  ExpectMessage(ErrorOf(scene), "grid.structural.k", "unknown key");

  scene = TwoNodes();
  scene["springs"][0]["stifness"] = 1;
  ExpectMessage(ErrorOf(scene), "springs[0].stifness", "unknown key");

  scene = TwoNodes();
  scene["nodes"]["velocity"] = {0, 0};
  ExpectMessage(ErrorOf(scene), "nodes.velocity", "unknown key");

  scene = TwoNodes();
  scene["damping"] = {{"alpha", 1}};
  scene["effects"].push_back("damping");
  ExpectMessage(ErrorOf(scene), "damping.alpha", "unknown key");
}

TEST(BadInputTest, WrongTypes) {
  json scene = TwoNodes();
  scene["time_step"] = "fast";
  ExpectMessage(ErrorOf(scene), "time_step", "must be a number");

  scene = TwoNodes();
  scene["steps"] = 10.5;
  ExpectMessage(ErrorOf(scene), "steps", "must be an integer");

  scene = TwoNodes();
  scene["effects"] = "gravity";
  ExpectMessage(ErrorOf(scene), "effects", "must be an array");

  scene = TwoNodes();
  scene["nodes"]["positions"][0] = {0, 0, 0};
  ExpectMessage(ErrorOf(scene), "nodes.positions[0]", "must be an array of 2 numbers");

  scene = TwoNodes();
  scene["nodes"]["masses"] = 1;
  ExpectMessage(ErrorOf(scene), "nodes.masses", "must be an array");

  scene = TwoNodes();
  scene["nodes"] = json::array();
  ExpectMessage(ErrorOf(scene), "nodes", "must be an object");

  scene = TwoNodes();
  scene["springs"][0]["model"] = "linear";
  ExpectMessage(ErrorOf(scene), "springs[0].model", "unknown spring model");

  scene = TwoNodes();
  scene["pinned"] = {true};
  ExpectMessage(ErrorOf(scene), "pinned[0]", "must be a node index");

  ExpectMessage(ErrorOfText(std::string("[1, 2]")), "(top level)", "must be an object");
}

TEST(BadInputTest, OutOfRangeNumbers) {
  json scene = TwoNodes();
  scene["nodes"]["masses"][1] = -1;
  ExpectMessage(ErrorOf(scene), "nodes.masses[1]", "must be in [1e-12, 1e12] kg, got -1");

  scene = TwoNodes();
  scene["springs"][0]["stiffness"] = 0;
  ExpectMessage(ErrorOf(scene), "springs[0].stiffness", "must be in (0, 1e15], got 0");

  scene = TwoNodes();
  scene["springs"][0]["rest_length"] = -0.5;
  ExpectMessage(ErrorOf(scene), "springs[0].rest_length", "must be in [1e-9, 1e7] m, got -0.5");

  scene = TwoNodes();
  scene["time_step"] = 0;
  ExpectMessage(ErrorOf(scene), "time_step", "must be in [1e-12, 1e3] s, got 0");

  scene = TwoNodes();
  scene["steps"] = -1;
  ExpectMessage(ErrorOf(scene), "steps", "got -1");

  scene = TwoNodes();
  scene["steps"] = 1e10;
  ExpectMessage(ErrorOf(scene), "steps", "must be an integer");

  ExpectMessage(
      ErrorOfText(R"({"steps": 10000000000, "particle": {"position": [0, 0], "mass": 1}})"),
      "steps", "got 10000000000");

  scene = TwoNodes();
  scene["dimension"] = 4;
  ExpectMessage(ErrorOf(scene), "dimension", "got 4");

  scene = TwoNodes();
  scene["effects"].push_back("damping");
  scene["damping"] = {{"mass_proportional", -0.1}};
  ExpectMessage(ErrorOf(scene), "damping.mass_proportional", "must be in [0, 1e12] 1/s, got -0.1");

  scene = Grid(3, 3, {});
  scene["grid"]["nx"] = 1;
  ExpectMessage(ErrorOf(scene), "grid.nx", "got 1");

  scene = Grid(3, 3, {});
  scene["grid"]["nx"] = 100000;
  scene["grid"]["ny"] = 100000;
  ExpectMessage(ErrorOf(scene), "grid", "exceeds the limit");
}

TEST(BadInputTest, HugeValues) {
  // 1e400 does not fit in a double.
  std::string text = R"({"particle": {"position": [0, 0], "mass": 1e400}})";
  ExpectMessage(ErrorOfText(text), "particle.mass", "out of the range of a double");
  text = R"({"particle": {"position": [0, -1e999], "mass": 1}})";
  ExpectMessage(ErrorOfText(text), "particle.position[1]", "out of the range of a double");

  // Programmatic JSON can hold non-finite numbers.
  json scene = TwoNodes();
  scene["nodes"]["masses"][1] = std::numeric_limits<double>::infinity();
  ExpectMessage(ErrorOfText(scene.dump()), "nodes.masses[1]", "must be a number, got null");
  ExpectMessage(InputErrorOf([&] { ParseScene(scene, kSource); }), "nodes.masses[1]",
                "must be finite, got inf");
  scene["nodes"]["masses"][1] = std::nan("");
  ExpectMessage(InputErrorOf([&] { ParseScene(scene, kSource); }), "nodes.masses[1]",
                "must be finite, got nan");

  scene = TwoNodes();
  scene["nodes"]["positions"] = {{-1e308, 0}, {1e308, 0}};
  ExpectMessage(ErrorOf(scene), "nodes.positions[0][0]", "must be in [-1e6, 1e6] m, got -1e+308");

  scene = Grid(3, 3, {});
  scene["grid"]["width"] = 1e308;
  scene["grid"]["origin"] = {1e308, 0};
  ExpectMessage(ErrorOf(scene), "grid.origin[0]", "must be in [-1e6, 1e6] m");
  scene["grid"]["origin"] = {0, 0};
  ExpectMessage(ErrorOf(scene), "grid", "outside [-1e6, 1e6] m");

  scene = Grid(3, 3, {});
  scene["grid"].erase("mass");
  scene["grid"]["density"] = 1e300;
  scene["grid"]["width"] = 1e300;
  ExpectMessage(ErrorOf(scene), "grid.density", "gives each node a mass of inf kg");
}

// Finite but overflowing values are rejected at load with the key and the
// documented range (core/input_limits.h, docs/scenes.md "Validation"); they
// used to load and give inf/NaN energies later.
TEST(BadInputTest, PhysicalRanges) {
  json scene = TwoNodes();
  scene["gravity"] = {0, -1e200};
  ExpectMessage(ErrorOf(scene), "gravity[1]", "must be in [-1e6, 1e6] m/s^2, got -1e+200");

  scene = TwoNodes();
  scene["nodes"].erase("velocities");
  scene["initial_velocity"] = {1e308, 0};
  ExpectMessage(ErrorOf(scene), "initial_velocity[0]", "must be in [-1e6, 1e6] m/s");
  scene = TwoNodes();
  scene["nodes"]["velocities"][1] = {0, 2e6};
  ExpectMessage(ErrorOf(scene), "nodes.velocities[1][1]", "must be in [-1e6, 1e6] m/s");
  scene = TwoNodes();
  scene["pinned"] = json::array();
  scene["nodes"]["velocities"][0] = {0, 0};
  scene["moving"] = {{{"node", 0}, {"velocity", {1e300, 0}}}};
  ExpectMessage(ErrorOf(scene), "moving[0].velocity[0]", "must be in [-1e6, 1e6] m/s");

  scene = TwoNodes();
  scene["springs"][0]["stiffness"] = 1e308;
  ExpectMessage(ErrorOf(scene), "springs[0].stiffness", "must be in (0, 1e15], got 1e+308");
  scene = Grid(3, 3, {"shear"});
  scene["grid"]["shear"]["stiffness"] = 1e16;
  ExpectMessage(ErrorOf(scene), "grid.shear.stiffness", "must be in (0, 1e15]");

  scene = TwoNodes();
  scene["time_step"] = 5e-324;
  ExpectMessage(ErrorOf(scene), "time_step", "must be in [1e-12, 1e3] s");
  scene["time_step"] = 1e4;
  ExpectMessage(ErrorOf(scene), "time_step", "must be in [1e-12, 1e3] s, got 1e+04");
  scene = TwoNodes();
  scene["steps"] = 10000001;
  ExpectMessage(ErrorOf(scene), "steps", "must be an integer in [0, 10000000]");

  scene = TwoNodes();
  scene["nodes"]["masses"] = {1, 1e-320};
  ExpectMessage(ErrorOf(scene), "nodes.masses[1]", "must be in [1e-12, 1e12] kg");
  scene = TwoNodes();
  scene["nodes"].erase("masses");
  scene["nodes"]["mass"] = 1e13;
  ExpectMessage(ErrorOf(scene), "nodes.mass", "must be in [1e-12, 1e12] kg");
  scene = Grid(3, 3, {});
  scene["grid"].erase("mass");
  scene["grid"]["total_mass"] = 1e-12;  // 1/9 of it per node
  ExpectMessage(ErrorOf(scene), "grid.total_mass", "in [1e-12, 1e12] kg");
  scene = Grid(3, 3, {});
  scene["grid"].erase("mass");
  scene["grid"]["density"] = 1e300;
  ExpectMessage(ErrorOf(scene), "grid.density", "in [1e-12, 1e12] kg");

  scene = TwoNodes();
  scene["nodes"]["positions"] = {{0, 0}, {1e300, 0}};
  ExpectMessage(ErrorOf(scene), "nodes.positions[1][0]", "must be in [-1e6, 1e6] m");
  scene = R"({"particle": {"position": [0, 0], "mass": 1}})"_json;
  scene["particle"]["position"] = {0, -2e6};
  ExpectMessage(ErrorOf(scene), "particle.position[1]", "must be in [-1e6, 1e6] m");
  scene = Grid(3, 3, {});
  scene["grid"]["origin"] = {1e300, 0};
  ExpectMessage(ErrorOf(scene), "grid.origin[0]", "must be in [-1e6, 1e6] m");
  scene = Grid(3, 3, {});
  scene["grid"]["width"] = 1e300;
  ExpectMessage(ErrorOf(scene), "grid", "outside [-1e6, 1e6] m");

  scene = TwoNodes();
  scene["springs"][0]["rest_length"] = 1e-300;
  ExpectMessage(ErrorOf(scene), "springs[0].rest_length", "must be in [1e-9, 1e7] m");
  scene = TwoNodes();
  scene["nodes"]["positions"] = {{0, 0}, {1e-12, 0}};
  ExpectMessage(ErrorOf(scene), "springs[0].rest_length", "[1e-9, 1e7] m");
  scene = Grid(3, 3, {"structural"});
  scene["grid"]["width"] = 1e-12;
  ExpectMessage(ErrorOf(scene), "grid.structural", "[1e-9, 1e7] m");

  scene = TwoNodes();
  scene["effects"].push_back("damping");
  scene["damping"] = {{"mass_proportional", 1e300}};
  ExpectMessage(ErrorOf(scene), "damping.mass_proportional", "must be in [0, 1e12] 1/s");
  scene["damping"] = {{"stiffness_proportional", 1e4}};
  ExpectMessage(ErrorOf(scene), "damping.stiffness_proportional", "must be in [0, 1e3] s");

  // The edges of the hard-case benchmarks load: stiff springs, small steps,
  // fast impacts, light nodes next to heavy ones.
  scene = TwoNodes();
  scene["time_step"] = 1e-6;
  scene["springs"][0]["stiffness"] = 1e8;
  scene["nodes"]["masses"] = {1e-6, 1};
  scene["nodes"]["velocities"][1] = {-1000, 0};
  scene["gravity"] = {0, -9.81};
  const Scene loaded = ParseScene(scene, kSource);
  EXPECT_EQ(loaded.masses[0], 1e-6);
  EXPECT_EQ(loaded.time_step, 1e-6);
}

TEST(BadInputTest, BadNodeIndices) {
  json scene = TwoNodes();
  scene["springs"][0]["nodes"] = {0, 2};
  ExpectMessage(ErrorOf(scene), "springs[0].nodes[1]", "out of range");

  scene = TwoNodes();
  scene["springs"][0]["nodes"] = {1, 1};
  ExpectMessage(ErrorOf(scene), "springs[0].nodes", "two different nodes");

  scene = TwoNodes();
  scene["springs"][0]["nodes"] = {0};
  ExpectMessage(ErrorOf(scene), "springs[0].nodes", "exactly 2 nodes");

  scene = TwoNodes();
  scene["pinned"] = {-1};
  ExpectMessage(ErrorOf(scene), "pinned[0]", "out of range");

  scene = TwoNodes();
  scene["pinned"] = {0, 1, 0};
  ExpectMessage(ErrorOf(scene), "pinned[2]", "already pinned by pinned[0]");

  scene = Grid(3, 3, {});
  scene["pinned"] = {"top_row", "top_left"};
  ExpectMessage(ErrorOf(scene), "pinned[1]", "already pinned by pinned[0]");

  scene = TwoNodes();
  scene["moving"] = {{{"node", 0}, {"velocity", {1, 0}}}};
  ExpectMessage(ErrorOf(scene), "moving[0].node", "both pinned and moving");

  scene = TwoNodes();
  scene["moving"] = {{{"node", 1}, {"velocity", {1, 0}}}, {{"node", 1}, {"velocity", {1, 0}}}};
  ExpectMessage(ErrorOf(scene), "moving[1].node", "already moving");

  scene = TwoNodes();
  scene["pinned"] = {"top_left"};
  ExpectMessage(ErrorOf(scene), "pinned[0]", "use a node index");

  scene = Grid(3, 3, {});
  scene["pinned"] = {"top"};
  ExpectMessage(ErrorOf(scene), "pinned[0]", "unknown node name \"top\"");

  scene = Grid(3, 3, {"structural"});
  scene["springs"] = {{{"nodes", {"top_row", 4}}, {"model", "hookean"}, {"stiffness", 1}}};
  ExpectMessage(ErrorOf(scene), "springs[0].nodes[0]", "single node");
}

TEST(BadInputTest, ContradictoryVelocities) {
  json scene = TwoNodes();
  scene["pinned"] = {1};
  ExpectMessage(ErrorOf(scene), "nodes.velocities[1]", "pinned by pinned[0]");

  scene = TwoNodes();
  scene["moving"] = {{{"node", 1}, {"velocity", {2, 0}}}};
  ExpectMessage(ErrorOf(scene), "nodes.velocities[1]", "moving by moving[0]");

  scene = TwoNodes();
  scene["initial_velocity"] = {1, 1};
  ExpectMessage(ErrorOf(scene), "initial_velocity", "has no effect");

  scene = TwoNodes();
  scene["nodes"]["velocities"].push_back({0, 0});
  ExpectMessage(ErrorOf(scene), "nodes.velocities", "one velocity per position (2), got 3");
}

TEST(BadInputTest, ZeroLengthSpringNeedsRestLength) {
  json scene = TwoNodes();
  scene["nodes"]["positions"][1] = {0, 0};
  ExpectMessage(ErrorOf(scene), "springs[0].rest_length", "same position");
  scene["springs"][0]["rest_length"] = 1;
  EXPECT_EQ(ParseScene(scene, kSource).springs[0].rest_length, 1.0);
}

TEST(BadInputTest, DataWithoutEffect) {
  json scene = TwoNodes();
  scene["damping"] = {{"mass_proportional", 0.1}};
  ExpectMessage(ErrorOf(scene), "damping", "\"damping\" is not listed in \"effects\"");

  scene = TwoNodes();
  scene["effects"] = {"springs"};
  ExpectMessage(ErrorOf(scene), "gravity", "\"gravity\" is not listed");

  scene = TwoNodes();
  scene["effects"] = {"gravity"};
  ExpectMessage(ErrorOf(scene), "springs", "\"springs\" is not listed");

  scene = Grid(3, 3, {"shear"});
  scene["effects"] = json::array();
  ExpectMessage(ErrorOf(scene), "grid.shear", "\"springs\" is not listed");

  scene = TwoNodes();
  scene.erase("gravity");
  ExpectMessage(ErrorOf(scene), "gravity", "is missing but \"effects\" lists \"gravity\"");

  scene = TwoNodes();
  scene.erase("springs");
  ExpectMessage(ErrorOf(scene), "effects[1]", "defines no springs");

  scene = TwoNodes();
  scene["effects"].push_back("damping");
  ExpectMessage(ErrorOf(scene), "damping", "is missing");

  scene = TwoNodes();
  scene["effects"] = {"gravity", "damping"};
  scene.erase("springs");
  scene["damping"] = {{"stiffness_proportional", 0.1}};
  ExpectMessage(ErrorOf(scene), "damping.stiffness_proportional", "no effect without");

  SceneLoadOptions options;
  options.extra_effects = {"wind"};
  scene = TwoNodes();
  scene["wind"] = {{"speed", 1}};
  ExpectMessage(ErrorOf(scene, options), "wind", "\"wind\" is not listed");
  ExpectMessage(ErrorOf(scene), "wind", "unknown key");  // not registered
  scene["effects"].push_back("wind");
  scene["wind"] = 3;
  ExpectMessage(ErrorOf(scene, options), "wind", "must be an object");
}

TEST(BadInputTest, UnknownAndDuplicateEffects) {
  json scene = TwoNodes();
  scene["effects"].push_back("wind");
  ExpectMessage(ErrorOf(scene), "effects[2]", "unknown effect \"wind\"");

  scene = TwoNodes();
  scene["effects"].push_back("gravity");
  ExpectMessage(ErrorOf(scene), "effects[2]", "already listed at effects[0]");
}

TEST(BadInputTest, NodeSources) {
  json scene = TwoNodes();
  scene["particle"] = {{"position", {0, 0}}, {"mass", 1}};
  ExpectMessage(ErrorOf(scene), "particle", "exactly one of");

  scene = TwoNodes();
  scene.erase("nodes");
  ExpectMessage(ErrorOf(scene), "nodes", "no nodes");

  scene = TwoNodes();
  scene["nodes"]["positions"] = json::array();
  ExpectMessage(ErrorOf(scene), "nodes.positions", "at least one node");

  scene = TwoNodes();
  scene["nodes"]["mass"] = 1;
  ExpectMessage(ErrorOf(scene), "nodes.mass", "conflicts with nodes.masses");

  scene = TwoNodes();
  scene["nodes"]["masses"] = {1, 1, 1};
  ExpectMessage(ErrorOf(scene), "nodes.masses", "one mass per node (2), got 3");

  scene = TwoNodes();
  scene["nodes"]["density"] = 1;
  ExpectMessage(ErrorOf(scene), "nodes.density", "unknown key");

  scene = Grid(3, 3, {});
  scene["grid"]["total_mass"] = 1;
  ExpectMessage(ErrorOf(scene), "grid.total_mass", "conflicts with grid.mass");

  scene = Grid(3, 3, {});
  scene["grid"].erase("mass");
  ExpectMessage(ErrorOf(scene), "grid.mass", "missing");

  scene = Grid(3, 3, {});
  scene["grid"]["plane"] = "xz";
  ExpectMessage(ErrorOf(scene), "grid.plane", "only allowed when \"dimension\" is 3");

  scene = Grid(3, 3, {});
  scene["grid"].erase("width");
  ExpectMessage(ErrorOf(scene), "grid.width", "required key is missing");

  const json chain = {{"chain", {{"count", 3}, {"from", {1, 1}}, {"to", {1, 1}}, {"mass", 1}}}};
  ExpectMessage(ErrorOf(chain), "chain.to", "must differ from chain.from");
}

// Errors of SceneLoadOptions::grid_size name the option and the scene (the
// programs print them naming --grid_size, apps/flag_names.h).
void ExpectGridSizeError(const std::string& message, const std::string& source,
                         const std::string& what) {
  EXPECT_EQ(message.rfind("options: SceneLoadOptions.grid_size: ", 0), 0u) << message;
  EXPECT_NE(message.find(source), std::string::npos) << message;
  EXPECT_NE(message.find(what), std::string::npos) << message;
}

TEST(BadInputTest, GridSizeFlag) {
  SceneLoadOptions options;
  options.grid_size = 10;
  ExpectGridSizeError(ErrorOf(TwoNodes(), options), kSource, "has no \"grid\"");
  ExpectGridSizeError(InputErrorOf([&] { LoadScene("oscillator", options); }),
                      "problems/oscillator.json", "has no \"grid\"");
  options.grid_size = 1;
  ExpectGridSizeError(ErrorOf(Grid(3, 3, {}), options), kSource, "must be >= 2");
  options.grid_size = 2000;
  ExpectGridSizeError(ErrorOf(Grid(3, 3, {}), options), kSource, "exceeds the limit");
}

TEST(BadInputTest, MalformedJson) {
  const std::string message = ErrorOfText(std::string("{\n  \"steps\": 10,\n  \"dimension\": }\n"));
  ExpectMessage(message, "malformed JSON", "line 3");
  ExpectMessage(ErrorOfText(std::string("")), "malformed JSON", "unexpected end of input");
}

TEST(BadInputTest, DuplicateKeys) {
  ExpectMessage(ErrorOfText(std::string(R"({"steps": 1, "steps": 2})")), "steps", "duplicate key");
  ExpectMessage(ErrorOfText(std::string(
                    R"({"nodes": {"positions": [[0, 0]], "mass": 1, "mass": 2}, "steps": 1})")),
                "nodes.mass", "duplicate key");
  ExpectMessage(ErrorOfText(std::string(R"({"springs": [{}, {"model": 1, "model": 2}]})")),
                "springs[1].model", "duplicate key");
}

TEST(BadInputTest, UnreadableFiles) {
  const std::string missing = ::testing::TempDir() + "/no_such_dir/scene.json";
  std::string message = InputErrorOf([&] { LoadSceneFile(missing); });
  EXPECT_NE(message.find(missing + ": cannot open"), std::string::npos) << message;

  message = InputErrorOf([&] { LoadSceneFile(::testing::TempDir()); });
  EXPECT_NE(message.find("is a directory"), std::string::npos) << message;

  message = InputErrorOf([] { LoadScene(""); });
  EXPECT_EQ(message.rfind("scene: the name is empty", 0), 0u) << message;

  message = InputErrorOf([&] { LoadScene(missing); });
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  EXPECT_NE(message.find("no such scene file"), std::string::npos) << message;
}

// Only regular files are read, up to a size limit; a NUL byte or anything
// after the scene's JSON value is an error (nlohmann stops at a NUL byte).
TEST(BadInputTest, FileKindSizeAndTrailingGarbage) {
  std::string message = InputErrorOf([] { LoadSceneFile("/dev/zero"); });
  EXPECT_NE(message.find("/dev/zero: cannot read scene file: not a regular file"),
            std::string::npos)
      << message;
  message = InputErrorOf([] { LoadScene("/dev/null"); });
  EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;

  const std::string big = ::testing::TempDir() + "/scene_loader_test_big.json";
  {
    std::ofstream file(big);
    file << TwoNodes().dump();
  }
  std::filesystem::resize_file(big, (256u << 20) + 1);  // sparse: no disk space used
  message = InputErrorOf([&] { LoadSceneFile(big); });
  EXPECT_NE(message.find("larger than the limit of 256 MiB"), std::string::npos) << message;
  std::remove(big.c_str());

  const std::string valid = TwoNodes().dump();
  ExpectMessage(ErrorOfText(valid + std::string(1, '\0') + "garbage"), "NUL byte",
                "at offset " + std::to_string(valid.size()));
  ExpectMessage(ErrorOfText(valid + std::string(1, '\0')), "NUL byte", "");
  ExpectMessage(ErrorOfText(valid + " {}"), "malformed JSON", "expected end of input");
  ExpectMessage(ErrorOfText(valid + "\n x"), "malformed JSON", "");
  EXPECT_EQ(ParseScene(valid + " \n\t\r\n", kSource).num_nodes(), 2);  // trailing blanks are fine
}

// Input echoed in a message (keys, names, tokens) is cut to about 80
// characters, so that a 10 MB key does not make a 10 MB error line.
TEST(BadInputTest, EchoedInputIsCut) {
  const std::string huge(10 << 20, 'k');
  const auto expect_short = [&](const std::string& message, const std::string& what) {
    ExpectMessage(message, "...", what);
    EXPECT_LT(message.size(), 400u) << message.substr(0, 400);
  };
  json scene = TwoNodes();
  scene[huge] = 1;
  expect_short(ErrorOf(scene), "unknown key");
  scene = TwoNodes();
  scene["nodes"][huge] = 1;
  expect_short(ErrorOf(scene), "unknown key");
  scene = TwoNodes();
  scene["effects"].push_back(huge);
  expect_short(ErrorOf(scene), "unknown effect");
  scene = TwoNodes();
  scene["springs"][0]["model"] = huge;
  expect_short(ErrorOf(scene), "unknown spring model");
  scene = Grid(3, 3, {});
  scene["pinned"] = {huge};
  expect_short(ErrorOf(scene), "unknown node name");
  // Parse errors quote the token nlohmann last read.
  expect_short(ErrorOfText("{\"name\": \"" + huge), "malformed JSON");
  expect_short(ErrorOfText("{\"steps\": 1" + std::string(10 << 20, '0') + "}"), "out of the range");
  expect_short(ErrorOfText("{\"a\": 1, \"" + huge + "\": 1, \"" + huge + "\": 2}"),
               "duplicate key");
}

TEST(BadInputTest, UnknownBuiltinName) {
  std::string message = InputErrorOf([] { LoadScene("no_such_scene"); });
  EXPECT_NE(message.find("no_such_scene"), std::string::npos) << message;
  EXPECT_NE(message.find("cloth, cloth_box, cloth_sphere, drop, fpu, hanging_square, impact, "
                         "oscillator, slope, spring_pendulum, squash_square, squeeze, "
                         "twisted_bar_3d, two_squares"),
            std::string::npos)
      << message;
  message = InputErrorOf([] { BuiltinSceneText("no_such_scene"); });
  EXPECT_NE(message.find("unknown built-in scene"), std::string::npos) << message;
}

// Replacing any value of a built-in scene with any other JSON value must give
// a valid scene or an InputError, never another exception or a crash.
TEST(BadInputTest, MutatedScenesOnlyRaiseInputError) {
  const json replacements = json::parse(
      R"([null, true, "x", -1, 0, 2.5, 1e308, 18446744073709551615, [], {}, [0, 1], [1e308, 0]])");
  int errors = 0;
  SceneLoadOptions small_grid;  // keeps the cloth small, so that the test is fast
  small_grid.grid_size = 3;
  for (const std::string& name : BuiltinSceneNames()) {
    const SceneLoadOptions options = name == "cloth" ? small_grid : SceneLoadOptions{};
    const json original = json::parse(BuiltinSceneText(name));
    std::set<std::string> pointers;
    const json flat = original.flatten();
    for (const auto& leaf : flat.items()) {
      for (json::json_pointer pointer(leaf.key()); !pointer.empty();
           pointer = pointer.parent_pointer()) {
        pointers.insert(pointer.to_string());
      }
    }
    for (const std::string& pointer : pointers) {
      for (const json& replacement : replacements) {
        json mutated = original;
        mutated[json::json_pointer(pointer)] = replacement;
        try {
          ParseScene(mutated, "mutated.json", options);
        } catch (const InputError& error) {
          ++errors;
          EXPECT_EQ(std::string(error.what()).rfind("mutated.json: ", 0), 0u) << error.what();
        } catch (const std::exception& error) {
          ADD_FAILURE() << name << " " << pointer << " = " << replacement.dump() << ": "
                        << error.what();
        }
      }
    }
  }
  EXPECT_GT(errors, 1000);
}

}  // namespace
}  // namespace ipstep
