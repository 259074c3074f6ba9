// The incremental potential of one time step: the step context (what the
// integrator sets before each step) and the list of energy terms. Terms are
// added once per scene; only the context changes between steps.
//
// Evaluation here loops over the terms' own cost functions (no ceres::Problem
// overhead); it serves the line-search optimisers (solver/first_order_potential.h),
// the stopping rule, force and energy reports. The trust-region optimisers hand
// the very same cost functions to a ceres::Problem (solver/trust_region_solver.h).
//
// The loop runs on the potential's thread pool (SetNumThreads; core/thread_pool.h):
// each term's energy and gradient go to memory of that term, and are summed
// afterwards in term order, so the results are the same for any number of
// threads. Terms' cost functions must therefore be safe to call concurrently
// (Ceres's own rule for cost functions); step filters are called on the
// calling thread only.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/step_context.h"
#include "core/step_filter.h"
#include "core/term.h"
#include "core/thread_pool.h"

namespace ipstep {

class IncrementalPotential {
 public:
  IncrementalPotential(int dimension, int num_nodes);

  StepContext& context() { return *context_; }
  const StepContext& context() const { return *context_; }
  int dimension() const { return dimension_; }
  int num_nodes() const { return num_nodes_; }

  // Checks node indices and parameter block sizes (throws std::invalid_argument).
  void AddTerm(Term term);
  // A new term group (Term::group, > 0) for an owner that removes its terms
  // and adds them again (the contact state: every step's pairs).
  int NewTermGroup() { return ++term_groups_; }
  // Removes every term of `group` (> 0); returns how many.
  int RemoveTerms(int group);
  const std::vector<Term>& terms() const { return terms_; }
  int CountTerms(TermKind kind) const;
  // Changes whenever terms are added or removed: solvers that mirror the terms
  // (the ceres::Problem) rebuild when it differs from the version they built.
  int structure_version() const { return structure_version_; }

  // Step filters (core/step_filter.h), owned. Evaluate() fails at trial points
  // that any filter rejects.
  void AddStepFilter(std::unique_ptr<StepFilter> filter);
  void NotifyAccepted(const double* x) const;
  bool IsStepValid(const double* x) const;
  double MaxStepSize(const double* from, const double* to) const;
  bool IsFeasible(const double* x) const;
  // Every filter's CheckState: penetration if any says so, else a moving
  // boundary not reached if any says so; and the earliest ReachedTime.
  StepFilter::Infeasibility CheckState(const double* x) const;
  double ReachedTime() const;
  bool has_step_filters() const { return !filters_.empty(); }
  const std::vector<std::unique_ptr<StepFilter>>& step_filters() const { return filters_; }

  using TermFilter = std::function<bool(const Term&)>;

  // E(x) = sum of weighted term energies, and its gradient (full length,
  // dimension * num_nodes; may be null). Returns false when a term cannot be
  // evaluated at x (infeasible point) or the result is not finite.
  bool Evaluate(const double* x, double* energy, double* gradient) const;

  // Sum of UNWEIGHTED energies (and gradient) of the terms passing `filter`.
  // For the terms with a frame velocity u (core/term.h): the sum over them of
  // dR/dx_k . u at x, unweighted (false if one cannot be evaluated).
  bool FrameDissipationRate(const double* x, double* rate) const;
  bool EvaluateUnweighted(const TermFilter& filter, const double* x, double* energy,
                          double* gradient) const;

  // E(x) with residuals in extended precision where terms provide them.
  bool EvaluatePreciseEnergy(const double* x, long double* energy) const;

  // The threads term loops run on (1 at construction); the solvers' own
  // loops over terms use the same pool.
  void SetNumThreads(int threads);
  ThreadPool& thread_pool() const { return *pool_; }
  // Terms per thread below which a loop stays on the calling thread: for
  // energies and gradients (about 0.1 us a spring), and for Newton models
  // (about 1-3 us a tetrahedron). Measured on the 20 x 20 cloth (1,880 terms):
  // with 256 for both, 2 threads made lbfgs 28 -> 41 ms and newton 5.8 -> 7.1
  // ms per step (waking the team costs more than the work it shares).
  static constexpr int kEnergyGrain = 4096;
  static constexpr int kModelGrain = 512;

 private:
  // Per-thread evaluation memory.
  struct Scratch {
    std::vector<double> residuals;
    std::vector<long double> precise_residuals;
    std::vector<double> jacobian_storage;
    std::vector<double*> jacobians;
    std::vector<const double*> parameters;
  };
  bool Accumulate(const TermFilter& filter, bool weighted, const double* x, double* energy,
                  double* gradient) const;
  // Term t's weighted (or not) energy and, with `gradient`, its gradient
  // into term_gradient_ at gradient_offset_[t]. False if it cannot be
  // evaluated at x.
  bool EvaluateTerm(int t, double weight, const double* x, bool gradient, Scratch* scratch) const;
  bool PreciseTermEnergy(int t, double weight, const double* x, Scratch* scratch) const;
  void ResizeScratch() const;

  int dimension_;
  int num_nodes_;
  std::unique_ptr<StepContext> context_;  // stable address: terms point into it
  std::vector<Term> terms_;
  std::vector<std::unique_ptr<StepFilter>> filters_;
  int structure_version_ = 0;
  int term_groups_ = 0;  // the last NewTermGroup
  int max_residuals_ = 0;
  int max_nodes_ = 0;
  std::unique_ptr<ThreadPool> pool_;
  // Evaluation memory (mutable: Evaluate is logically const): per thread,
  // and per term (energies, ok flags, gradients at gradient_offset_[t]).
  mutable std::vector<Scratch> scratch_;
  mutable std::vector<double> term_energy_;
  mutable std::vector<long double> term_precise_energy_;
  mutable std::vector<char> term_ok_;
  mutable std::vector<double> term_gradient_;
  std::vector<int> gradient_offset_;
};

}  // namespace ipstep
