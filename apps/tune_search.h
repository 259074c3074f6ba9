// The search of ipstep_tune (apps/tune_program.cc): its candidate runs, the
// coarse-to-fine sequences of one integrator x optimiser family, how a run is
// measured, and the choice among the runs (the Pareto front and the pick).
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "problems/scene.h"
#include "sim/error_measure.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep {
namespace tune {

struct Candidate {
  std::string integrator, optimizer;
  bool adaptive = false;
  double dt = 0.0;               // fixed runs, and the first step of adaptive ones
  double tolerance = 0.0;        // solver [m/s]
  double error_tolerance = 0.0;  // adaptive [m]
  // Its place in the search: the family (SearchSpace::Family; -1 for the
  // default configuration) and its position in the family's list.
  int family = -1;
  int position = 0;
  // results
  double error = NAN, seconds = NAN;
  int steps = 0, failed = 0;
  long iterations = 0;  // solver iterations, rejected attempts included
  std::string status;
  // --tune_output: search (a run of the search), pick (the recommended one),
  // default (backward_euler + newton at the scene's step), timing (the
  // second runs of the pick and the default), validation (the pick against
  // the finer reference).
  std::string role = "search";
  std::string shard = "0/1";  // the shard that ran it (--shard)
};

// What a run costs, for the front and the pick (--tune_cost).
enum class Cost { kSeconds, kIterations };
double CostOf(const Candidate& c, Cost cost);

// The default configuration: backward_euler + newton at the scene's step `dt`
// (adjusted to end on t_end) with the default solver tolerance.
Candidate DefaultCandidate(double dt, double t_end);

// The ipstep command line that runs `c` to t_end, with `extra` flags (name,
// value) appended: what else the search's runs had (--grid_size, a pinned
// --contact_kappa, ...). Those the line sets itself (scene, integrator,
// optimizer, dt, t_end, tolerance and the adaptive ones) are skipped, and
// --max_substeps for an adaptive run, which refuses it.
std::string CommandLine(const std::string& scene, const Candidate& c, double t_end,
                        const std::vector<std::pair<std::string, std::string>>& extra = {});
// "newmark + newton, h = 0.01 s, tolerance 1e-05 m/s" / "..., adaptive E = 0.001 m".
std::string Label(const Candidate& c);

// The candidates of a search.
struct SearchSpace {
  std::vector<std::string> integrators, optimizers;
  double dt = 0.0;     // the scene's step [s]
  double t_end = 0.0;  // [s]
  double target = 0.0;
  double within = 0.0;             // an error at most this reaches the target
  double default_tolerance = 0.0;  // the solver's default tolerance [m/s]

  int families() const { return static_cast<int>(integrators.size() * optimizers.size()); }
  // Family f is integrators[f / optimizers.size()] x optimizers[f % optimizers.size()]:
  // fixed h = dt * {2, 1, 1/2, 1/4, 1/8} with the default solver tolerance and
  // with one tied to the target (0.1 E / T; once if they are equal), then
  // --adaptive with E = target * {1, 1/3, 1/10}. `starts`: where each
  // coarse-to-fine sequence begins (5 fixed h per tolerance, 3 adaptive).
  std::vector<Candidate> Family(int f, std::vector<size_t>* starts) const;
};

// Runs candidates of one scene and measures their errors.
// The simulation and run options of `c` on `base` to t_end (its integrator,
// optimiser, tolerance and step; an adaptive one's controller, as --adaptive
// sets it); `run`'s wall-time limit is left to the caller.
SimulationOptions CandidateOptions(const SimulationOptions& base, const Candidate& c, double t_end,
                                   RunOptions* run);

class Runner {
 public:
  Runner(const Scene& scene, const SimulationOptions& base, ErrorMeasure measure, double t_end,
         double budget_seconds);
  // Runs `c` and sets its results; its error against `against` (null for
  // the energy measure). A run stops once the budget is spent (at least 1 s).
  void Measure(Candidate* c, const ReferenceSolution* against) const;
  // Wall time since the runner was made [s]; whether it exceeds the budget.
  double elapsed() const;
  bool out_of_time() const { return elapsed() > budget_seconds_; }
  ErrorMeasure measure() const { return measure_; }

 private:
  const Scene& scene_;
  SimulationOptions base_;
  ErrorMeasure measure_;
  double t_end_, budget_seconds_;
  std::chrono::steady_clock::time_point start_;
};

// Runs the families f of `space` with f % shards == shard, in order, each
// sequence coarse to fine up to its first run within the target; appends
// them to `runs` (family and position set). False if the budget ran out.
bool Search(const SearchSpace& space, const Runner& runner, const ReferenceSolution* reference,
            int shard, int shards, std::vector<Candidate>* runs);

// The Pareto front of `runs`: the runs with an error and no failed step, by
// cost (equal costs in the order of `runs`), each more accurate than every
// cheaper one; indices into `runs`. The pick is the first of them within
// the target.
std::vector<size_t> ParetoFront(const std::vector<Candidate>& runs, Cost cost);

}  // namespace tune
}  // namespace ipstep
