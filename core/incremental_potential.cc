#include "core/incremental_potential.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ipstep {

IncrementalPotential::IncrementalPotential(int dimension, int num_nodes)
    : dimension_(dimension), num_nodes_(num_nodes), context_(std::make_unique<StepContext>()) {
  context_->Resize(dimension, num_nodes);
}

void IncrementalPotential::AddTerm(Term term) {
  if (!term.cost) throw std::invalid_argument("term of family '" + term.family + "' has no cost");
  const auto& sizes = term.cost->parameter_block_sizes();
  if (sizes.size() != term.nodes.size()) {
    throw std::invalid_argument("term of family '" + term.family + "' has " +
                                std::to_string(sizes.size()) + " parameter blocks for " +
                                std::to_string(term.nodes.size()) + " nodes");
  }
  for (size_t b = 0; b < sizes.size(); ++b) {
    if (sizes[b] != dimension_) {
      throw std::invalid_argument("term of family '" + term.family +
                                  "': parameter block size must equal the dimension");
    }
    const int node = term.nodes[b];
    if (node < 0 || node >= num_nodes_) {
      throw std::invalid_argument("term of family '" + term.family + "': node " +
                                  std::to_string(node) + " out of range");
    }
    for (size_t c = 0; c < b; ++c) {
      if (term.nodes[c] == node) {
        throw std::invalid_argument("term of family '" + term.family + "': node " +
                                    std::to_string(node) + " used twice in one term");
      }
    }
  }
  if (static_cast<int>(sizes.size()) * dimension_ > kMaxTermCoordinates) {
    throw std::invalid_argument("term of family '" + term.family + "' has " +
                                std::to_string(sizes.size() * dimension_) +
                                " parameters; at most " + std::to_string(kMaxTermCoordinates) +
                                " (nodes x dimension) are supported");
  }
  if (term.pair_difference && sizes.size() != 2) {
    throw std::invalid_argument("term of family '" + term.family +
                                "': a pair-difference term has exactly two nodes");
  }
  // Inertia is ½ m |x - x_tilde|^2: affine residuals by definition.
  if (term.kind == TermKind::kInertia) term.gauss_newton_model = true;
  max_residuals_ = std::max(max_residuals_, term.cost->num_residuals());
  max_nodes_ = std::max(max_nodes_, static_cast<int>(term.nodes.size()));
  residuals_.resize(max_residuals_);
  precise_residuals_.resize(max_residuals_);
  jacobian_storage_.resize(static_cast<size_t>(max_residuals_) * max_nodes_ * dimension_);
  jacobians_.resize(max_nodes_);
  parameters_.resize(max_nodes_);
  terms_.push_back(std::move(term));
  ++structure_version_;
}

int IncrementalPotential::RemoveTerms(const std::string& family) {
  const size_t before = terms_.size();
  terms_.erase(std::remove_if(terms_.begin(), terms_.end(),
                              [&](const Term& t) { return t.family == family; }),
               terms_.end());
  const int removed = static_cast<int>(before - terms_.size());
  if (removed > 0) ++structure_version_;
  return removed;
}

void IncrementalPotential::AddStepFilter(std::unique_ptr<StepFilter> filter) {
  filters_.push_back(std::move(filter));
}

void IncrementalPotential::NotifyAccepted(const double* x) const {
  for (const auto& f : filters_) f->OnAccepted(x);
}

bool IncrementalPotential::IsStepValid(const double* x) const {
  for (const auto& f : filters_) {
    if (!f->IsStepValid(x)) return false;
  }
  return true;
}

double IncrementalPotential::MaxStepSize(const double* from, const double* to) const {
  double t = 1.0;
  for (const auto& f : filters_) t = std::min(t, f->MaxStepSize(from, to));
  return t;
}

bool IncrementalPotential::IsFeasible(const double* x) const {
  for (const auto& f : filters_) {
    if (!f->IsFeasible(x)) return false;
  }
  return true;
}

