// Building blocks of ipstep_bench: one timed run of a scene (its optimiser:
// bench/optimizer_spec.h), reference solutions and the CSV row format. See docs/benchmarks.md.
#pragma once

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Core>

#include "bench/optimizer_spec.h"
#include "sim/reference.h"
#include "sim/simulation.h"
#include "solver/projected_newton_solver.h"

namespace ipstep {
namespace bench {

struct RunConfig {
  int id = 0;  // position in the sweep (rows are merged back in this order)
  std::string scene;
  int grid_size = 0;  // 0: the scene's
  std::string integrator;
  std::string optimizer;  // spec text
  double dt = 0.0;
  int steps = 0;
  double tolerance = 1e-6;
  int repeats = 1;
  int warmup = 0;
  double max_run_seconds = 0.0;  // one run stops (status "timeout") beyond this; 0: none
  // The effects scenes are loaded and built with; null: DefaultEffects().
  const EffectRegistry* effects = nullptr;
};

// What one run (one trajectory) produced.
struct Trajectory {
  Eigen::VectorXd final_x;
  std::vector<int> free_nodes;
  double initial_energy = 0.0;
  // max_n |E_n - E_0| / E_s(t_n), in the divergence rule's energy scales
  // (sim/divergence.h)
  double max_energy_drift = 0.0;
  int steps_done = 0;
  int failed_steps = 0;
  double worst_residual = 0.0;  // largest stopping measure at the end of a step [m/s]
  long iterations = 0;
  int max_step_iterations = 0;
  long evaluations = 0;
  double loop_seconds = 0.0;   // Step() loop
  double setup_seconds = 0.0;  // scene loading + Simulation construction
  // ok | failed steps (first: ...) | diverged at step N (sim/divergence.h: the
  // run stops there) | timeout after N steps | error: ...
  std::string status = "ok";
  int nodes = 0;
  int free_dofs = 0;
  int dimension = 2;
  // projected_newton only: time per phase over the run.
  ProjectedNewtonSolver::Timings phases;
};

// Runs config.steps steps once. Never throws for run failures (they go into
// status); throws InputError only for an invalid config.
Trajectory RunConfiguration(const RunConfig& config, const OptimizerSpec& spec);

// One CSV row per config.
struct RunRow {
  RunConfig config;
  Trajectory result;            // of the last repeat
  std::vector<double> wall;     // loop seconds per timed repeat
  double position_error = 0.0;  // final time, max over free nodes [m]
  std::string reference;        // "exact" or a description
  double reference_dt = 0.0;
  double reference_error = 0.0;  // estimated error of the reference itself [m]
  std::string shard;
  int configurations = 0;  // in the whole sweep (all shards): ipstep_bench --merge checks them
};

std::string CsvHeader();
std::string CsvRow(const RunRow& row);

// Reference final positions for (scene, grid, integrator family, t_end)
// (sim/reference.h: ComputeReference), computed once per key.
class ReferenceCache {
 public:
  ReferenceCache(std::string optimizer, double tolerance, const EffectRegistry* effects = nullptr)
      : optimizer_(std::move(optimizer)), tolerance_(tolerance), effects_(effects) {}
  // Keeps every reference also as a file in `directory` (created if needed)
  // and reads it from there when another run of the same sweep (a shard, or a
  // later sweep of the same build) computed it: one file per key (scene, grid,
  // method, dt_min, t_end, optimiser, tolerance, commit), written to a
  // temporary name and renamed, so shards on one host share them safely
  // (io/reference_file.h; shards that need one at once compute it once).
  void set_directory(std::string directory) { directory_ = std::move(directory); }
  int computed() const { return computed_; }  // references computed (not read)
  const ReferenceSolution& Get(const std::string& scene, int grid_size,
                               const std::string& integrator, double dt_min, double t_end);

 private:
  std::string optimizer_;
  double tolerance_;
  const EffectRegistry* effects_;
  std::string directory_;
  int computed_ = 0;
  std::map<std::tuple<std::string, int, std::string, double, double>, ReferenceSolution> cache_;
};

}  // namespace bench
}  // namespace ipstep
