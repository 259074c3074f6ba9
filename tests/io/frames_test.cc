// --frames: the ParaView time series (io/frame_writer.h). The .pvd lists every
// frame at its simulated time; each .vtu holds the scene's nodes, springs and
// triangles; obstacles are drawn where they are at that time.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "core/input_error.h"
#include "energies/effect_registry.h"
#include "io/frame_writer.h"
#include "io/obstacle_mesh.h"
#include "io/positions_writer.h"
#include "io/stats_writer.h"
#include "io/surface_triangles.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/run_program.h"
#include "tests/support/vtu_arrays.h"

namespace {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The attributes of every element `tag` of an XML text.
std::vector<std::map<std::string, std::string>> Elements(const std::string& xml,
                                                         const std::string& tag) {
  std::vector<std::map<std::string, std::string>> elements;
  const std::regex element("<" + tag + "\\b([^>]*)>");
  const std::regex attribute("(\\w+)=\"([^\"]*)\"");
  for (auto e = std::sregex_iterator(xml.begin(), xml.end(), element); e != std::sregex_iterator();
       ++e) {
    std::map<std::string, std::string> attributes;
    const std::string text = (*e)[1];
    for (auto a = std::sregex_iterator(text.begin(), text.end(), attribute);
         a != std::sregex_iterator(); ++a) {
      attributes[(*a)[1]] = (*a)[2];
    }
    elements.push_back(attributes);
  }
  return elements;
}

// The numbers of the Points DataArray of a .vtu (any encoding).
std::vector<double> PointCoordinates(const std::string& vtu) {
  return ipstep::testing::VtuArrays(vtu).Values("");
}

// A built-in scene; contact is registered as an effect with its own top-level
// object, so the loader must accept the registry's user effects.
ipstep::Scene Load(const std::string& name) {
  ipstep::SceneLoadOptions options;
  options.extra_effects = ipstep::DefaultEffects().UserNames();
  return ipstep::LoadScene(name, options);
}

// The numbers of the DataArray named `name` of a .vtu (any encoding); empty if
// there is none.
std::vector<double> NamedArray(const std::string& vtu, const std::string& name) {
  return ipstep::testing::VtuArrays(vtu).Values(name);
}

class Frames : public ipstep::testing::ProgramTest {
 protected:
  // Runs `scene` for `steps` steps, a frame every step; returns the times.
  std::vector<double> Run(const std::string& scene_name, int steps, ipstep::Scene* scene_out) {
    const ipstep::Scene scene = Load(scene_name);
    if (scene_out != nullptr) *scene_out = scene;
    ipstep::SimulationOptions options;
    options.steps = steps;
    ipstep::Simulation sim(scene, options);
    ipstep::FrameWriter frames((dir_ / "frames").string(), sim, "frames",
                               ipstep::VtkEncoding::kAscii);
    std::vector<double> times{sim.state().time};
    frames.Write(0);
    for (int step = 1; step <= steps; ++step) {
      EXPECT_TRUE(sim.Step().converged);
      frames.Write(step);
      times.push_back(sim.state().time);
    }
    return times;
  }
};

TEST_F(Frames, SeriesListsEveryFrameAtItsSimulatedTime) {
  ipstep::Scene scene;
  const std::vector<double> times = Run("drop", 4, &scene);
  const auto datasets = Elements(ReadFile(dir_ / "frames" / "run.pvd"), "DataSet");
  ASSERT_EQ(datasets.size(), 2 * times.size());  // body and obstacles per frame
  const size_t triangles = ipstep::SurfaceTriangles(scene).size();
  EXPECT_EQ(triangles, 32u);  // 4 x 4 cells, two triangles each
  for (size_t f = 0; f < times.size(); ++f) {
    const auto& body = datasets[2 * f];
    const auto& obstacles = datasets[2 * f + 1];
    EXPECT_EQ(body.at("part"), "0");
    EXPECT_EQ(obstacles.at("part"), "1");
    EXPECT_NEAR(std::stod(body.at("timestep")), times[f], 1e-12 * (1 + times[f]));
    EXPECT_EQ(body.at("timestep"), obstacles.at("timestep"));
    EXPECT_EQ(obstacles.at("file"), "obstacles.vtu");  // static: written once
    const auto pieces = Elements(ReadFile(dir_ / "frames" / body.at("file")), "Piece");
    ASSERT_EQ(pieces.size(), 1u);
    EXPECT_EQ(std::stoul(pieces[0].at("NumberOfPoints")), static_cast<size_t>(scene.num_nodes()));
    EXPECT_EQ(std::stoul(pieces[0].at("NumberOfCells")), scene.springs.size() + triangles);
  }
  EXPECT_NEAR(std::stod(datasets.back().at("timestep")), 4 * scene.time_step, 1e-12);
  // The ground y = -1: a segment (2D plane) at that height.
  const std::string ground = ReadFile(dir_ / "frames" / "obstacles.vtu");
  EXPECT_EQ(Elements(ground, "Piece")[0].at("NumberOfCells"), "1");
  const std::vector<double> xyz = PointCoordinates(ground);
  ASSERT_EQ(xyz.size(), 6u);
  EXPECT_DOUBLE_EQ(xyz[1], -1.0);
  EXPECT_DOUBLE_EQ(xyz[4], -1.0);
}

// With contact, each node carries the barrier's force on it: upwards on the
// nodes near the ground once the square has landed, zero out of the barrier's
// reach (d_hat = 0.01 m); scenes without contact carry none.
TEST_F(Frames, ContactForcesPushNodesOutOfTheGround) {
  ipstep::Scene scene;
  const std::vector<double> times = Run("drop", 45, &scene);  // lands at t = 0.32 s
  const std::string last = ReadFile(dir_ / "frames" / "frame_00045.vtu");
  const std::vector<double> xyz = PointCoordinates(last);
  const std::vector<double> force = NamedArray(last, "contact_force");
  ASSERT_EQ(force.size(), 3u * scene.num_nodes());
  double upwards = 0.0;
  int pushed = 0;
  for (int i = 0; i < scene.num_nodes(); ++i) {
    EXPECT_GE(force[3 * i + 1], 0.0) << "node " << i;
    if (xyz[3 * i + 1] > -1.0 + 0.011) {
      EXPECT_EQ(force[3 * i + 1], 0.0) << "node " << i << " at y = " << xyz[3 * i + 1];
    }
    if (force[3 * i + 1] > 0.0) ++pushed;
    upwards += force[3 * i + 1];
  }
  EXPECT_GE(pushed, 1);
  EXPECT_GT(upwards, 0.0);
  ipstep::SimulationOptions options;
  ipstep::Simulation oscillator(Load("oscillator"), options);
  ipstep::FrameWriter frames((dir_ / "oscillator").string(), oscillator);
  frames.Write(0);
  const std::string vtu = ReadFile(dir_ / "oscillator" / "frame_00000.vtu");
  EXPECT_FALSE(NamedArray(vtu, "velocity").empty());
  EXPECT_TRUE(NamedArray(vtu, "contact_force").empty());
}

TEST_F(Frames, MovingObstaclesAreDrawnWhereTheyAre) {
  const std::vector<double> times = Run("two_squares", 3, nullptr);
  const auto datasets = Elements(ReadFile(dir_ / "frames" / "run.pvd"), "DataSet");
  ASSERT_EQ(datasets.size(), 2 * times.size());
  for (size_t f = 0; f < times.size(); ++f) {
    const auto& obstacles = datasets[2 * f + 1];
    char name[48];
    std::snprintf(name, sizeof(name), "obstacles_%05zu.vtu", f);
    ASSERT_EQ(obstacles.at("file"), name);
    // Two segments: the ground at y = -0.505 and the ceiling at 1.6 - 0.5 t.
    const std::vector<double> xyz = PointCoordinates(ReadFile(dir_ / "frames" / name));
    ASSERT_EQ(xyz.size(), 12u);
    EXPECT_DOUBLE_EQ(xyz[1], -0.505);
    EXPECT_NEAR(xyz[7], 1.6 - 0.5 * times[f], 1e-12);
  }
}

TEST(SurfaceTriangles, GuessedTwoPerCellWithoutOverlapsOrBendingChords) {
  // cloth_sphere: 10 x 10 nodes with structural, shear and bending springs.
  const ipstep::Scene cloth = Load("cloth_sphere");
  ASSERT_EQ(cloth.num_nodes(), 100);
  const auto triangles = ipstep::SpringTriangles(cloth);
  EXPECT_EQ(triangles.size(), 2u * 9 * 9);
  // Their areas add up to the cloth's (1 m x 1 m, flat at the start).
  double area = 0.0;
  for (const auto& t : triangles) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = Eigen::Map<const Eigen::Vector3d>(&cloth.positions[3 * t[k]]);
    area += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  EXPECT_NEAR(area, 1.0, 1e-9);
  // A chain has springs but no triangles.
  EXPECT_TRUE(ipstep::SpringTriangles(Load("fpu")).empty());
  EXPECT_TRUE(ipstep::SurfaceTriangles(Load("fpu")).empty());
  // 2D scenes declare edges, not triangles: their cells are guessed.
  const ipstep::Scene drop = Load("drop");
  EXPECT_TRUE(drop.surface.triangles.empty());
  EXPECT_EQ(ipstep::SurfaceTriangles(drop), ipstep::SpringTriangles(drop));
}

// A scene that declares its surface is drawn with the declared triangles, not
// the guess: a 3D grid's two per cell, and a "surface" key's triangles even
// where the springs would suggest others.
TEST(SurfaceTriangles, DeclaredTrianglesAreDrawn) {
  const ipstep::Scene cloth = Load("cloth_sphere");
  ASSERT_EQ(cloth.surface.triangles.size(), 2u * 9 * 9);
  EXPECT_EQ(ipstep::SurfaceTriangles(cloth), cloth.surface.triangles);

  // A unit square in 3D whose springs run along its edges and the diagonal
  // 0-2 (guessed: 0-1-2 and 0-2-3), declaring the triangles across the other
  // diagonal 1-3.
  ipstep::SceneLoadOptions options;
  options.extra_effects = ipstep::DefaultEffects().UserNames();
  const ipstep::Scene square = ipstep::ParseScene(std::string(R"({
    "dimension": 3,
    "effects": ["springs", "contact"],
    "nodes": {"positions": [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], "total_mass": 1},
    "springs": [{"nodes": [0, 1], "model": "hookean", "stiffness": 10}, {"nodes": [1, 2], "model": "hookean", "stiffness": 10},
                {"nodes": [2, 3], "model": "hookean", "stiffness": 10}, {"nodes": [3, 0], "model": "hookean", "stiffness": 10},
                {"nodes": [0, 2], "model": "hookean", "stiffness": 10}],
    "surface": {"triangles": [[0, 1, 3], [1, 2, 3]]},
    "contact": {"obstacles": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 0, 1]}]}
  })"),
                                                  "square.json", options);
  using Triangles = std::vector<std::array<int, 3>>;
  EXPECT_EQ(ipstep::SpringTriangles(square), (Triangles{{0, 1, 2}, {0, 2, 3}}));
  EXPECT_EQ(ipstep::SurfaceTriangles(square), (Triangles{{0, 1, 3}, {1, 2, 3}}));
}

