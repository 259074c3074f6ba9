// Rotating obstacles (contact/obstacle.h: "angular_velocity" about
// "rotation_center"): the rigid motion and its inverse, distances and their
// derivatives in the world, the obstacle's velocity field, and conservative
// continuous collision detection of points, segments, triangles and box edges
// along curved relative paths (checked against dense sampling of the exact
// distance); and in a simulation: a floor that tilts and stops gives the
// frictionless slide g sin(theta) exactly, and fast paddles in 2D and 3D never
// let anything through.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "contact/contact_effect.h"
#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/plane_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"
#include "io/obstacle_mesh.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using Eigen::Vector3d;
using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

std::shared_ptr<Obstacle> Rotating(std::shared_ptr<Obstacle> o, int dimension) {
  const Vector3d omega = dimension == 2 ? Vector3d(0, 0, 1.3) : Vector3d(0.4, -0.9, 1.1);
  o->set_rotation(omega, Vector3d(0.3, -0.2, dimension == 2 ? 0.0 : 0.1));
  return o;
}

std::vector<std::shared_ptr<Obstacle>> Shapes(int dimension) {
  const Vector3d v = dimension == 2 ? Vector3d(0.2, -0.1, 0) : Vector3d(0.2, -0.1, 0.05);
  const double z = dimension == 2 ? 0.0 : 1.0;
  Vector3d normal(0.3, 1.0, 0.2 * z);
  normal.normalize();
  return {
      Rotating(std::make_shared<PlaneObstacle>(dimension, Vector3d(0.1, -0.3, 0), normal, v),
               dimension),
      Rotating(std::make_shared<SphereObstacle>(dimension, Vector3d(0.6, 0.1, 0.1 * z), 0.25, v),
               dimension),
      Rotating(std::make_shared<BoxObstacle>(dimension, Vector3d(-0.4, -0.2, -0.3 * z),
                                             Vector3d(0.3, 0.25, 0.2 * z), v),
               dimension)};
}

Vector3d RandomPoint(std::mt19937* rng, int dimension, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Vector3d p(u(*rng), u(*rng), dimension == 3 ? u(*rng) : 0.0);
  return p;
}

TEST(PrescribedMotion, InitialPositionInvertsPositionBeforeAndAfterTheStop) {
  PrescribedMotion m;
  m.velocity = {0.3, -0.1, 0.2};
  m.angular_velocity = {0.5, 1.0, -2.0};
  m.center = {1.0, 2.0, -1.0};
  m.until = 0.8;
  const Vector3d x0(0.4, -0.7, 1.9);
  for (double t : {0.0, 0.3, 0.8, 2.5}) {
    EXPECT_LT((m.InitialPosition(m.Position(x0, t), t) - x0).norm(), 1e-14) << t;
    EXPECT_LT((m.Rotation(t) * (x0 - m.center) + m.Center(t) - m.Position(x0, t)).norm(), 1e-14);
  }
}

TEST(RotatingObstacle, ARotatingPlaneIsThePlaneCarriedByTheMotion) {
  // The line y = 0 turning at 0.5 rad/s about (1, 0): at t its normal is
  // (-sin 0.5t, cos 0.5t) and it passes through (1, 0).
  PlaneObstacle plane(2, Vector3d(0, 0, 0), Vector3d(0, 1, 0));
  plane.set_rotation(Vector3d(0, 0, 0.5), Vector3d(1, 0, 0));
  for (double t : {0.0, 0.7, 2.0}) {
    const Vector3d n(-std::sin(0.5 * t), std::cos(0.5 * t), 0);
    const Vector3d x(0.3, 0.8, 0);
    Vector3d gradient;
    EXPECT_NEAR(plane.Distance(x, t, &gradient), n.dot(x - Vector3d(1, 0, 0)), 1e-14);
    EXPECT_LT((gradient - n).norm(), 1e-14);
    Eigen::Matrix3d hessian;
    ASSERT_TRUE(plane.DistanceHessian(x, t, &hessian));
    EXPECT_EQ(hessian.norm(), 0.0);
  }
}

