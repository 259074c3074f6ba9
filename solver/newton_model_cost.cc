#include "solver/newton_model_cost.h"

#include <algorithm>
#include <cmath>

#include "core/term_hessian.h"
#include "solver/newton_model_cache.h"

namespace ipstep {

void NewtonModelRows(const Term& term, int dimension, const ProjectedHessian& projected,
                     double* residuals, double** jacobians) {
  const int n = static_cast<int>(projected.values.size());
  const int blocks = static_cast<int>(term.nodes.size());
  for (int i = 0; i < n; ++i) {
    const double lambda = projected.values[i];
    if (!(lambda > 0.0)) {
      // H = 0 and J = 0: the gradient is zero too (core/term_hessian.h).
      residuals[i] = 0.0;
      for (int b = 0; b < blocks; ++b) {
        if (jacobians[b] == nullptr) continue;
        for (int k = 0; k < dimension; ++k) jacobians[b][i * dimension + k] = 0.0;
      }
      continue;
    }
    const double root = std::sqrt(lambda);
    residuals[i] = projected.coordinates[i] / root;
    for (int b = 0; b < blocks; ++b) {
      if (jacobians[b] == nullptr) continue;
      double* row = jacobians[b] + i * dimension;
      if (term.pair_difference) {
        const double sign = b == 0 ? -root : root;
        for (int k = 0; k < dimension; ++k) row[k] = sign * projected.vectors(k, i);
      } else {
        for (int k = 0; k < dimension; ++k) row[k] = root * projected.vectors(b * dimension + k, i);
      }
    }
  }
}

NewtonModelCost::NewtonModelCost(const Term* term, int dimension, const double* weight,
                                 const bool* veto, const EigenvalueFilter* filter,
                                 const NewtonModelCache* cache, int cache_index)
    : term_(term),
      dimension_(dimension),
      weight_(weight),
      veto_(veto),
      filter_(filter),
      cache_(cache),
      cache_index_(cache_index) {
  set_num_residuals(cache != nullptr ? cache->rows(cache_index) : ModelRows(*term, dimension));
  *mutable_parameter_block_sizes() = term->cost->parameter_block_sizes();
}

bool NewtonModelCost::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  if (veto_ != nullptr && *veto_) return false;
  const int n = num_residuals();
  const int blocks = static_cast<int>(term_->nodes.size());
  if (cache_ != nullptr && cache_->Has(jacobians != nullptr)) {
    if (!cache_->ok(cache_index_)) return false;
    energy_ = cache_->energy(cache_index_);
    if (jacobians == nullptr) {
      std::fill(residuals, residuals + n, 0.0);
      return true;
    }
    const double* r = cache_->residuals(cache_index_);
    std::copy(r, r + n, residuals);
    const double* jacobian = cache_->jacobian(cache_index_);
    for (int b = 0; b < blocks; ++b) {
      if (jacobians[b] != nullptr) {
        std::copy(jacobian + b * n * dimension_, jacobian + (b + 1) * n * dimension_, jacobians[b]);
      }
    }
    return true;
  }
  thread_local TermModelEvaluator evaluator;
  thread_local TermModel model;
  thread_local ProjectedHessian projected;
  if (jacobians == nullptr) {
    if (!evaluator.Evaluate(*term_, dimension_, *weight_, parameters, false, &model)) return false;
    energy_ = model.energy;
    for (int i = 0; i < n; ++i) residuals[i] = 0.0;
    return true;
  }
  if (!evaluator.Evaluate(*term_, dimension_, *weight_, parameters, true, &model)) return false;
  energy_ = model.energy;
  ProjectHessian(model, &projected, filter_ != nullptr ? *filter_ : EigenvalueFilter::kClamp);
  // Rows beyond the model's own (the inertia projection's full rows) are zero.
  std::fill(residuals, residuals + n, 0.0);
  for (int b = 0; b < blocks; ++b) {
    if (jacobians[b] != nullptr) std::fill(jacobians[b], jacobians[b] + n * dimension_, 0.0);
  }
  NewtonModelRows(*term_, dimension_, projected, residuals, jacobians);
  return true;
}

void NewtonModelLoss::Evaluate(double, double rho[3]) const {
  rho[0] = 2.0 * cost_->energy();
  rho[1] = 1.0;
  rho[2] = 0.0;
}

}  // namespace ipstep