// The frames of a scene with a declared surface hold its triangles.
TEST_F(Frames, DeclaredSurfaceIsWrittenToTheFrames) {
  ipstep::Scene scene;
  Run("cloth_sphere", 1, &scene);
  const std::string vtu = ReadFile(dir_ / "frames" / "frame_00000.vtu");
  const std::vector<double> kind = NamedArray(vtu, "kind");
  const std::vector<double> connectivity = NamedArray(vtu, "connectivity");
  ASSERT_EQ(kind.size(), scene.springs.size() + scene.surface.triangles.size());
  // Springs (2 points each) come first, then the triangles in declared order.
  const size_t first = 2 * scene.springs.size();
  ASSERT_EQ(connectivity.size(), first + 3 * scene.surface.triangles.size());
  for (size_t t = 0; t < scene.surface.triangles.size(); ++t) {
    EXPECT_EQ(kind[scene.springs.size() + t], 1.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(connectivity[first + 3 * t + k], scene.surface.triangles[t][k]) << t;
    }
  }
}

TEST(ObstacleMesh, SpheresBoxesAndPlanesAtTheirTime) {
  const auto sphere = std::make_shared<ipstep::SphereObstacle>(3, Eigen::Vector3d(0.1, 0.2, 0.3),
                                                               0.5, Eigen::Vector3d(1.0, 0.0, 0.0));
  const auto box =
      std::make_shared<ipstep::BoxObstacle>(3, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const ipstep::VtkMesh mesh = ipstep::ObstacleMesh({sphere, box}, 2.0, {0, 0, 0}, 1.0);
  const std::vector<int>& owner = mesh.cell_integers.at(0).second;
  ASSERT_EQ(owner.size(), mesh.cells.size());
  int box_cells = 0;
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    for (int i : mesh.cells[c]) {
      if (owner[c] == 0) {  // on the sphere, moved by velocity * t
        EXPECT_NEAR((mesh.points[i] - Eigen::Vector3d(2.1, 0.2, 0.3)).norm(), 0.5, 1e-12);
      }
    }
    if (owner[c] == 1) {
      ++box_cells;
      EXPECT_EQ(mesh.types[c], ipstep::VtkCell::kQuad);
    }
  }
  EXPECT_EQ(box_cells, 6);
}