TEST(RotatingObstacle, GradientHessianAndVelocityMatchFiniteDifferences) {
  std::mt19937 rng(7);
  for (int dimension : {2, 3}) {
    for (const auto& o : Shapes(dimension)) {
      for (int trial = 0; trial < 20; ++trial) {
        const Vector3d x = RandomPoint(&rng, dimension, 1.0);
        const double t = 0.37 + 0.1 * trial;
        Vector3d g;
        o->Distance(x, t, &g);
        const double h = 1e-6;
        for (int k = 0; k < dimension; ++k) {
          Vector3d e = Vector3d::Zero();
          e[k] = h;
          const double fd = (o->Distance(x + e, t) - o->Distance(x - e, t)) / (2 * h);
          EXPECT_NEAR(g[k], fd, 1e-6) << o->type_name() << " " << dimension;
        }
        Eigen::Matrix3d hessian;
        if (o->DistanceHessian(x, t, &hessian)) {
          for (int k = 0; k < dimension; ++k) {
            Vector3d e = Vector3d::Zero();
            e[k] = h;
            Vector3d gp, gm;
            o->Distance(x + e, t, &gp);
            o->Distance(x - e, t, &gm);
            const Vector3d fd = (gp - gm) / (2 * h);
            for (int j = 0; j < dimension; ++j) {
              EXPECT_NEAR(hessian(j, k), fd[j], 1e-5) << o->type_name();
            }
          }
        }
        // The material point at x: d/dt ToWorld(ToRest(x, t), t').
        const Vector3d y = o->ToRest(x, t);
        const Vector3d fd = (o->ToWorld(y, t + h) - o->ToWorld(y, t - h)) / (2 * h);
        EXPECT_LT((o->VelocityAt(x, t) - fd).norm(), 1e-7) << o->type_name();
        EXPECT_LT((o->ToWorld(y, t) - x).norm(), 1e-14);
      }
    }
  }
}

// The first fraction in [0, 1] at which f(s) <= margin, on a fine sampling
// (2 if none).
template <class F>
double SampledFirst(const F& f, double margin) {
  const int n = 4000;
  for (int i = 0; i <= n; ++i) {
    if (f(double(i) / n) <= margin) return double(i) / n;
  }
  return 2.0;
}

// s is safe (no sample below it within the margin) and not far from the
// first contact: the gap there has fallen to within 2 % of max(margin, d0/10).
template <class F>
void ExpectConservative(const F& gap, double s, double margin, const std::string& what) {
  const double first = SampledFirst(gap, margin);
  EXPECT_LE(s, first + 1e-9) << what;
  if (s > 1.0 || s == 0.0) return;
  const double d0 = gap(0.0), goal = std::max(margin, Obstacle::kEdgeGapFraction * d0);
  EXPECT_LE(gap(s), goal + 0.02 * (d0 - goal) + 1e-12) << what << " s " << s;
  EXPECT_GE(gap(s), margin * (1.0 - 1e-9)) << what;  // exact answers reach the margin
}

TEST(RotatingObstacle, PointTimeOfImpactIsConservativeAlongTheCurvedPath) {
  std::mt19937 rng(11);
  int impacts = 0;
  for (int dimension : {2, 3}) {
    for (const auto& o : Shapes(dimension)) {
      for (int trial = 0; trial < 60; ++trial) {
        const Vector3d a = RandomPoint(&rng, dimension, 1.2), b = RandomPoint(&rng, dimension, 1.2);
        const double t0 = 0.2, t1 = 0.2 + 0.5 * (trial % 3);
        const double margin = 1e-3;
        auto gap = [&](double s) { return o->Distance(a + s * (b - a), t0 + s * (t1 - t0)); };
        const double s = o->TimeOfImpact(a, b, t0, t1, margin);
        ExpectConservative(gap, s, margin, o->type_name());
        impacts += s <= 1.0 && s > 0.0;
      }
    }
  }
  EXPECT_GT(impacts, 30);  // the sample meets the shapes
}

