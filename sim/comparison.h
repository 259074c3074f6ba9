// A comparison of integrators x optimisers on one scene: what ipstep_compare
// prints as its table (apps/compare_program.cc) and the Python module's
// ipstep.compare returns (python/). Every configuration runs the scene from
// its start through the run loop (sim/run_trajectory.h) with the base options'
// effects, step, tolerance and checks; its position error at the end time is
// measured against the exact solution where known (the oscillator), else
// against a Newmark reference at dt/16 with a tight tolerance
// (sim/reference.h), whose own error is estimated from a dt/8 run.
#pragma once

#include <csignal>
#include <functional>
#include <string>
#include <vector>

#include "problems/scene.h"
#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep {

// The default lists (ipstep_compare's --integrators and --optimizers): bfgs
// and gradient_descent are left out, slow on large scenes.
constexpr const char* kCompareIntegrators = "backward_euler,newmark,symplectic_euler";
constexpr const char* kCompareOptimizers = "newton,dogleg,gauss_newton,projected_newton,lbfgs,ncg";

struct ComparisonOptions {
  std::vector<std::string> integrators;  // names (IntegratorOptions.name)
  std::vector<std::string> optimizers;   // names (OptimizerOptions.optimizer)
  // The reference's tolerance [m/s]: near the precision floor of cost-based
  // acceptance (docs/optimisers.md "Precision floor").
  double reference_tolerance = 1e-7;
  // Read between steps (RunOptions::interrupt): once non-zero, the
  // configuration in progress stops and no other starts.
  const volatile std::sig_atomic_t* interrupt = nullptr;
  // Called after every step of every run (RunOptions::after_step); may be empty.
  std::function<void(const StepReport& report)> after_step;
};
// The default lists, split.
ComparisonOptions DefaultComparisonOptions();

struct ComparisonRow {
  std::string integrator;
  std::string optimizer;  // "" for an explicit integrator (no optimiser)
  double dt = 0.0;        // [s]
  RunSummary run;
  // Final-time max node distance from the reference [m]; NaN for a diverged run.
  double position_error = 0.0;
};

struct Comparison {
  double dt = 0.0;  // [s]
  int steps = 0;
  double t_end = 0.0;      // [s]
  double tolerance = 0.0;  // the runs' stopping tolerance [m/s]
  ReferenceSolution reference;
  // "newmark(...) ... (0 of 320 steps not converged); its estimated error 7.83e-06 m"
  std::string reference_note;
  std::vector<ComparisonRow> rows;  // integrators x optimisers, one row per explicit integrator
  bool interrupted = false;         // ComparisonOptions::interrupt stopped it
};

// What a caller sees of a comparison as it goes; each may be empty.
struct ComparisonCallbacks {
  std::function<void()> before_reference;  // before the reference runs (not for an exact one)
  // Once the reference is known (dt, steps, t_end, tolerance, reference set; no rows yet).
  std::function<void(const Comparison& comparison)> after_reference;
  // After each row, with the rows done and their total.
  std::function<void(const ComparisonRow& row, int done, int total)> after_row;
};

// Throws InputError for an unknown integrator or optimiser name (naming
// IntegratorOptions.name or OptimizerOptions.optimizer) or invalid options, as
// Simulation does.
Comparison RunComparison(const Scene& scene, const SimulationOptions& base,
                         const ComparisonOptions& options,
                         const ComparisonCallbacks& callbacks = {});

}  // namespace ipstep
