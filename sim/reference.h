// Reference solutions and the error measures taken against them: what
// ipstep_compare and ipstep_bench call "position error" (every measure:
// sim/error_measure.h).
//
// Where the exact solution is known (the built-in oscillator: x = 1 + 0.1 cos t)
// it is the reference. Otherwise the reference is a fine run of the scene: the
// trapezoidal rule (Newmark 1/4, 1/2; second order) for dynamic integrators,
// quasi_static for quasi_static (a different problem), at dt_min / refinement
// with a tight tolerance, and again at twice that step to estimate its own
// error by Richardson: e ~ |x(2 dt_ref) - x(dt_ref)| / (2^p - 1).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "problems/scene.h"
#include "sim/simulation.h"

namespace ipstep {

// The exact positions of every node at time t where known (the built-in
// oscillator, omega = 1, u0 = 0.1, from rest); false otherwise. With x null:
// whether they are known.
bool ExactPositions(const Scene& scene, double t, Eigen::VectorXd* x);

// The largest distance |x_i - y_i| [m] over the listed nodes; NaN if the sizes
// differ, a vector is empty or a distance is not finite.
double MaxNodeDistance(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                       const std::vector<int>& nodes, int dimension);
// The free nodes of a state (those the error is measured on).
std::vector<int> FreeNodes(const State& state);

struct ReferenceOptions {
  // The integrator of the reference: "newmark" (order 2) or "quasi_static"
  // (order 1); ReferenceIntegratorFor picks it from the runs' integrator.
  std::string integrator = "newmark";
  // Its optimiser and tolerance (tight: near the precision floor).
  OptimizerOptions optimizer;
  // dt_ref = dt_min / refinement; the error estimate runs at 2 dt_ref.
  int refinement = 16;
  // Also the positions at K = `checkpoints` times t_end j / K, j = 1 .. K
  // (sim/checkpoint_recorder.h), for the max_position measure
  // (sim/error_measure.h); in [0, 10000], 0: none.
  int checkpoints = 0;
};
std::string ReferenceIntegratorFor(const std::string& integrator);

struct ReferenceSolution {
  Eigen::VectorXd x;     // positions at t_end
  double dt = 0.0;       // its step [s]
  double error = 0.0;    // its estimated own error [m] (0 for the exact solution)
  bool exact = false;    // the exact solution
  bool ok = false;       // both runs completed with no failed step
  int failed_steps = 0;  // of the fine run
  int steps = 0;         // of the fine run
  std::string description;
  // With ReferenceOptions::checkpoints: their times [s] (the last is t_end),
  // the positions there, and the estimated own error, the largest over them [m].
  std::vector<double> checkpoint_times;
  std::vector<Eigen::VectorXd> checkpoint_x;
  double checkpoint_error = 0.0;
};

// The reference at t_end (and at its checkpoints) for runs of `scene` with
// time steps >= dt_min: `base` gives the effects and their overrides, the
// energy check and the substeps; its integrator, optimiser and step are
// replaced by `reference`'s.
// Throws InputError for invalid options (as Simulation does).
ReferenceSolution ComputeReference(const Scene& scene, const SimulationOptions& base,
                                   const ReferenceOptions& reference, double dt_min, double t_end);

}  // namespace ipstep