TEST(RotatingObstacle, EdgeFaceAndBoxEdgeTimesOfImpactAreConservative) {
  std::mt19937 rng(5);
  int impacts = 0;
  const double margin = 1e-3, t0 = 0.1, t1 = 0.9;
  for (int dimension : {2, 3}) {
    for (const auto& o : Shapes(dimension)) {
      for (int trial = 0; trial < 30; ++trial) {
        Vector3d v0[3], v1[3];
        for (int k = 0; k < 3; ++k) {
          v0[k] = RandomPoint(&rng, dimension, 1.0);
          v1[k] = RandomPoint(&rng, dimension, 1.0);
        }
        auto at = [&](int k, double s) { return Vector3d(v0[k] + s * (v1[k] - v0[k])); };
        auto time = [&](double s) { return t0 + s * (t1 - t0); };
        for (int f = 0; f < o->NumEdgeFeatures(); ++f) {
          auto gap = [&](double s) { return o->EdgeDistance(f, at(0, s), at(1, s), time(s)); };
          const double s = o->EdgeTimeOfImpact(f, v0[0], v1[0], v0[1], v1[1], t0, t1, margin);
          ExpectConservative(gap, s, margin, std::string("edge ") + o->type_name());
          impacts += s <= 1.0 && s > 0.0;
        }
        for (int f = 0; f < o->NumFaceFeatures(); ++f) {
          auto gap = [&](double s) {
            return o->FaceDistance(f, at(0, s), at(1, s), at(2, s), time(s));
          };
          const double s = o->FaceTimeOfImpact(f, v0, v1, t0, t1, margin);
          ExpectConservative(gap, s, margin, std::string("face ") + o->type_name());
          impacts += s <= 1.0 && s > 0.0;
        }
        for (int e = 0; e < o->NumBoxEdges(); ++e) {
          auto gap = [&](double s) { return o->BoxEdgeDistance(e, at(0, s), at(1, s), time(s)); };
          const double s = o->BoxEdgeTimeOfImpact(e, v0[0], v1[0], v0[1], v1[1], t0, t1, margin);
          ExpectConservative(gap, s, margin, "box edge");
          impacts += s <= 1.0 && s > 0.0;
        }
      }
    }
  }
  EXPECT_GT(impacts, 30);
}

// Frames draw a rotating obstacle where it is: every drawn point of a box
// turned by 0.6 rad lies on the boundary of the rest box (mapped back), and
// a point of a plane's drawing on the turned plane.
TEST(RotatingObstacle, FramesDrawItTurned) {
  auto box = std::make_shared<BoxObstacle>(3, Vector3d(0, 0, 0), Vector3d(1, 2, 3));
  box->set_rotation(Vector3d(0, 0.3, 0), Vector3d(0.5, 0, 0));
  auto plane = std::make_shared<PlaneObstacle>(3, Vector3d(0, 0, 0), Vector3d(0, 0, 1));
  plane->set_rotation(Vector3d(0.3, 0, 0), Vector3d(0, 0, 0));
  const VtkMesh mesh = ObstacleMesh({box, plane}, 2.0, {0, 0, 0}, 1.0);
  const std::vector<int>& owner = mesh.cell_integers.at(0).second;
  int moved = 0;  // box points off the box at rest (not on the rotation axis)
  for (size_t c = 0; c < mesh.cells.size(); ++c) {
    for (int i : mesh.cells[c]) {
      const Obstacle& o = owner[c] == 0 ? static_cast<const Obstacle&>(*box) : *plane;
      EXPECT_NEAR(o.Distance(mesh.points[i], 2.0), 0.0, 1e-12);
      if (owner[c] == 0) moved += std::abs(box->Distance(mesh.points[i], 0.0)) > 0.1;
    }
  }
  EXPECT_GE(moved, 12);  // of the 24 corner uses, 6 faces x 4
}

Scene Parse(const json& scene) {
  SceneLoadOptions options;
  options.extra_effects = DefaultEffects().UserNames();
  return ParseScene(scene, "rotating.json", options);
}

// The scene's contact state, through the effect that owns it.
const ContactState& Contact(const Simulation& sim) {
  const ContactEffect* contact = sim.FindEffect<ContactEffect>();
  if (contact == nullptr) throw std::logic_error("no contact effect");
  return contact->state();
}

