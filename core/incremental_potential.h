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
  const std::vector<Term>& terms() const { return terms_; }
  int CountTerms(TermKind kind) const;

  using TermFilter = std::function<bool(const Term&)>;

  // E(x) = sum of weighted term energies, and its gradient (full length,
  // dimension * num_nodes; may be null). Returns false when a term cannot be
  // evaluated at x (infeasible point) or the result is not finite.
  bool Evaluate(const double* x, double* energy, double* gradient) const;

  // Sum of UNWEIGHTED energies (and gradient) of the terms passing `filter`.
  bool EvaluateUnweighted(const TermFilter& filter, const double* x, double* energy,
                          double* gradient) const;

 private:
  bool Accumulate(const TermFilter& filter, bool weighted, const double* x, double* energy,
                  double* gradient) const;

  int dimension_;
  int num_nodes_;
  std::unique_ptr<StepContext> context_;  // stable address: terms point into it
  std::vector<Term> terms_;
  int max_residuals_ = 0;
  int max_nodes_ = 0;
  // Scratch for evaluation (mutable: Evaluate is logically const).
  mutable std::vector<double> residuals_;
  mutable std::vector<double> jacobian_storage_;
  mutable std::vector<double*> jacobians_;
  mutable std::vector<const double*> parameters_;
};

}  // namespace ipstep
