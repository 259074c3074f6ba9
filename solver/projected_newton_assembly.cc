// ProjectedNewtonSolver (solver/projected_newton_solver.h): the sparse Hessian
// over the free degrees of freedom. Its pattern and each term's slots in it
// (once per term structure), the terms' local model Hessians (exact, clamped
// or absolute) on the potential's thread pool, and their sum in term order.
#include "solver/projected_newton_solver.h"

#include <algorithm>
#include <vector>

#include "core/scoped_timer.h"

namespace ipstep {

void ProjectedNewtonSolver::BuildStructure() {
  factorised_in_solve_ = false;  // the free DOFs and the pattern may change
  const auto start = WallClock::now();
  const int dim = state_->dimension;
  free_index_.assign(state_->num_dofs(), -1);
  num_free_ = 0;
  for (int i = 0; i < state_->num_nodes(); ++i) {
    if (!state_->is_free(i)) continue;
    for (int k = 0; k < dim; ++k) free_index_[dim * i + k] = num_free_++;
  }
  // Local index l = b * dim + k of a term maps to DOF dim * nodes[b] + k.
  auto free_of = [&](const Term& term, int l) {
    return free_index_[dim * term.nodes[l / dim] + l % dim];
  };
  std::vector<Eigen::Triplet<double>> triplets;
  for (int d = 0; d < num_free_; ++d) triplets.emplace_back(d, d, 0.0);
  for (const Term& term : potential_->terms()) {
    const int nt = dim * static_cast<int>(term.nodes.size());
    for (int a = 0; a < nt; ++a) {
      for (int b = 0; b < a; ++b) {
        const int fa = free_of(term, a), fb = free_of(term, b);
        if (fa >= 0 && fb >= 0) triplets.emplace_back(std::max(fa, fb), std::min(fa, fb), 0.0);
      }
    }
  }
  hessian_.resize(num_free_, num_free_);
  hessian_.setFromTriplets(triplets.begin(), triplets.end());
  hessian_.makeCompressed();
  auto slot_of = [&](int row, int col) {
    const int* begin = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[col];
    const int* end = hessian_.innerIndexPtr() + hessian_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - hessian_.innerIndexPtr());
  };
  diagonal_slots_.resize(num_free_);
  for (int d = 0; d < num_free_; ++d) diagonal_slots_[d] = slot_of(d, d);
  slot_offset_.clear();
  slots_.clear();
  for (const Term& term : potential_->terms()) {
    slot_offset_.push_back(static_cast<int>(slots_.size()));
    const int nt = dim * static_cast<int>(term.nodes.size());
    for (int a = 0; a < nt; ++a) {
      for (int b = 0; b <= a; ++b) {
        const int fa = free_of(term, a), fb = free_of(term, b);
        slots_.push_back(fa >= 0 && fb >= 0 ? slot_of(std::max(fa, fb), std::min(fa, fb)) : -1);
      }
    }
  }
  local_values_.resize(slots_.size());
  free_rhs_.resize(num_free_);
  free_step_.resize(num_free_);
  analyzed_ = false;
  built_version_ = potential_->structure_version();
  timings_.analyze += SecondsSince(start);
}

