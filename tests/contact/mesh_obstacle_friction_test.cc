// Friction of the 3D face and box-edge pairs against obstacles
// (contact/pairs/face_obstacle_pairs.h, box_edge_pairs.h,
// contact/primitive_obstacle_friction.h):
//  * the terms of a cloth patch over two boxes (one static, one moving) sum to
//    IPC's dissipation mu lambda f0(|v_t|) of every face-corner and
//    edge-box-edge combination within d_hat, found by brute force, with the
//    lagged normal force lambda = kappa w (-B'(d)) and the velocity relative
//    to the obstacle; their gradient matches central differences;
//  * a rigid triangle resting on a box only through face-corner pairs, or only
//    through edge-box-edge pairs, thrown sideways, decelerates at mu g (Coulomb)
//    and then sticks; resting on a box moving sideways, it is dragged up to the
//    box's speed at mu g.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/obstacles/box_obstacle.h"
#include "contact/pairs/box_edge_pairs.h"
#include "contact/pairs/face_obstacle_pairs.h"
#include "core/incremental_potential.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"
#include "tests/support/cloth_meshes.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using nlohmann::json;
using V = Eigen::Vector3d;

V At(const std::vector<double>& x, int node) {
  return V(x[3 * node], x[3 * node + 1], x[3 * node + 2]);
}

// A 3 x 3 cloth patch (spacing 0.5, [0, 1]^2 at height h) over a small box
// whose top [0.3, 0.45] x [0.05, 0.2] lies under the interior of one triangle
// (its four top corners are face features within d_hat, no box edge is near a
// cloth edge) and a moving bar along y whose top edges at x = 0.2 and 0.3 pass
// under the cloth edges crossing them (box-edge pairs; its corners are far).
struct PatchOverBoxes {
  CollisionMesh mesh;
  std::vector<double> x;
  ObstacleList obstacles;
  std::vector<bool> free;
  double time = 0.0;
  double kappa = 7.0;
  double d_hat = 0.02;
  IncrementalPotential potential{3, 9};
  PairSetContext context;

  explicit PatchOverBoxes(double h) {
    testing::AddClothGrid(
        3, 3, 0.5, 0, [h](int i, int j) { return V(0.5 * i, 0.5 * j, h); }, &mesh, &x);
    // Distinct weights (the grid's are a^2 / 2 each): each pair must use its own.
    for (size_t f = 0; f < mesh.faces.size(); ++f) mesh.face_weights[f] = 0.1 + 0.02 * f;
    for (size_t e = 0; e < mesh.edges.size(); ++e) mesh.edge_weights[e] = 0.1 + 0.01 * e;
    obstacles.push_back(std::make_shared<BoxObstacle>(3, V(0.3, 0.05, -1), V(0.45, 0.2, 0)));
    obstacles.push_back(
        std::make_shared<BoxObstacle>(3, V(0.2, -0.5, -1), V(0.3, 1.5, 0), V(0.003, -0.001, 0.0)));
    free.assign(mesh.nodes.size(), true);
    context.dimension = 3;
    context.num_coordinates = 27;
    context.mesh = &mesh;
    context.obstacles = &obstacles;
    context.node_free = &free;
    context.d_hat = d_hat;
    context.time = &time;
    context.kappa = &kappa;
    context.step = &potential.context();
    potential.context().Resize(3, 9);
  }
};

// mu lambda f0(|T^T (sum alpha v - v_o)|) with T the tangent plane of n.
double Dissipation(double mu, double lambda, const V& n, const V& v_rel, double eps_v) {
  const V v_t = v_rel - v_rel.dot(n) * n;
  return mu * lambda * FrictionF0(v_t.norm(), eps_v);
}

