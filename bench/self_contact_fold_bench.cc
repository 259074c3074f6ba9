// An n x n cloth (1 m, 0.2 kg, one triangulation: structural springs and one
// shear diagonal per quad, squared strain k = 2e3, Hookean bending k = 50)
// folded on itself: the columns i < n/2 lie flat at y = 0, held fixed, the
// others are mirrored back over them, shifted by half a cell (nodes over
// faces) at height sqrt(3)/2 a, so that the one-cell crease is unstrained
// (rest lengths those of the flat grid; no bending springs across the
// crease). Gravity drops the top layer onto the bottom one (after ~15 steps):
// about n^2 / 2 nodes in self-contact. Runs `steps` steps of backward Euler with the Newton
// optimiser and prints iterations and wall time per step. Broad-phase cost:
// profile with perf (docs in the commit), or see bench/broad_phase_bench.cc
// for one pass on the same fold.
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
        s.positions.insert(s.positions.end(), {(n - 1 - i) * a + 0.5 * a, gap, j * a + 0.5 * a});
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
  double total = 0.0;
  int iterations = 0;
  for (int step = 0; step < steps; ++step) {
    const ipstep::StepReport r = sim.Step();
    total += r.wall_seconds;
    iterations += r.iterations;
    std::printf("step %d: %s, %d iterations, %.0f ms, min_distance %.3g, active_contacts %.0f\n",
                r.step, r.status.c_str(), r.iterations, 1e3 * r.wall_seconds,
                r.diagnostics.size() > 0 ? r.diagnostics[0] : -1.0,
                r.diagnostics.size() > 1 ? r.diagnostics[1] : -1.0);
  }
  std::printf("%d x %d fold: %.1f iterations/step, %.0f ms/step\n", n, n,
              double(iterations) / steps, 1e3 * total / steps);
  return 0;
}
