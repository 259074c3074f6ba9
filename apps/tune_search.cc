#include "apps/tune_search.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sim/run_trajectory.h"
#include "sim/step_size_controller.h"
#include "solver/optimizer_options.h"

namespace ipstep {
namespace tune {
namespace {

// The fixed steps of the search, coarse to fine, in units of the scene's step.
constexpr double kStepFactors[] = {2.0, 1.0, 0.5, 0.25, 0.125};
// The adaptive error tolerances, in units of the target.
constexpr double kAdaptiveShares[] = {1.0, 1.0 / 3.0, 0.1};

Candidate Fixed(const std::string& integrator, const std::string& optimizer, double dt,
                double tolerance) {
  Candidate c;
  c.integrator = integrator;
  c.optimizer = optimizer;
  c.dt = dt;
  c.tolerance = tolerance;
  return c;
}

// A step near `h` that ends on t_end.
double StepTo(double t_end, double h) { return t_end / std::max(1.0, std::round(t_end / h)); }

}  // namespace

double CostOf(const Candidate& c, Cost cost) {
  return cost == Cost::kIterations ? static_cast<double>(c.iterations) : c.seconds;
}

Candidate DefaultCandidate(double dt, double t_end) {
  Candidate c = Fixed("backward_euler", "newton", StepTo(t_end, dt), OptimizerOptions{}.tolerance);
  c.role = "default";
  return c;
}

std::string CommandLine(const std::string& scene, const Candidate& c, double t_end,
                        const std::vector<std::pair<std::string, std::string>>& extra) {
  char text[400];
  if (c.adaptive) {
    std::snprintf(text, sizeof(text),
                  "ipstep --scene=%s --integrator=%s --optimizer=%s --adaptive "
                  "--error_tolerance=%.3g --dt=%.6g --t_end=%.6g",
                  scene.c_str(), c.integrator.c_str(), c.optimizer.c_str(), c.error_tolerance, c.dt,
                  t_end);
  } else {
    std::snprintf(text, sizeof(text),
                  "ipstep --scene=%s --integrator=%s --optimizer=%s --dt=%.10g --t_end=%.6g "
                  "--tolerance=%.3g",
                  scene.c_str(), c.integrator.c_str(), c.optimizer.c_str(), c.dt, t_end,
                  c.tolerance);
  }
  static const std::set<std::string> own = {
      "scene",  "integrator", "optimizer",         "dt",
      "t_end",  "tolerance",  "adaptive",          "error_tolerance",
      "min_dt", "max_dt",     "filter_stiff_modes"};
  std::string line = text;
  for (const auto& [name, value] : extra) {
    if (own.count(name) || (c.adaptive && name == "max_substeps")) continue;
    // Shell-quoted unless plain (paths with spaces, lists with brackets).
    const bool plain = !value.empty() && value.find_first_not_of(
                                             "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVW"
                                             "XYZ0123456789._/:,+-=") == std::string::npos;
    std::string quoted = "'";
    for (char ch : value) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
    line += " --" + name + "=" + (plain ? value : quoted + "'");
  }
  return line;
}

std::string Label(const Candidate& c) {
  char text[200];
  if (c.adaptive) {
    std::snprintf(text, sizeof(text), "%s + %s, adaptive E = %.3g m", c.integrator.c_str(),
                  c.optimizer.c_str(), c.error_tolerance);
  } else {
    std::snprintf(text, sizeof(text), "%s + %s, h = %.4g s, tolerance %.3g m/s",
                  c.integrator.c_str(), c.optimizer.c_str(), c.dt, c.tolerance);
  }
  return text;
}

std::vector<Candidate> SearchSpace::Family(int f, std::vector<size_t>* starts) const {
  const std::string& integrator = integrators[f / optimizers.size()];
  const std::string& optimizer = optimizers[f % optimizers.size()];
  const double tied_tolerance = 0.1 * target / t_end;
  std::vector<Candidate> family;
  starts->clear();
  for (double tolerance : {default_tolerance, tied_tolerance}) {
    // A tied tolerance equal to the default would repeat the same runs.
    if (tolerance == tied_tolerance && tied_tolerance == default_tolerance && !family.empty()) {
      break;
    }
    starts->push_back(family.size());
    for (double factor : kStepFactors) {
      family.push_back(Fixed(integrator, optimizer, StepTo(t_end, dt * factor), tolerance));
    }
  }
  starts->push_back(family.size());
  for (double share : kAdaptiveShares) {
    Candidate c = Fixed(integrator, optimizer, dt, 0.0);
    c.adaptive = true;
    c.error_tolerance = target * share;
    c.tolerance = 0.1 * c.error_tolerance / t_end;
    family.push_back(c);
  }
  for (size_t k = 0; k < family.size(); ++k) {
    family[k].family = f;
    family[k].position = static_cast<int>(k);
  }
  return family;
}

Runner::Runner(const Scene& scene, const SimulationOptions& base, ErrorMeasure measure,
               double t_end, double budget_seconds)
    : scene_(scene),
      base_(base),
      measure_(measure),
      t_end_(t_end),
      budget_seconds_(budget_seconds),
      start_(std::chrono::steady_clock::now()) {}

double Runner::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

SimulationOptions CandidateOptions(const SimulationOptions& base, const Candidate& c, double t_end,
                                   RunOptions* run) {
  SimulationOptions options = base;
  options.integrator.name = c.integrator;
  options.optimizer.optimizer = ParseOptimizer(c.optimizer);
  options.optimizer.tolerance = c.tolerance;
  options.time_step = c.dt;
  if (c.adaptive) {
    run->adaptive = true;
    run->adaptive_options.error_tolerance = c.error_tolerance;
    run->adaptive_options.t_end = t_end;
    run->adaptive_options.initial_time_step = c.dt;
    options.accept_residual = AdaptiveStallResidual(run->adaptive_options);
    options.max_substeps = 1;
  } else {
    options.steps = static_cast<int>(std::llround(t_end / c.dt));
  }
  return options;
}

void Runner::Measure(Candidate* c, const ReferenceSolution* against) const {
  RunOptions run_options;
  const SimulationOptions options = CandidateOptions(base_, *c, t_end_, &run_options);
  run_options.max_wall_seconds = std::max(1.0, budget_seconds_ - elapsed());
  Simulation sim(scene_, options);
  const MeasuredRun measured = RunMeasured(sim, run_options, measure_, against);
  const RunSummary& run = measured.run;
  c->seconds = run.wall_seconds;
  c->steps = run.steps_done;
  c->failed = run.failed;
  c->iterations = run.iterations;
  c->status = run.message;
  c->error = measured.error;
}

bool Search(const SearchSpace& space, const Runner& runner, const ReferenceSolution* reference,
            int shard, int shards, std::vector<Candidate>* runs) {
  for (int f = shard; f < space.families(); f += shards) {
    std::vector<size_t> starts;
    const std::vector<Candidate> family = space.Family(f, &starts);
    starts.push_back(family.size());
    // Coarse to fine within each sequence; stop it at its first run within the target.
    for (size_t s = 0; s + 1 < starts.size(); ++s) {
      for (size_t k = starts[s]; k < starts[s + 1]; ++k) {
        if (runner.out_of_time()) return false;
        Candidate c = family[k];
        runner.Measure(&c, reference);
        std::fprintf(stderr, "ipstep_tune: %s: error %.3g, %.3f s, %d steps%s\n", Label(c).c_str(),
                     c.error, c.seconds, c.steps,
                     std::isnan(c.error) ? (" (" + c.status + ")").c_str() : "");
        runs->push_back(c);
        if (c.error <= space.within) break;
      }
    }
  }
  return true;
}

std::vector<size_t> ParetoFront(const std::vector<Candidate>& runs, Cost cost) {
  std::vector<size_t> measured;
  for (size_t k = 0; k < runs.size(); ++k) {
    if (!std::isnan(runs[k].error) && runs[k].failed == 0) measured.push_back(k);
  }
  std::stable_sort(measured.begin(), measured.end(), [&runs, cost](size_t a, size_t b) {
    return CostOf(runs[a], cost) < CostOf(runs[b], cost);
  });
  std::vector<size_t> front;
  double best_error = HUGE_VAL;
  for (size_t k : measured) {
    if (runs[k].error >= best_error) continue;
    best_error = runs[k].error;
    front.push_back(k);
  }
  return front;
}

}  // namespace tune
}  // namespace ipstep