TEST(MeshObstacleFriction, TermsAreTheLaggedDissipationOfEveryPair) {
  PatchOverBoxes s(0.01);
  FaceObstaclePairs face_pairs(s.context);
  BoxEdgePairs edge_pairs(s.context);
  const std::vector<double> reach(s.mesh.nodes.size(), 0.0), travel(2, 0.0);
  const CandidateRegion region{s.x.data(), nullptr, &reach, 0.0, &travel};  // at s.time = 0
  ASSERT_TRUE(face_pairs.Extend(region));
  ASSERT_TRUE(edge_pairs.Extend(region));
  face_pairs.LagFriction(s.x.data(), 0.0);
  edge_pairs.LagFriction(s.x.data(), 0.0);
  // Velocities v = v_base + (x - x_base) with slope 1: every node slides at
  // `slide`, faster than eps_v relative to both boxes.
  StepContext& step = s.potential.context();
  step.velocity_slope = 1.0;
  step.x_base = Eigen::Map<const Eigen::VectorXd>(s.x.data(), s.x.size());
  step.v_base.setZero();
  FrictionSettings friction;
  friction.mu = 0.4;
  friction.epsilon_v = 1e-3;
  int contacts = face_pairs.AddFrictionTerms(friction, &s.potential);
  contacts += edge_pairs.AddFrictionTerms(friction, &s.potential);
  const V slide(0.01, 0.004, 0.0);
  std::vector<double> y = s.x;
  for (int node = 0; node < 9; ++node) {
    for (int k = 0; k < 3; ++k) y[3 * node + k] += slide[k];
  }
  // Brute force over every face x corner and edge x box edge at x.
  double expected = 0.0;
  int faces = 0, edges = 0;
  for (const ObstaclePtr& o : s.obstacles) {
    const V v_rel = slide - o->velocity();
    for (size_t f = 0; f < s.mesh.faces.size(); ++f) {
      const auto& face = s.mesh.faces[f];
      for (int k = 0; k < o->NumFaceFeatures(); ++k) {
        V grad[3];
        const double d =
            o->FaceDistance(k, At(s.x, face[0]), At(s.x, face[1]), At(s.x, face[2]), 0.0, grad);
        if (!(d > 0.0 && d < s.d_hat)) continue;
        const double lambda = -s.kappa * s.mesh.face_weights[f] * BarrierDerivative(d, s.d_hat);
        expected += Dissipation(friction.mu, lambda, grad[0] + grad[1] + grad[2], v_rel, 1e-3);
        ++faces;
      }
    }
    for (size_t e = 0; e < s.mesh.edges.size(); ++e) {
      const auto& edge = s.mesh.edges[e];
      for (int k = 0; k < o->NumBoxEdges(); ++k) {
        V ga, gb;
        const double d = o->BoxEdgeDistance(k, At(s.x, edge[0]), At(s.x, edge[1]), 0.0, &ga, &gb);
        if (!(d > 0.0 && d < s.d_hat)) continue;
        const double lambda = -s.kappa * s.mesh.edge_weights[e] * BarrierDerivative(d, s.d_hat);
        expected += Dissipation(friction.mu, lambda, ga + gb, v_rel, 1e-3);
        ++edges;
      }
    }
  }
  EXPECT_EQ(faces, 4);   // the small box's top corners under one triangle
  EXPECT_EQ(edges, 10);  // the bar's two top edges under five cloth edges
  EXPECT_EQ(contacts, faces + edges);
  auto friction_terms = [](const Term& t) { return t.kind == TermKind::kDissipation; };
  double energy = 0.0;
  Eigen::VectorXd gradient(27);
  ASSERT_TRUE(s.potential.EvaluateUnweighted(friction_terms, y.data(), &energy, gradient.data()));
  EXPECT_NEAR(energy, expected, 1e-12 * expected);
  // The friction force (minus the gradient) against central differences.
  for (int i = 0; i < 27; ++i) {
    const double step_size = 1e-7;
    std::vector<double> plus = y, minus = y;
    plus[i] += step_size;
    minus[i] -= step_size;
    double e_plus = 0.0, e_minus = 0.0;
    ASSERT_TRUE(s.potential.EvaluateUnweighted(friction_terms, plus.data(), &e_plus, nullptr));
    ASSERT_TRUE(s.potential.EvaluateUnweighted(friction_terms, minus.data(), &e_minus, nullptr));
    EXPECT_NEAR(gradient[i], (e_plus - e_minus) / (2 * step_size), 1e-6 * gradient.norm()) << i;
  }
  // Moving with each box: no dissipation from its pairs (mu = 0: no terms).
  friction.mu = 0.0;
  IncrementalPotential none(3, 9);
  EXPECT_EQ(
      face_pairs.AddFrictionTerms(friction, &none) + edge_pairs.AddFrictionTerms(friction, &none),
      0);
}

