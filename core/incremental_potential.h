// The incremental potential of one time step: the step context (what the
// integrator sets before each step) and the list of energy terms. Terms are
// added once per scene; only the context changes between steps.
//
// Evaluation here loops over the terms' own cost functions (no ceres::Problem
// overhead); it serves the line-search optimisers (solver/first_order_potential.h),
// the stopping rule, force and energy reports. The trust-region optimisers hand
// the very same cost functions to a ceres::Problem (solver/trust_region_solver.h).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "core/step_context.h"
#include "core/step_filter.h"
#include "core/term.h"

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
  // Removes every term of `family` (e.g. to rebuild a contact set); returns how many.
  int RemoveTerms(const std::string& family);
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
  bool has_step_filters() const { return !filters_.empty(); }
  const std::vector<std::unique_ptr<StepFilter>>& step_filters() const { return filters_; }

  using TermFilter = std::function<bool(const Term&)>;

  // E(x) = sum of weighted term energies, and its gradient (full length,
  // dimension * num_nodes; may be null). Returns false when a term cannot be
  // evaluated at x (infeasible point) or the result is not finite.
  bool Evaluate(const double* x, double* energy, double* gradient) const;

  // Sum of UNWEIGHTED energies (and gradient) of the terms passing `filter`.
  bool EvaluateUnweighted(const TermFilter& filter, const double* x, double* energy,
                          double* gradient) const;

  // E(x) with residuals in extended precision where terms provide them.
  bool EvaluatePreciseEnergy(const double* x, long double* energy) const;

 private:
  bool Accumulate(const TermFilter& filter, bool weighted, const double* x, double* energy,
                  double* gradient) const;

  int dimension_;
  int num_nodes_;
  std::unique_ptr<StepContext> context_;  // stable address: terms point into it
  std::vector<Term> terms_;
  std::vector<std::unique_ptr<StepFilter>> filters_;
  int structure_version_ = 0;
  int max_residuals_ = 0;
  int max_nodes_ = 0;
  // Scratch for evaluation (mutable: Evaluate is logically const).
  mutable std::vector<double> residuals_;
  mutable std::vector<long double> precise_residuals_;
  mutable std::vector<double> jacobian_storage_;
  mutable std::vector<double*> jacobians_;
  mutable std::vector<const double*> parameters_;
};

}  // namespace ipstep
