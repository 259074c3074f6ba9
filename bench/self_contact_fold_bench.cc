// An n x n cloth (1 m, 0.2 kg, one triangulation: structural springs and one
// shear diagonal per quad, squared strain k = 2e3, Hookean bending k = 50)
// folded on itself: the columns i < n/2 lie flat at y = 0, held fixed, the
// others are mirrored back over them, shifted by half a cell along x (nodes
// over the bottom layer's edge midpoints) at height sqrt(3)/2 a, so that the
// one-cell crease is unstrained (its springs have their flat-grid lengths; no
// bending springs across the crease). Gravity drops the top layer onto the
// bottom one (contact after ~15 steps at h = 1/400 s for n = 100): about
// n^2 / 2 nodes in self-contact. Runs `steps` steps of backward Euler and
// prints per step the iterations, wall time and its broad-phase share (the
// BVH builds and queries of the point-triangle and edge-edge kinds, the
// contact filter's `broad_phase_ms`), then the averages over the steps with
// self-contact.
//   self_contact_fold_bench [n=100] [steps=30] [d_hat=2e-3] [optimizer=projected_newton]
// (Ceres's "newton" factorises with CXSparse here: at n = 100 its Cholesky
// took minutes per step, 82 % of the time in cs_di_chol.)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "energies/effect_registry.h"
#include "problems/scene.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "solver/optimizer_options.h"

namespace {

ipstep::Scene FoldedClothScene(int n, double d_hat) {
  using ipstep::Spring;
  using ipstep::SpringModel;
  ipstep::Scene s;
  s.name = s.source = "folded_cloth";
  s.dimension = 3;
  const double a = 1.0 / (n - 1);
  const int half = n / 2;
  const double gap = std::sqrt(3.0) / 2.0 * a;
  auto id = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i < half) {
        s.positions.insert(s.positions.end(), {i * a, 0.0, j * a});
      } else {
        s.positions.insert(s.positions.end(), {(n - 1 - i) * a + 0.5 * a, gap, j * a});
      }
      s.masses.push_back(0.2 / (n * n));
    }
  }
  s.velocities.assign(s.positions.size(), 0.0);
  auto add = [&](int p, int q, SpringModel model, double k, double rest) {
    s.springs.push_back(Spring{p, q, model, k, rest});
  };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) add(id(i, j), id(i + 1, j), SpringModel::kSquaredStrain, 2e3, a);
      if (j + 1 < n) add(id(i, j), id(i, j + 1), SpringModel::kSquaredStrain, 2e3, a);
      if (i + 1 < n && j + 1 < n) {
        add(id(i, j), id(i + 1, j + 1), SpringModel::kSquaredStrain, 2e3, a * std::sqrt(2.0));
      }
      if (i + 2 < n && !(i < half && half <= i + 2)) {
        add(id(i, j), id(i + 2, j), SpringModel::kHookean, 50.0, 2 * a);
      }
      if (j + 2 < n) add(id(i, j), id(i, j + 2), SpringModel::kHookean, 50.0, 2 * a);
    }
  }
  // The contact surface: two triangles per quad along the shear spring.
  s.surface.declared = true;
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      s.surface.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.surface.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  // The bottom layer is held (no ground: its barrier against ~n^2/2 resting
  // nodes made every step's Newton iterations, not the self-contact).
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < half; ++i) s.pinned.push_back(id(i, j));
  }
  s.gravity = {0.0, -9.81, 0.0};
  s.effects = {"gravity", "springs", "contact"};
  s.effect_parameters["contact"] = {{"dhat", d_hat}, {"self_contact", true}};
  s.time_step = 1.0 / 400.0;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress as it runs
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 30;
  const double d_hat = argc > 3 ? std::atof(argv[3]) : 2e-3;
  ipstep::SimulationOptions options;
  options.integrator.name = "backward_euler";
  options.optimizer.optimizer = ipstep::ParseOptimizer(argc > 4 ? argv[4] : "projected_newton");
  options.optimizer.tolerance = 1e-5;
  options.max_substeps = 8;
  ipstep::Simulation sim(FoldedClothScene(n, d_hat), options);
  for (const std::string& line : sim.effect_summaries()) std::printf("%s\n", line.c_str());
  double total = 0.0, total_broad = 0.0, contact_total = 0.0, contact_broad = 0.0;
  int iterations = 0, contact_iterations = 0, contact_steps = 0, failed = 0;
  ipstep::RunOptions run;
  run.steps = steps;
  run.stop_on_divergence = false;  // a timing of every step asked for
  run.after_step = [&](const ipstep::StepReport& r) {
    const double contacts = r.diagnostics.size() > 1 ? r.diagnostics[1] : 0.0;
    const double broad_ms = r.diagnostics.size() > 2 ? r.diagnostics[2] : 0.0;
    total += r.wall_seconds;
    total_broad += 1e-3 * broad_ms;
    iterations += r.iterations;
    failed += r.converged ? 0 : 1;
    if (contacts > 0.0) {
      ++contact_steps;
      contact_total += r.wall_seconds;
      contact_broad += 1e-3 * broad_ms;
      contact_iterations += r.iterations;
    }
    std::printf(
        "step %d: %s, %d iterations, %.0f ms (broad phase %.0f ms), min_distance %.3g, "
        "active_contacts %.0f\n",
        r.step, r.status.c_str(), r.iterations, 1e3 * r.wall_seconds, broad_ms,
        r.diagnostics.size() > 0 ? r.diagnostics[0] : -1.0, contacts);
  };
  ipstep::RunTrajectory(sim, run);
  std::printf(
      "%d x %d fold, %d steps, %d failed: %.1f iterations/step, %.0f ms/step (broad phase "
      "%.0f ms)\n",
      n, n, steps, failed, double(iterations) / steps, 1e3 * total / steps,
      1e3 * total_broad / steps);
  if (contact_steps > 0) {
    std::printf(
        "steps with self-contact (%d): %.1f iterations/step, %.0f ms/step (broad phase "
        "%.0f ms, %.0f %%)\n",
        contact_steps, double(contact_iterations) / contact_steps,
        1e3 * contact_total / contact_steps, 1e3 * contact_broad / contact_steps,
        100.0 * contact_broad / contact_total);
  }
  return 0;
}
