// Small scenes built in code for the tests (independent of the JSON loader).
#pragma once

#include <string>
#include <vector>

#include "problems/scene.h"
#include "sim/simulation.h"

namespace ipstep::testing {

// Node 0 pinned at the origin, node 1 (mass m) at (L + stretch, 0), one Hookean
// spring k, rest length L: a linear oscillator with omega = sqrt(k/m) as long as
// the node stays on the positive x axis (a long spring keeps large steps linear).
inline Scene OscillatorScene(double stretch = 0.1, double k = 1.0, double m = 1.0,
                             double rest_length = 1.0) {
  Scene s;
  s.name = s.source = "test_oscillator";
  s.dimension = 2;
  s.positions = {0.0, 0.0, rest_length + stretch, 0.0};
  s.velocities = {0.0, 0.0, 0.0, 0.0};
  s.masses = {1.0, m};
  s.springs = {Spring{0, 1, SpringModel::kHookean, k, rest_length}};
  s.pinned = {0};
  s.effects = {"springs"};
  return s;
}

// The stiff spring pendulum q'' = -C (|q| - 1) q/|q| - (0, 1), q0 = (0.9, 0.1).
inline Scene SpringPendulumScene(double stiffness = 1000.0) {
  Scene s;
  s.name = s.source = "test_spring_pendulum";
  s.positions = {0.0, 0.0, 0.9, 0.1};
  s.velocities = {0.0, 0.0, 0.0, 0.0};
  s.masses = {1.0, 1.0};
  s.springs = {Spring{0, 1, SpringModel::kHookean, stiffness, 1.0}};
  s.pinned = {0};
  s.gravity = {0.0, -1.0};
  s.effects = {"gravity", "springs"};
  return s;
}

// n x n grid over [-0.5, 0.5] x [-1, 0], total mass 1, structural and shear
// Hookean springs k, pinned at the two top corners, gravity -9.81 y.
inline Scene ClothScene(int n, double k = 1e4) {
  Scene s;
  s.name = s.source = "test_cloth";
  const double spacing = 1.0 / (n - 1);
  auto id = [n](int r, int c) { return r * n + c; };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      s.positions.push_back(-0.5 + c * spacing);
      s.positions.push_back(-r * spacing);
      s.masses.push_back(1.0 / (n * n));
    }
  }
  s.velocities.assign(s.positions.size(), 0.0);
  auto add = [&](int i, int j) {
    const double dx = s.positions[2 * j] - s.positions[2 * i];
    const double dy = s.positions[2 * j + 1] - s.positions[2 * i + 1];
    s.springs.push_back(Spring{i, j, SpringModel::kHookean, k, std::sqrt(dx * dx + dy * dy)});
  };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n) add(id(r, c), id(r, c + 1));
      if (r + 1 < n) add(id(r, c), id(r + 1, c));
      if (r + 1 < n && c + 1 < n) {
        add(id(r, c), id(r + 1, c + 1));
        add(id(r, c + 1), id(r + 1, c));
      }
    }
  }
  s.pinned = {id(0, 0), id(0, n - 1)};
  s.gravity = {0.0, -9.81};
  s.effects = {"gravity", "springs"};
  s.time_step = 1.0 / 60.0;
  return s;
}

inline SimulationOptions Options(const std::string& integrator, const std::string& optimizer,
                                 double dt, double tolerance = 1e-10) {
  SimulationOptions o;
  o.integrator.name = integrator;
  o.optimizer.optimizer = ParseOptimizer(optimizer);
  o.optimizer.tolerance = tolerance;
  o.time_step = dt;
  return o;
}

}  // namespace ipstep::testing