bool ProjectedNewtonSolver::TermLocalHessian(int t, const double* x, double weight,
                                             TermHessian kind, Scratch* scratch) {
  const Term& term = potential_->terms()[t];
  const int dim = state_->dimension;
  const int blocks = static_cast<int>(term.nodes.size());
  scratch->parameters.resize(blocks);
  for (int b = 0; b < blocks; ++b) scratch->parameters[b] = x + dim * term.nodes[b];
  TermModel& model = scratch->model;
  if (kind == TermHessian::kExact && term.affine_energy) {
    // The exact Hessian of an affine energy: zero (Term::affine_energy).
    const int nt = dim * blocks;
    std::fill_n(local_values_.data() + slot_offset_[t], nt * (nt + 1) / 2, 0.0);
    return true;
  }
  if (!scratch->evaluator.Evaluate(term, dim, weight, scratch->parameters.data(), true, &model)) {
    return false;
  }
  // Gauss-Newton models are PSD as they are (rho' J^T J, rho'' part only where
  // positive); the others are projected unless exact.
  const TermMatrix* h = &model.hessian;
  if (!term.gauss_newton_model && kind != TermHessian::kExact) {
    ProjectedHessian& projected = scratch->projected;
    ProjectHessian(
        model, &projected,
        kind == TermHessian::kAbsolute ? EigenvalueFilter::kAbsolute : EigenvalueFilter::kClamp);
    scratch->scaled.noalias() = projected.vectors * projected.values.asDiagonal();
    scratch->local.noalias() = scratch->scaled * projected.vectors.transpose();
    h = &scratch->local;
  }
  // Pair-difference terms: the full Hessian is [[K, -K], [-K, K]].
  const int n = static_cast<int>(h->rows());
  const int nt = dim * blocks;
  double* out = local_values_.data() + slot_offset_[t];
  int index = 0;
  for (int a = 0; a < nt; ++a) {
    for (int b = 0; b <= a; ++b, ++index) {
      if (term.pair_difference) {
        const double sign = (a < n) == (b < n) ? 1.0 : -1.0;
        out[index] = sign * (*h)(a % n, b % n);
      } else {
        out[index] = (*h)(a, b);
      }
    }
  }
  return true;
}

bool ProjectedNewtonSolver::AssembleHessian(const Eigen::VectorXd& x, TermHessian kind,
                                            const std::vector<char>* projected_terms) {
  if (built_version_ != potential_->structure_version()) BuildStructure();
  const auto start = WallClock::now();
  const auto& terms = potential_->terms();
  const StepContext& context = potential_->context();
  const int n = static_cast<int>(terms.size());
  ThreadPool& pool = potential_->thread_pool();
  if (static_cast<int>(scratch_.size()) < pool.num_threads()) scratch_.resize(pool.num_threads());
  term_ok_.resize(n);
  // term_ok_: 1 computed, 0 failed, 2 skipped (weight 0).
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    for (int t = begin; t < end; ++t) {
      const double weight = TermWeight(terms[t].kind, context);
      if (weight == 0.0) {
        term_ok_[t] = 2;
        continue;
      }
      const TermHessian term_kind = projected_terms == nullptr ? kind
                                    : (*projected_terms)[t]    ? TermHessian::kClamped
                                                               : TermHessian::kExact;
      term_ok_[t] = TermLocalHessian(t, x.data(), weight, term_kind, &scratch_[thread]) ? 1 : 0;
    }
  });
  const bool ok = ScatterTermHessians();
  term_models_ += n;
  timings_.hessian += SecondsSince(start);
  return ok;
}

bool ProjectedNewtonSolver::UpdateTermHessians(const Eigen::VectorXd& x,
                                               const std::vector<int>& terms, TermHessian kind) {
  const auto start = WallClock::now();
  const StepContext& context = potential_->context();
  const auto& all = potential_->terms();
  const int n = static_cast<int>(terms.size());
  ThreadPool& pool = potential_->thread_pool();
  pool.ParallelFor(n, IncrementalPotential::kModelGrain, [&](int begin, int end, int thread) {
    for (int k = begin; k < end; ++k) {
      const int t = terms[k];
      const double weight = TermWeight(all[t].kind, context);
      term_ok_[t] = weight == 0.0
                        ? 2
                        : (TermLocalHessian(t, x.data(), weight, kind, &scratch_[thread]) ? 1 : 0);
    }
  });
  term_models_ += n;
  const bool ok = ScatterTermHessians();
  timings_.hessian += SecondsSince(start);
  return ok;
}

bool ProjectedNewtonSolver::ScatterTermHessians() {
  // The sum in term order: the same matrix for any number of threads.
  const int n = static_cast<int>(potential_->terms().size());
  std::fill(hessian_.valuePtr(), hessian_.valuePtr() + hessian_.nonZeros(), 0.0);
  double* values = hessian_.valuePtr();
  for (int t = 0; t < n; ++t) {
    if (term_ok_[t] == 2) continue;
    if (term_ok_[t] != 1) return false;
    const int begin = slot_offset_[t];
    const int end = t + 1 < n ? slot_offset_[t + 1] : static_cast<int>(slots_.size());
    for (int i = begin; i < end; ++i) {
      if (slots_[i] >= 0) values[slots_[i]] += local_values_[i];
    }
  }
  return true;
}

}  // namespace ipstep
