#include "core/incremental_potential.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ipstep {

IncrementalPotential::IncrementalPotential(int dimension, int num_nodes)
    : dimension_(dimension),
      num_nodes_(num_nodes),
      context_(std::make_unique<StepContext>()),
      pool_(std::make_unique<ThreadPool>(1)) {
  context_->Resize(dimension, num_nodes);
  ResizeScratch();
}

void IncrementalPotential::SetNumThreads(int threads) {
  if (threads == pool_->num_threads()) return;
  pool_ = std::make_unique<ThreadPool>(threads);
  ResizeScratch();
}

void IncrementalPotential::ResizeScratch() const {
  scratch_.resize(pool_->num_threads());
  for (Scratch& s : scratch_) {
    s.residuals.resize(max_residuals_);
    s.precise_residuals.resize(max_residuals_);
    s.jacobian_storage.resize(static_cast<size_t>(max_residuals_) * max_nodes_ * dimension_);
    s.jacobians.resize(max_nodes_);
    s.parameters.resize(max_nodes_);
  }
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
  ResizeScratch();
  gradient_offset_.push_back(static_cast<int>(term_gradient_.size()));
  term_gradient_.resize(term_gradient_.size() + term.nodes.size() * dimension_);
  terms_.push_back(std::move(term));
  term_energy_.resize(terms_.size());
  term_precise_energy_.resize(terms_.size());
  term_ok_.resize(terms_.size());
  ++structure_version_;
}