bool IncrementalPotential::EvaluatePreciseEnergy(const double* x, long double* energy) const {
  if (!IsStepValid(x)) return false;
  long double total = 0.0L;
  for (const Term& term : terms_) {
    const double weight = TermWeight(term.kind, *context_);
    if (weight == 0.0) continue;
    const int m = term.cost->num_residuals();
    for (size_t b = 0; b < term.nodes.size(); ++b) parameters_[b] = x + dimension_ * term.nodes[b];
    long double s = 0.0L;
    if (term.precise_residual) {
      if (!term.precise_residual(parameters_.data(), precise_residuals_.data())) return false;
      for (int r = 0; r < m; ++r) s += precise_residuals_[r] * precise_residuals_[r];
    } else {
      if (!term.cost->Evaluate(parameters_.data(), residuals_.data(), nullptr)) return false;
      for (int r = 0; r < m; ++r) s += static_cast<long double>(residuals_[r]) * residuals_[r];
    }
    long double e = s;
    if (term.precise_loss) {
      e = term.precise_loss(s);
    } else if (term.loss) {
      double rho[3];
      term.loss->Evaluate(static_cast<double>(s), rho);
      e = rho[0];
    }
    total += 0.5L * weight * e;
  }
  if (!std::isfinite(static_cast<double>(total))) return false;
  *energy = total;
  return true;
}

int IncrementalPotential::CountTerms(TermKind kind) const {
  int count = 0;
  for (const Term& t : terms_) count += (t.kind == kind);
  return count;
}

bool IncrementalPotential::Evaluate(const double* x, double* energy, double* gradient) const {
  if (!IsStepValid(x)) return false;
  return Accumulate(nullptr, /*weighted=*/true, x, energy, gradient);
}

bool IncrementalPotential::EvaluateUnweighted(const TermFilter& filter, const double* x,
                                              double* energy, double* gradient) const {
  return Accumulate(filter, /*weighted=*/false, x, energy, gradient);
}

bool IncrementalPotential::Accumulate(const TermFilter& filter, bool weighted, const double* x,
                                      double* energy, double* gradient) const {
  const int n = dimension_ * num_nodes_;
  double total = 0.0;
  if (gradient != nullptr) std::fill(gradient, gradient + n, 0.0);
  for (const Term& term : terms_) {
    if (filter && !filter(term)) continue;
    const double weight = weighted ? TermWeight(term.kind, *context_) : 1.0;
    if (weight == 0.0) continue;
    const int m = term.cost->num_residuals();
    const int blocks = static_cast<int>(term.nodes.size());
    for (int b = 0; b < blocks; ++b) {
      parameters_[b] = x + dimension_ * term.nodes[b];
      jacobians_[b] = jacobian_storage_.data() + static_cast<size_t>(b) * m * dimension_;
    }
    if (!term.cost->Evaluate(parameters_.data(), residuals_.data(),
                             gradient != nullptr ? jacobians_.data() : nullptr)) {
      return false;
    }
    double s = 0.0;
    for (int r = 0; r < m; ++r) s += residuals_[r] * residuals_[r];
    double rho[3] = {s, 1.0, 0.0};
    if (term.loss) term.loss->Evaluate(s, rho);
    total += 0.5 * weight * rho[0];
    if (gradient == nullptr) continue;
    // d/dx 1/2 rho(|r|^2) = rho'(s) J^T r (row-major Jacobian blocks).
    const double scale = weight * rho[1];
    for (int b = 0; b < blocks; ++b) {
      const double* jac = jacobians_[b];
      double* g = gradient + dimension_ * term.nodes[b];
      for (int r = 0; r < m; ++r) {
        const double sr = scale * residuals_[r];
        for (int k = 0; k < dimension_; ++k) g[k] += sr * jac[r * dimension_ + k];
      }
    }
  }
  if (!std::isfinite(total)) return false;
  *energy = total;
  if (gradient != nullptr) {
    for (int d = 0; d < n; ++d) {
      if (!std::isfinite(gradient[d])) return false;
    }
  }
  return true;
}

}  // namespace ipstep
