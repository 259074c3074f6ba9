#include "core/term.h"

#include <cmath>

namespace ipstep {

const char* TermKindName(TermKind kind) {
  switch (kind) {
    case TermKind::kInertia:
      return "inertia";
    case TermKind::kPotential:
      return "potential";
    case TermKind::kDissipation:
      return "dissipation";
  }
  return "unknown";
}

double TermWeight(TermKind kind, const StepContext& context) {
  switch (kind) {
    case TermKind::kInertia:
      return context.inertia_weight;
    case TermKind::kPotential:
      return context.potential_weight;
    case TermKind::kDissipation:
      return context.dissipation_weight;
  }
  return 0.0;
}

WeightedCostFunction::WeightedCostFunction(const ceres::CostFunction* inner, const double* weight,
                                           const bool* veto)
    : inner_(inner), weight_(weight), veto_(veto) {
  set_num_residuals(inner->num_residuals());
  *mutable_parameter_block_sizes() = inner->parameter_block_sizes();
}

bool WeightedCostFunction::Evaluate(double const* const* parameters, double* residuals,
                                    double** jacobians) const {
  if (veto_ != nullptr && *veto_) return false;
  if (!inner_->Evaluate(parameters, residuals, jacobians)) return false;
  const double scale = std::sqrt(*weight_);
  const int m = num_residuals();
  for (int r = 0; r < m; ++r) residuals[r] *= scale;
  if (jacobians != nullptr) {
    const auto& sizes = parameter_block_sizes();
    for (size_t b = 0; b < sizes.size(); ++b) {
      if (jacobians[b] == nullptr) continue;
      for (int k = 0; k < m * sizes[b]; ++k) jacobians[b][k] *= scale;
    }
  }
  return true;
}

WeightedLoss::WeightedLoss(const ceres::LossFunction* inner, const double* weight)
    : inner_(inner), weight_(weight) {}

void WeightedLoss::Evaluate(double s, double rho[3]) const {
  inner_->Evaluate(s, rho);
  for (int k = 0; k < 3; ++k) rho[k] *= *weight_;
  // Ceres's corrector aborts (CHECK) when rho'' > 0 and rho' <= 0, e.g. when
  // a tiny rho' underflows with the weight: drop the curvature correction.
  if (!(rho[1] > 0.0) && !(rho[2] <= 0.0)) rho[2] = 0.0;
}

}  // namespace ipstep