int IncrementalPotential::RemoveTerms(int group) {
  if (group <= 0) throw std::invalid_argument("RemoveTerms: a term group is > 0");
  const size_t before = terms_.size();
  terms_.erase(
      std::remove_if(terms_.begin(), terms_.end(), [&](const Term& t) { return t.group == group; }),
      terms_.end());
  const int removed = static_cast<int>(before - terms_.size());
  if (removed > 0) {
    ++structure_version_;
    gradient_offset_.clear();
    size_t offset = 0;
    for (const Term& t : terms_) {
      gradient_offset_.push_back(static_cast<int>(offset));
      offset += t.nodes.size() * dimension_;
    }
    term_gradient_.resize(offset);
    term_energy_.resize(terms_.size());
    term_precise_energy_.resize(terms_.size());
    term_ok_.resize(terms_.size());
  }
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

StepFilter::Infeasibility IncrementalPotential::CheckState(const double* x) const {
  StepFilter::Infeasibility worst = StepFilter::Infeasibility::kNone;
  for (const auto& f : filters_) {
    const StepFilter::Infeasibility found = f->CheckState(x);
    if (found == StepFilter::Infeasibility::kPenetration) return found;
    if (found != StepFilter::Infeasibility::kNone) worst = found;
  }
  return worst;
}

double IncrementalPotential::ReachedTime() const {
  double reached = std::numeric_limits<double>::infinity();
  for (const auto& f : filters_) reached = std::min(reached, f->ReachedTime());
  return reached;
}

bool IncrementalPotential::PreciseTermEnergy(int t, double weight, const double* x,
                                             Scratch* scratch) const {
  const Term& term = terms_[t];
  const int m = term.cost->num_residuals();
  for (size_t b = 0; b < term.nodes.size(); ++b) {
    scratch->parameters[b] = x + dimension_ * term.nodes[b];
  }
  if (term.precise_energy) {
    long double e = 0.0L;
    if (!term.precise_energy(scratch->parameters.data(), &e)) return false;
    term_precise_energy_[t] = weight * e;
    return true;
  }
  long double s = 0.0L;
  if (term.precise_residual) {
    if (!term.precise_residual(scratch->parameters.data(), scratch->precise_residuals.data())) {
      return false;
    }
    for (int r = 0; r < m; ++r) s += scratch->precise_residuals[r] * scratch->precise_residuals[r];
  } else {
    if (!term.cost->Evaluate(scratch->parameters.data(), scratch->residuals.data(), nullptr)) {
      return false;
    }
    for (int r = 0; r < m; ++r) {
      s += static_cast<long double>(scratch->residuals[r]) * scratch->residuals[r];
    }
  }
  long double e = s;
  if (term.precise_loss) {
    e = term.precise_loss(s);
  } else if (term.loss) {
    double rho[3];
    term.loss->Evaluate(static_cast<double>(s), rho);
    e = rho[0];
  }
  term_precise_energy_[t] = 0.5L * weight * e;
  return true;
}

bool IncrementalPotential::EvaluatePreciseEnergy(const double* x, long double* energy) const {
  if (!IsStepValid(x)) return false;
  const int n = static_cast<int>(terms_.size());
  pool_->ParallelFor(n, kEnergyGrain, [&](int begin, int end, int thread) {
    for (int t = begin; t < end; ++t) {
      const double weight = TermWeight(terms_[t].kind, *context_);
      term_precise_energy_[t] = 0.0L;
      term_ok_[t] = weight == 0.0 || PreciseTermEnergy(t, weight, x, &scratch_[thread]);
    }
  });
  long double total = 0.0L;
  for (int t = 0; t < n; ++t) {
    if (!term_ok_[t]) return false;
    total += term_precise_energy_[t];
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

bool IncrementalPotential::FrameDissipationRate(const double* x, double* rate) const {
  *rate = 0.0;
  const auto moving = [](const Term& term) { return !term.frame_velocity.isZero(0.0); };
  if (std::none_of(terms_.begin(), terms_.end(), moving)) return true;
  std::vector<double> gradient(static_cast<size_t>(dimension_) * num_nodes_);
  double energy = 0.0;
  if (!Accumulate(moving, /*weighted=*/false, x, &energy, gradient.data())) return false;
  // Per term: its own gradient (left by Accumulate) against its own u.
  for (size_t t = 0; t < terms_.size(); ++t) {
    if (term_ok_[t] != 1) continue;
    const Term& term = terms_[t];
    const double* g = term_gradient_.data() + gradient_offset_[t];
    for (size_t b = 0; b < term.nodes.size(); ++b) {
      for (int k = 0; k < dimension_; ++k) *rate += g[b * dimension_ + k] * term.frame_velocity[k];
    }
  }
  return std::isfinite(*rate);
}

bool IncrementalPotential::EvaluateTerm(int t, double weight, const double* x, bool gradient,
                                        Scratch* scratch) const {
  const Term& term = terms_[t];
  const int m = term.cost->num_residuals();
  const int blocks = static_cast<int>(term.nodes.size());
  for (int b = 0; b < blocks; ++b) {
    scratch->parameters[b] = x + dimension_ * term.nodes[b];
    scratch->jacobians[b] =
        scratch->jacobian_storage.data() + static_cast<size_t>(b) * m * dimension_;
  }
  double* residuals = scratch->residuals.data();
  if (!term.cost->Evaluate(scratch->parameters.data(), residuals,
                           gradient ? scratch->jacobians.data() : nullptr)) {
    return false;
  }
  double s = 0.0;
  for (int r = 0; r < m; ++r) s += residuals[r] * residuals[r];
  double rho[3] = {s, 1.0, 0.0};
  if (term.loss) term.loss->Evaluate(s, rho);
  term_energy_[t] = 0.5 * weight * rho[0];
  if (!gradient) return true;
  // d/dx 1/2 rho(|r|^2) = rho'(s) J^T r (row-major Jacobian blocks).
  const double scale = weight * rho[1];
  double* g = term_gradient_.data() + gradient_offset_[t];
  for (int b = 0; b < blocks; ++b) {
    const double* jac = scratch->jacobians[b];
    for (int k = 0; k < dimension_; ++k) g[b * dimension_ + k] = 0.0;
    for (int r = 0; r < m; ++r) {
      const double sr = scale * residuals[r];
      for (int k = 0; k < dimension_; ++k) g[b * dimension_ + k] += sr * jac[r * dimension_ + k];
    }
  }
  return true;
}

bool IncrementalPotential::Accumulate(const TermFilter& filter, bool weighted, const double* x,
                                      double* energy, double* gradient) const {
  const int n_dofs = dimension_ * num_nodes_;
  const int n = static_cast<int>(terms_.size());
  const bool with_gradient = gradient != nullptr;
  // term_ok_: 1 evaluated, 0 failed, 2 skipped (filtered out or weight 0).
  pool_->ParallelFor(n, kEnergyGrain, [&](int begin, int end, int thread) {
    for (int t = begin; t < end; ++t) {
      const Term& term = terms_[t];
      const double weight = weighted ? TermWeight(term.kind, *context_) : 1.0;
      if ((filter && !filter(term)) || weight == 0.0) {
        term_ok_[t] = 2;
        continue;
      }
      term_ok_[t] = EvaluateTerm(t, weight, x, with_gradient, &scratch_[thread]) ? 1 : 0;
    }
  });
  // Sums in term order: the same for any number of threads.
  double total = 0.0;
  if (with_gradient) std::fill(gradient, gradient + n_dofs, 0.0);
  for (int t = 0; t < n; ++t) {
    if (term_ok_[t] == 0) return false;
    if (term_ok_[t] == 2) continue;
    total += term_energy_[t];
    if (!with_gradient) continue;
    const Term& term = terms_[t];
    const double* g = term_gradient_.data() + gradient_offset_[t];
    for (size_t b = 0; b < term.nodes.size(); ++b) {
      double* out = gradient + dimension_ * term.nodes[b];
      for (int k = 0; k < dimension_; ++k) out[k] += g[b * dimension_ + k];
    }
  }
  if (!std::isfinite(total)) return false;
  *energy = total;
  if (with_gradient) {
    for (int d = 0; d < n_dofs; ++d) {
      if (!std::isfinite(gradient[d])) return false;
    }
  }
  return true;
}

}  // namespace ipstep