// The ground y = 0 turns about the origin at 0.2 rad/s until it is tilted by
// 0.2 rad (t = 1 s); a frictionless particle resting on it at x = 0.5 is
// lifted and then slides down the incline with the acceleration g sin(0.2)
// (backward Euler's velocity update is exact for a constant force).
TEST(RotatingObstacle, AFloorThatTiltsAndStopsGivesTheFrictionlessSlide) {
  const json ground = {{"type", "plane"},         {"point", {0, 0}},           {"normal", {0, 1}},
                       {"angular_velocity", 0.2}, {"rotation_center", {0, 0}}, {"until", 1.0}};
  const json scene = {{"dimension", 2},
                      {"time_step", 0.01},
                      {"steps", 200},
                      {"effects", {"gravity", "contact"}},
                      {"gravity", {0, -9.81}},
                      {"particle", {{"position", {0.5, 5e-4}}, {"mass", 1}}},
                      {"contact", {{"dhat", 1e-3}, {"kappa", 1e5}, {"obstacles", {ground}}}}};
  Simulation sim(Parse(scene), testing::Options("backward_euler", "newton", 0.0, 1e-6));
  const Obstacle& floor = *Contact(sim).obstacles()[0];
  const Vector3d down_slope(-std::cos(0.2), -std::sin(0.2), 0);
  double v_at_1_5 = 0.0;
  for (int step = 1; step <= 200; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << r.step << " " << r.status;
    const Vector3d x(sim.state().x[0], sim.state().x[1], 0);
    const double d = floor.Distance(x, sim.state().time);
    ASSERT_GT(d, 0.0) << step;
    ASSERT_LT(d, 1e-3) << step;  // in contact throughout
    const Vector3d v(sim.state().v[0], sim.state().v[1], 0);
    if (step == 150) v_at_1_5 = v.dot(down_slope);
  }
  const Vector3d v(sim.state().v[0], sim.state().v[1], 0);
  const double acceleration = (v.dot(down_slope) - v_at_1_5) / 0.5;
  EXPECT_NEAR(acceleration, 9.81 * std::sin(0.2), 1e-3 * 9.81 * std::sin(0.2));
}

// A 1 m paddle (2D box) turning at 5 rad/s (tip speed 5 m/s, 5 cm per step)
// through a row of free particles: every step converges and no particle is
// ever inside the paddle; they are thrown ahead of it.
TEST(RotatingObstacle, AFastPaddleInTwoDimensionsLetsNothingThrough) {
  json positions = json::array(), masses = json::array();
  for (int k = 0; k < 7; ++k) {
    const double r = 0.3 + 0.1 * k;
    positions.push_back({r * std::cos(0.5), r * std::sin(0.5)});
    masses.push_back(0.1);
  }
  const json paddle = {{"type", "box"},
                       {"min", {0.05, -0.02}},
                       {"max", {1.0, 0.02}},
                       {"angular_velocity", 5.0},
                       {"rotation_center", {0, 0}}};
  const json scene = {{"dimension", 2},
                      {"time_step", 0.01},
                      {"steps", 40},
                      {"effects", {"contact"}},
                      {"nodes", {{"positions", positions}, {"masses", masses}}},
                      {"contact", {{"dhat", 2e-3}, {"kappa", 1e3}, {"obstacles", {paddle}}}}};
  Simulation sim(Parse(scene), testing::Options("backward_euler", "newton", 0.0, 1e-6));
  const Obstacle& box = *Contact(sim).obstacles()[0];
  for (int step = 1; step <= 40; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << r.step << " " << r.status;
    for (int k = 0; k < 7; ++k) {
      const Vector3d x(sim.state().x[2 * k], sim.state().x[2 * k + 1], 0);
      ASSERT_GT(box.Distance(x, sim.state().time), 0.0) << "particle " << k << " step " << step;
    }
  }
  // Each particle was hit: it moves, about as fast as the paddle there (not
  // faster than twice the tip speed).
  for (int k = 0; k < 7; ++k) {
    const double speed = std::hypot(sim.state().v[2 * k], sim.state().v[2 * k + 1]);
    EXPECT_GT(speed, 0.5) << k;
    EXPECT_LT(speed, 10.0) << k;
  }
}