// A rigid triangle of three 1 kg nodes (stiff springs) d_hat / 2 above the box
// [-0.1, 0.1] x [-0.2, 0] x [-0.1, 0.1] (moving at box_speed along x), sliding
// at v0 along x; returns its mean x velocity after each step. `weight` is the
// sum of its pairs' barrier weights: kappa is set so that the barrier holds
// the triangle's weight at d_hat / 2, where it starts (at rest vertically: the
// lagged normal forces add up to m g from the first step on).
std::vector<double> SlideOnBox(const std::vector<V>& corners, double weight, double v0,
                               double box_speed, double mu, double h, int steps) {
  // The energy balance counts a moving obstacle's work through the barrier
  // (ContactFilter::PrescribedWork), not through friction: a box dragging the
  // triangle would fail its check ("energy growth"), as would a node dragged
  // by a plane moving along itself. Not checked when the box moves.
  const double d_hat = 1e-3, g = 9.81;
  const double kappa = 3.0 * g / (weight * -BarrierDerivative(0.5 * d_hat, d_hat));
  json positions = json::array(), velocities = json::array();
  for (const V& c : corners) {
    positions.push_back({c[0], 0.5 * d_hat, c[2]});
    velocities.push_back({v0, 0.0, 0.0});
  }
  json springs = json::array();
  for (int i = 0; i < 3; ++i) {
    springs.push_back({{"nodes", {i, (i + 1) % 3}}, {"model", "hookean"}, {"stiffness", 1e5}});
  }
  const json box = {{"type", "box"},
                    {"min", {-0.1, -0.2, -0.1}},
                    {"max", {0.1, 0.0, 0.1}},
                    {"velocity", {box_speed, 0.0, 0.0}}};
  const json scene = {
      {"dimension", 3},
      {"effects", {"gravity", "springs", "contact", "friction"}},
      {"gravity", {0, -9.81, 0}},
      {"nodes", {{"positions", positions}, {"velocities", velocities}, {"mass", 1.0}}},
      {"springs", springs},
      {"surface", {{"triangles", {{0, 1, 2}}}}},
      {"contact", {{"dhat", d_hat}, {"kappa", kappa}, {"obstacles", {box}}}},
      {"friction", {{"mu", mu}, {"epsilon_v", 1e-4}, {"iterations", 2}}}};
  SceneLoadOptions load;
  load.extra_effects = DefaultEffects().UserNames();
  SimulationOptions options = testing::Options("backward_euler", "newton", h, 1e-7);
  if (box_speed != 0.0) options.energy_tolerance = 0.0;
  Simulation sim(ParseScene(scene, "slide_test.json", load), options);
  std::vector<double> speed;
  for (int step = 0; step < steps; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << "step " << r.step << " " << r.status;
    const Eigen::VectorXd& v = sim.state().v;
    speed.push_back((v[0] + v[3] + v[6]) / 3.0);
  }
  return speed;
}

// Coulomb's law under backward Euler: the velocity changes by mu g h per step
// until it matches the support's (then it sticks, creeping below epsilon_v).
void ExpectCoulombSlide(const std::vector<double>& speed, double v0, double target, double mu,
                        double h, const char* what) {
  const double g = 9.81;
  const double direction = target > v0 ? 1.0 : -1.0;
  const double t_stop = std::abs(target - v0) / (mu * g);
  for (size_t n = 0; n < speed.size(); ++n) {
    const double t = h * (n + 1);
    if (t < 0.8 * t_stop) {
      const double coulomb = v0 + direction * mu * g * t;
      EXPECT_NEAR(speed[n], coulomb, 0.05 * mu * g * t + 1e-3) << what << " step " << n;
    } else if (t > 1.2 * t_stop) {
      EXPECT_NEAR(speed[n], target, 2e-3) << what << " step " << n;
    }
  }
}

TEST(MeshObstacleFriction, TriangleOnBoxCornersDeceleratesAtMuG) {
  // The box top lies under the triangle's interior: four face-corner pairs,
  // each weighted by the face's area 0.54 m^2.
  const std::vector<V> corners = {V(-0.6, 0, -0.3), V(0.6, 0, -0.3), V(0, 0, 0.6)};
  const double v0 = 0.2, mu = 0.3, h = 1e-3;
  ExpectCoulombSlide(SlideOnBox(corners, 4 * 0.54, v0, 0.0, mu, h, 120), v0, 0.0, mu, h, "corners");
}

TEST(MeshObstacleFriction, TriangleOnBoxEdgesDeceleratesAtMuG) {
  // Each triangle edge crosses two top edges of the box; the box corners are
  // outside the triangle and its nodes outside the box: six edge-box-edge pairs,
  // each weighted by half the mean of its nodes' weights (a third of the area
  // A each): A / 6, A = 0.2772 x 0.24 / 2.
  const std::vector<V> corners = {V(0, 0, 0.16), V(0.1386, 0, -0.08), V(-0.1386, 0, -0.08)};
  const double v0 = 0.2, mu = 0.3, h = 1e-3;
  ExpectCoulombSlide(SlideOnBox(corners, 0.5 * 0.2772 * 0.24, v0, 0.0, mu, h, 120), v0, 0.0, mu, h,
                     "edges");
}

TEST(MeshObstacleFriction, MovingBoxDragsTheTriangleAtMuG) {
  const std::vector<V> corners = {V(-0.6, 0, -0.3), V(0.6, 0, -0.3), V(0, 0, 0.6)};
  const double u = 0.15, mu = 0.3, h = 1e-3;
  ExpectCoulombSlide(SlideOnBox(corners, 4 * 0.54, 0.0, u, mu, h, 100), 0.0, u, mu, h,
                     "moving box");
}

}  // namespace
}  // namespace ipstep
