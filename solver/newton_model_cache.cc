#include "solver/newton_model_cache.h"

#include "solver/newton_model_cost.h"

namespace ipstep {

NewtonModelCache::NewtonModelCache(const IncrementalPotential* potential, std::vector<int> terms,
                                   std::vector<const double*> weights)
    : potential_(potential), terms_(std::move(terms)), weights_(std::move(weights)) {
  const int dim = potential_->dimension();
  size_t offset = 0;
  for (int t : terms_) {
    const Term& term = potential_->terms()[t];
    const int rows = ModelRows(term, dim);
    const int columns = dim * static_cast<int>(term.nodes.size());
    rows_.push_back(rows);
    columns_.push_back(columns);
    offset_.push_back(offset);
    offset += static_cast<size_t>(rows) * (1 + columns);
  }
  values_.resize(offset);
  energy_.resize(terms_.size());
  ok_.resize(terms_.size());
}

void NewtonModelCache::Compute(int k, const double* x, bool jacobians, EigenvalueFilter filter,
                               Scratch* scratch) {
  const Term& term = potential_->terms()[terms_[k]];
  const int dim = potential_->dimension();
  const int blocks = static_cast<int>(term.nodes.size());
  scratch->parameters.resize(blocks);
  for (int b = 0; b < blocks; ++b) scratch->parameters[b] = x + dim * term.nodes[b];
  ok_[k] = scratch->evaluator.Evaluate(term, dim, *weights_[k], scratch->parameters.data(),
                                       jacobians, &scratch->model);
  if (!ok_[k]) return;
  energy_[k] = scratch->model.energy;
  if (!jacobians) return;
  ProjectHessian(scratch->model, &scratch->projected, filter);
  double* residuals = values_.data() + offset_[k];
  double* jacobian = residuals + rows_[k];
  double* block_pointers[kMaxTermCoordinates];
  for (int b = 0; b < blocks; ++b) block_pointers[b] = jacobian + b * rows_[k] * dim;
  NewtonModelRows(term, dim, scratch->projected, residuals, block_pointers);
}

void NewtonModelCache::Prepare(const double* x, bool jacobians, EigenvalueFilter filter) {
  ThreadPool& pool = potential_->thread_pool();
  if (static_cast<int>(scratch_.size()) < pool.num_threads()) scratch_.resize(pool.num_threads());
  const int n = static_cast<int>(terms_.size());
  pool.ParallelFor(n, IncrementalPotential::kParallelGrain, [&](int begin, int end, int thread) {
    for (int k = begin; k < end; ++k) Compute(k, x, jacobians, filter, &scratch_[thread]);
  });
  prepared_ = true;
  with_jacobians_ = jacobians;
}

}  // namespace ipstep