// A 3D plate hinged along x (y = 0, z = -0.2) swings up at 2 rad/s through a
// free cloth (5 x 5 nodes, structural springs) lying at z = 0: vertices,
// faces (the plate's corners) and edges (the plate's edges) meet it, every
// step converges, and no cloth node is ever inside the plate.
TEST(RotatingObstacle, APlateSwingingThroughAClothInThreeDimensions) {
  const json plate = {{"type", "box"},
                      {"min", {0.2, -0.6, -0.22}},
                      {"max", {0.8, 0.0, -0.2}},
                      {"angular_velocity", {-2.0, 0, 0}},
                      {"rotation_center", {0, 0, -0.2}}};
  const json scene = {{"dimension", 3},
                      {"time_step", 0.01},
                      {"steps", 60},
                      {"effects", {"springs", "contact"}},
                      {"grid",
                       {{"nx", 5},
                        {"ny", 5},
                        {"width", 0.4},
                        {"height", 0.4},
                        {"origin", {0.3, 0.2, 0.0}},
                        {"total_mass", 0.1},
                        {"structural", {{"model", "hookean"}, {"stiffness", 100}}}}},
                      {"contact", {{"dhat", 2e-3}, {"kappa", 1e3}, {"obstacles", {plate}}}}};
  Simulation sim(Parse(scene), testing::Options("backward_euler", "newton", 0.0, 1e-6));
  const Obstacle& box = *Contact(sim).obstacles()[0];
  double highest = 0.0;
  for (int step = 1; step <= 60; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << r.step << " " << r.status;
    for (int k = 0; k < 25; ++k) {
      const Vector3d x(sim.state().x.data() + 3 * k);
      ASSERT_GT(box.Distance(x, sim.state().time), 0.0) << "node " << k << " step " << step;
      highest = std::max(highest, x.z());
    }
  }
  EXPECT_GT(highest, 0.1);  // the plate lifted the cloth
}

// A particle resting on a spinning drum (a circle turning about its own
// centre at 2 rad/s, friction mu 0.5) is dragged along: friction against the
// moving surface does work (h F . u, Term::frame_velocity), which the energy
// balance counts. Without it every step's kinetic energy gain looked created
// and the guard failed the run at step 4; with it no step fails, each step's
// work is positive and no energy is created beyond it.
TEST(RotatingObstacle, FrictionOfASpinningDrumDoesWorkTheBalanceCounts) {
  const json drum = {{"type", "circle"},
                     {"center", {0, 0}},
                     {"radius", 1},
                     {"angular_velocity", -2.0},
                     {"rotation_center", {0, 0}}};
  const json scene = {{"dimension", 2},
                      {"time_step", 0.01},
                      {"steps", 50},
                      {"effects", {"gravity", "contact", "friction"}},
                      {"gravity", {0, -9.81}},
                      {"particle", {{"position", {0, 1.0005}}, {"mass", 1}}},
                      {"contact", {{"dhat", 1e-3}, {"kappa", 1e5}, {"obstacles", {drum}}}},
                      {"friction", {{"mu", 0.5}}}};
  for (const std::string integrator : {"backward_euler", "newmark"}) {
    Simulation sim(Parse(scene), testing::Options(integrator, "newton", 0.0, 1e-6));
    double work = 0.0;
    for (int step = 1; step <= 20; ++step) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << integrator << " " << r.step << " " << r.status;
      EXPECT_EQ(r.substeps, 1) << integrator << " " << step;
      EXPECT_LE(r.energy_growth, 1e-9) << integrator << " " << step;
      work += r.prescribed_work;
    }
    EXPECT_GT(work, 0.0) << integrator;
    // Dragged clockwise (towards +x on top of the drum).
    EXPECT_GT(sim.state().v[0], 0.1) << integrator;
  }
}

}  // namespace
}  // namespace ipstep
