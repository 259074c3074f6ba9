#include "solver/newton_model_cache.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "solver/inertia_absorption.h"
#include "solver/newton_model_cost.h"

namespace ipstep {

NewtonModelCache::NewtonModelCache(const IncrementalPotential* potential, std::vector<int> terms,
                                   std::vector<const double*> weights, bool absorb,
                                   const State* state)
    : potential_(potential),
      terms_(std::move(terms)),
      weights_(std::move(weights)),
      absorb_(absorb),
      state_(state) {
  const int dim = potential_->dimension();
  size_t offset = 0, blocks = 0;
  for (int t : terms_) {
    const Term& term = potential_->terms()[t];
    const int columns = dim * static_cast<int>(term.nodes.size());
    const int rows = absorb_ ? columns : ModelRows(term, dim);
    rows_.push_back(rows);
    columns_.push_back(columns);
    offset_.push_back(offset);
    offset += static_cast<size_t>(rows) * (1 + columns);
    inertia_.push_back(term.kind == TermKind::kInertia);
    block_offset_.push_back(blocks);
    blocks += term.nodes.size() * dim * dim;
  }
  values_.resize(offset);
  energy_.resize(terms_.size());
  ok_.resize(terms_.size());
  if (absorb_) {
    blocks_.resize(blocks);
    negative_.resize(terms_.size());
    share_.resize(terms_.size());
    node_sum_.resize(static_cast<size_t>(potential_->num_nodes()) * dim * dim);
    node_inertia_.resize(potential_->num_nodes());
    node_share_.resize(potential_->num_nodes());
  }
}

bool NewtonModelCache::Evaluate(int k, const double* x, Scratch* scratch) {
  const Term& term = potential_->terms()[terms_[k]];
  const int dim = potential_->dimension();
  const int blocks = static_cast<int>(term.nodes.size());
  scratch->parameters.resize(blocks);
  for (int b = 0; b < blocks; ++b) scratch->parameters[b] = x + dim * term.nodes[b];
  return scratch->evaluator.Evaluate(term, dim, *weights_[k], scratch->parameters.data(), true,
                                     &scratch->model);
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
  // Rows beyond the model's own (kInertia: one per coordinate) stay zero.
  std::fill(residuals, residuals + static_cast<size_t>(rows_[k]) * (1 + columns_[k]), 0.0);
  double* block_pointers[kMaxTermCoordinates];
  for (int b = 0; b < blocks; ++b) block_pointers[b] = jacobian + b * rows_[k] * dim;
  NewtonModelRows(term, dim, scratch->projected, residuals, block_pointers);
}

void NewtonModelCache::PrepareAbsorbed(const double* x, EigenvalueFilter filter) {
  ThreadPool& pool = potential_->thread_pool();
  const int n = static_cast<int>(terms_.size());
  const int dim = potential_->dimension();
  const int d2 = dim * dim;
  const auto& terms = potential_->terms();
  std::fill(node_inertia_.begin(), node_inertia_.end(), 0.0);
  // 1. Every term's model, its clamped rows (the fallback) and its negative
  //    curvature's node blocks; the inertia terms' w_I m.
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    Scratch* scratch = &scratch_[thread];
    FullMatrix full;
    FullVector gradient;
    for (int k = begin; k < end; ++k) {
      Compute(k, x, true, filter, scratch);
      negative_[k] = 0;
      if (!ok_[k]) continue;
      const Term& term = terms[terms_[k]];
      if (inertia_[k]) {
        node_inertia_[term.nodes[0]] = scratch->model.hessian(0, 0);
        continue;
      }
      if (term.gauss_newton_model) continue;
      FullHessian(term, dim, scratch->model, &full, &gradient);
      negative_[k] =
          NegativeCurvatureBlocks(scratch->model, full, static_cast<int>(term.nodes.size()), dim,
                                  term.pair_difference, blocks_.data() + block_offset_[k]);
    }
  });
  // 2. The nodes' sums, in term order. A free node whose sum is over its
  //    budget (every node without inertia) scales its terms' blocks down;
  //    the sums again with the scaled blocks, within every budget.
  auto sum_blocks = [&](const std::vector<char>& use, const std::vector<double>* share) {
    std::fill(node_sum_.begin(), node_sum_.end(), 0.0);
    for (int k = 0; k < n; ++k) {
      if (!use[k]) continue;
      const double scale = share != nullptr ? (*share)[k] : 1.0;
      const Term& term = terms[terms_[k]];
      for (size_t b = 0; b < term.nodes.size(); ++b) {
        const double* block = blocks_.data() + block_offset_[k] + b * d2;
        double* sum = node_sum_.data() + static_cast<size_t>(term.nodes[b]) * d2;
        for (int i = 0; i < d2; ++i) sum[i] += scale * block[i];
      }
    }
  };
  sum_blocks(negative_, nullptr);
  // A node's share: the largest s <= 1 with s sum_t D_t,i within its budget;
  // a term takes the least share of its nodes.
  std::fill(node_share_.begin(), node_share_.end(), 1.0);
  for (int i = 0; i < potential_->num_nodes(); ++i) {
    if (!state_->is_free(i)) continue;
    const Eigen::Map<const Eigen::MatrixXd> sum(node_sum_.data() + static_cast<size_t>(i) * d2, dim,
                                                dim);
    if (sum.cwiseAbs().maxCoeff() == 0.0) continue;
    const double largest =
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sum).eigenvalues().maxCoeff();
    const double budget = kInertiaBudget * node_inertia_[i];
    node_share_[i] = largest > budget ? std::max(0.0, budget / largest) : 1.0;
  }
  absorbed_count_ = clamped_count_ = 0;
  for (int k = 0; k < n; ++k) {
    share_[k] = 0.0;
    if (!negative_[k]) continue;
    double share = 1.0;
    for (int node : terms[terms_[k]].nodes) {
      if (state_->is_free(node)) share = std::min(share, node_share_[node]);
    }
    share_[k] = share;
    ++(share == 1.0 ? absorbed_count_ : clamped_count_);
  }
  sum_blocks(negative_, &share_);
  // 3. The absorbed terms' rows (H_t + D_t) and the inertia terms' rows
  //    (w_I m I minus the node's sum).
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    Scratch* scratch = &scratch_[thread];
    FullMatrix full;
    FullVector gradient;
    double* pointers[kMaxTermCoordinates];
    for (int k = begin; k < end; ++k) {
      if (!ok_[k] || !((negative_[k] && share_[k] > 0.0) || inertia_[k])) continue;
      const Term& term = terms[terms_[k]];
      if (!Evaluate(k, x, scratch)) {
        ok_[k] = 0;
        continue;
      }
      FullHessian(term, dim, scratch->model, &full, &gradient);
      const int blocks = static_cast<int>(term.nodes.size());
      const double sign = inertia_[k] ? -1.0 : share_[k];
      for (int b = 0; b < blocks; ++b) {
        const double* block = inertia_[k]
                                  ? node_sum_.data() + static_cast<size_t>(term.nodes[b]) * d2
                                  : blocks_.data() + block_offset_[k] + b * d2;
        for (int i = 0; i < dim; ++i) {
          for (int j = 0; j < dim; ++j) full(b * dim + i, b * dim + j) += sign * block[i * dim + j];
        }
      }
      double* residuals = values_.data() + offset_[k];
      for (int b = 0; b < blocks; ++b) pointers[b] = residuals + rows_[k] + b * rows_[k] * dim;
      // H_t + s D_t: positive semi-definite for s = 1; MatrixRows clamps what
      // is left negative for a share s < 1.
      MatrixRows(full, gradient, dim, rows_[k], residuals, pointers);
    }
  });
}

void NewtonModelCache::Prepare(const double* x, bool jacobians, EigenvalueFilter filter) {
  ThreadPool& pool = potential_->thread_pool();
  if (static_cast<int>(scratch_.size()) < pool.num_threads()) scratch_.resize(pool.num_threads());
  const int n = static_cast<int>(terms_.size());
  if (absorb_ && jacobians) {
    PrepareAbsorbed(x, filter);
  } else {
    const int grain =
        jacobians ? IncrementalPotential::kModelGrain : IncrementalPotential::kEnergyGrain;
    pool.ParallelFor(n, grain, [&](int begin, int end, int thread) {
      for (int k = begin; k < end; ++k) Compute(k, x, jacobians, filter, &scratch_[thread]);
    });
  }
  prepared_ = true;
  with_jacobians_ = jacobians;
}

}  // namespace ipstep
