#include "solver/newton_model_cost.h"

#include <cmath>

#include "core/term_hessian.h"

namespace ipstep {

NewtonModelCost::NewtonModelCost(const Term* term, int dimension, const double* weight,
                                 const bool* veto)
    : term_(term), dimension_(dimension), weight_(weight), veto_(veto) {
  set_num_residuals(ModelRows(*term, dimension));
  *mutable_parameter_block_sizes() = term->cost->parameter_block_sizes();
}

bool NewtonModelCost::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  if (veto_ != nullptr && *veto_) return false;
  thread_local TermModelEvaluator evaluator;
  thread_local TermModel model;
  thread_local ProjectedHessian projected;
  const int n = num_residuals();
  if (jacobians == nullptr) {
    if (!evaluator.Evaluate(*term_, dimension_, *weight_, parameters, false, &model)) return false;
    energy_ = model.energy;
    for (int i = 0; i < n; ++i) residuals[i] = 0.0;
    return true;
  }
  if (!evaluator.Evaluate(*term_, dimension_, *weight_, parameters, true, &model)) return false;
  energy_ = model.energy;
  ProjectHessian(model, &projected);
  const int blocks = static_cast<int>(term_->nodes.size());
  for (int i = 0; i < n; ++i) {
    const double lambda = projected.values[i];
    if (!(lambda > 0.0)) {
      // H = 0 and J = 0: the gradient is zero too (core/term_hessian.h).
      residuals[i] = 0.0;
      for (int b = 0; b < blocks; ++b) {
        if (jacobians[b] == nullptr) continue;
        for (int k = 0; k < dimension_; ++k) jacobians[b][i * dimension_ + k] = 0.0;
      }
      continue;
    }
    const double root = std::sqrt(lambda);
    residuals[i] = projected.coordinates[i] / root;
    for (int b = 0; b < blocks; ++b) {
      if (jacobians[b] == nullptr) continue;
      double* row = jacobians[b] + i * dimension_;
      if (term_->pair_difference) {
        const double sign = b == 0 ? -root : root;
        for (int k = 0; k < dimension_; ++k) row[k] = sign * projected.vectors(k, i);
      } else {
        for (int k = 0; k < dimension_; ++k)
          row[k] = root * projected.vectors(b * dimension_ + k, i);
      }
    }
  }
  return true;
}

void NewtonModelLoss::Evaluate(double, double rho[3]) const {
  rho[0] = 2.0 * cost_->energy();
  rho[1] = 1.0;
  rho[2] = 0.0;
}

}  // namespace ipstep
