#include "sim/reference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/checkpoint_recorder.h"
#include "sim/run_trajectory.h"

namespace ipstep {

bool ExactPositions(const Scene& scene, double t, Eigen::VectorXd* x) {
  // The built-in scene (problems/oscillator.json), not a file that took its name.
  if (scene.name != "oscillator" || scene.source != "problems/oscillator.json") return false;
  if (x == nullptr) return true;
  *x = Eigen::Map<const Eigen::VectorXd>(scene.positions.data(), scene.positions.size());
  (*x)[2] = 1.0 + 0.1 * std::cos(t);
  return true;
}

double MaxNodeDistance(const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                       const std::vector<int>& nodes, int dimension) {
  if (x.size() != y.size() || x.size() == 0) return std::nan("");
  double worst = 0.0;
  for (int i : nodes) {
    const double distance =
        (x.segment(dimension * i, dimension) - y.segment(dimension * i, dimension)).norm();
    if (!std::isfinite(distance)) return std::nan("");  // std::max would drop a NaN
    worst = std::max(worst, distance);
  }
  return worst;
}

std::vector<int> FreeNodes(const State& state) {
  std::vector<int> nodes;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (state.is_free(i)) nodes.push_back(i);
  }
  return nodes;
}

std::string ReferenceIntegratorFor(const std::string& integrator) {
  return integrator == "quasi_static" ? "quasi_static" : "newmark";
}

ReferenceSolution ComputeReference(const Scene& scene, const SimulationOptions& base,
                                   const ReferenceOptions& reference, double dt_min, double t_end) {
  ReferenceSolution out;
  if (reference.checkpoints < 0 || reference.checkpoints > 10000) {
    throw InputError("options", "ReferenceOptions.checkpoints", "must be in [0, 10000]");
  }
  if (reference.integrator != "quasi_static" && ExactPositions(scene, t_end, &out.x)) {
    out.exact = out.ok = true;
    out.description = "exact solution";
    out.checkpoint_times = CheckpointTimes(0.0, t_end, reference.checkpoints);
    for (double t : out.checkpoint_times) {
      out.checkpoint_x.emplace_back();
      ExactPositions(scene, t, &out.checkpoint_x.back());
    }
    return out;
  }
  if (reference.refinement < 1 || reference.refinement > 1024) {
    throw InputError("options", "ReferenceOptions.refinement", "must be in [1, 1024]");
  }
  SimulationOptions options = base;
  options.integrator = IntegratorOptions{reference.integrator, 0.25, 0.5};
  options.optimizer = reference.optimizer;
  options.t_end = 0.0;  // the runs below set their steps
  Eigen::VectorXd x[2];
  std::vector<Eigen::VectorXd> checkpoint_x[2];
  std::vector<int> free_nodes;
  int dimension = scene.dimension;
  bool ok = true;
  std::string first_failure;
  for (int r = 0; r < 2; ++r) {
    const int refine = r == 0 ? reference.refinement : std::max(1, reference.refinement / 2);
    const double steps = std::max(1.0, std::round(t_end / dt_min * refine));
    if (!(steps <= limits::kMaxSteps)) {
      throw InputError("options", "ReferenceOptions.refinement",
                       "the reference would take " + limits::FormatLimit(steps) +
                           " steps, more than " + std::to_string(limits::kMaxSteps));
    }
    options.steps = static_cast<int>(steps);
    options.time_step = t_end / options.steps;
    Simulation sim(scene, options);
    RunOptions run_options;
    CheckpointRecorder recorder(CheckpointTimes(sim.state().time, t_end, reference.checkpoints));
    recorder.Attach(sim, &run_options);
    const RunSummary run = RunTrajectory(sim, run_options);
    x[r] = sim.state().x;
    checkpoint_x[r] = recorder.positions();
    if (r == 0) {
      out.checkpoint_times = recorder.times();
      out.dt = options.time_step;
      out.steps = run.steps_done;
      out.failed_steps = run.failed;
      free_nodes = FreeNodes(sim.state());
      dimension = sim.state().dimension;
    }
    if (run.failed > 0 || run.termination != RunTermination::kCompleted) {
      ok = false;
      if (first_failure.empty()) first_failure = run.message;
      if (run.first_failure.size() > 0 && run.termination == RunTermination::kCompleted) {
        first_failure =
            std::to_string(run.failed) + " failed steps (first: " + run.first_failure + ")";
      }
    }
  }
  const double order = reference.integrator == "newmark" ? 2.0 : 1.0;
  out.x = x[0];
  out.ok = ok;
  out.error = MaxNodeDistance(x[0], x[1], free_nodes, dimension) / (std::pow(2.0, order) - 1.0);
  // The checkpoints' error estimate as the end's. A run that stopped early
  // has fewer checkpoints: the missing ones are NaN, and so is the estimate.
  for (size_t j = 0; j < out.checkpoint_times.size(); ++j) {
    const bool both = j < checkpoint_x[0].size() && j < checkpoint_x[1].size();
    out.checkpoint_x.push_back(j < checkpoint_x[0].size()
                                   ? checkpoint_x[0][j]
                                   : Eigen::VectorXd::Constant(x[0].size(), std::nan("")));
    const double e =
        both ? MaxNodeDistance(checkpoint_x[0][j], checkpoint_x[1][j], free_nodes, dimension) /
                   (std::pow(2.0, order) - 1.0)
             : std::nan("");
    if (std::isnan(e) || std::isnan(out.checkpoint_error)) {
      out.checkpoint_error = std::nan("");
    } else {
      out.checkpoint_error = std::max(out.checkpoint_error, e);
    }
  }
  char text[200];
  std::snprintf(text, sizeof(text), "%s%s dt=%.4g tol=%g %s", reference.integrator.c_str(),
                reference.integrator == "newmark" ? "(1/4,1/2)" : "", out.dt,
                reference.optimizer.tolerance, OptimizerName(reference.optimizer.optimizer));
  out.description = text;
  if (!ok) out.description += " FAILED: " + first_failure;
  return out;
}

}  // namespace ipstep
