// The Newton models of the terms Ceres's newton and dogleg see through
// NewtonModelCost (solver/newton_model_cost.h), computed for one evaluation
// point on the potential's thread pool (core/thread_pool.h) before Ceres
// evaluates its residual blocks, so that each block's Evaluate only copies
// its rows. The trust-region solver calls Prepare from its
// ceres::EvaluationCallback, when the parameter memory holds the point Ceres
// is about to evaluate (solver/trust_region_solver.h).
//
// Each term's model depends on that term and the point alone, and Ceres runs
// its own evaluation on one thread (summing block costs in block order), so
// the iterates are the same for any number of threads.
#pragma once

#include <vector>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "core/term_hessian.h"

namespace ipstep {

class NewtonModelCache {
 public:
  // `terms`: the potential's indices of the terms given to Ceres as
  // NewtonModelCost; `weights`: per term, where its family's step weight is
  // read (StepContext).
  // With `absorb` (the kInertia projection, solver/inertia_absorption.h) the
  // terms include the inertia terms, every term has one row per coordinate,
  // and models with jacobians are the absorbed ones; `state` tells free nodes.
  NewtonModelCache(const IncrementalPotential* potential, std::vector<int> terms,
                   std::vector<const double*> weights, bool absorb = false,
                   const State* state = nullptr);
  // Rows of the k-th term's model (NewtonModelCost's residuals).
  int rows(int k) const { return rows_[k]; }
  // kInertia: terms whose negative curvature the inertia absorbed, and those
  // it absorbed in part (the rest clamped), in the last prepared model.
  long absorbed() const { return absorbed_count_; }
  long clamped() const { return clamped_count_; }

  // Every term's weighted energy at x (full positions), and with `jacobians`
  // its model rows (residuals r^ and Jacobian J^ of NewtonModelCost) with
  // the given eigenvalue filter.
  void Prepare(const double* x, bool jacobians, EigenvalueFilter filter);
  // Forgets the prepared point (Ceres will evaluate somewhere else).
  void Invalidate() { prepared_ = false; }

  // Whether the cache holds the terms' energies (and with `jacobians` their
  // rows) for the current point.
  bool Has(bool jacobians) const { return prepared_ && (!jacobians || with_jacobians_); }
  bool ok(int k) const { return ok_[k] != 0; }
  double energy(int k) const { return energy_[k]; }
  // Rows of the k-th term: `rows` residuals, then rows x columns Jacobian
  // entries, row-major over the term's model coordinates.
  const double* residuals(int k) const { return values_.data() + offset_[k]; }
  const double* jacobian(int k) const { return values_.data() + offset_[k] + rows_[k]; }

 private:
  struct Scratch {
    TermModelEvaluator evaluator;
    TermModel model;
    ProjectedHessian projected;
    std::vector<const double*> parameters;
  };
  void Compute(int k, const double* x, bool jacobians, EigenvalueFilter filter, Scratch* scratch);
  // The absorbed models (solver/inertia_absorption.h).
  void PrepareAbsorbed(const double* x, EigenvalueFilter filter);
  bool Evaluate(int k, const double* x, Scratch* scratch);

  const IncrementalPotential* potential_;
  std::vector<int> terms_;
  std::vector<const double*> weights_;
  std::vector<int> rows_;
  std::vector<int> columns_;
  std::vector<size_t> offset_;
  std::vector<double> values_;
  std::vector<double> energy_;
  std::vector<char> ok_;
  std::vector<Scratch> scratch_;
  // kInertia: per term whether it is an inertia term, its negative
  // curvature's node blocks (at block_offset_) and whether it has any (and
  // was absorbed); per node the blocks' sum and its inertia w_I m.
  bool absorb_ = false;
  const State* state_ = nullptr;
  std::vector<char> inertia_;
  std::vector<size_t> block_offset_;
  std::vector<double> blocks_;
  std::vector<char> negative_;
  std::vector<double> share_;  // of the term's blocks the inertia takes
  std::vector<double> node_share_;
  std::vector<double> node_sum_;
  std::vector<double> node_inertia_;
  long absorbed_count_ = 0;
  long clamped_count_ = 0;
  bool prepared_ = false;
  bool with_jacobians_ = false;
};

}  // namespace ipstep