TEST_F(Frames, UnwritableDirectoryIsAnInputError) {
  const ipstep::Scene scene = Load("oscillator");
  ipstep::Simulation sim(scene, {});
  std::ofstream(dir_ / "file") << "x";
  try {
    ipstep::FrameWriter frames((dir_ / "file" / "frames").string(), sim);
    FAIL() << "no error";
  } catch (const ipstep::InputError& e) {
    // The library names the output as its caller did (default "frames"), not a flag.
    EXPECT_EQ(std::string(e.what()).rfind("output: frames: cannot create directory '", 0), 0u)
        << e.what();
    EXPECT_EQ(std::string(e.what()).find("--"), std::string::npos) << e.what();
  }
}

// The CSV writers name the output as their caller does, with the path and the
// system's reason.
TEST_F(Frames, UnwritableFilesNameTheOutput) {
  const ipstep::Scene scene = Load("oscillator");
  ipstep::Simulation sim(scene, {});
  const std::string path = (dir_ / "missing" / "x.csv").string();
  const auto expect_error = [&path](const std::function<void()>& write, const std::string& name) {
    try {
      write();
      ADD_FAILURE() << "no error for " << name;
    } catch (const ipstep::OutputError& e) {
      EXPECT_EQ(std::string(e.what()),
                "output: " + name + ": cannot write '" + path + "': No such file or directory");
      EXPECT_EQ(e.kind(), ipstep::OutputError::Kind::kOpen);
      EXPECT_EQ(e.path(), path);
    }
  };
  expect_error([&] { ipstep::StatsWriter writer(path, "stats"); }, "stats");
  expect_error([&] { ipstep::IterationLogWriter writer(path, "iterations_log"); },
               "iterations_log");
  expect_error([&] { ipstep::WritePositionsCsv(sim.state(), path, "final positions"); },
               "final positions");
}

}  // namespace
