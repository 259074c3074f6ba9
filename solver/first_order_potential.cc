#include "solver/first_order_potential.h"

#include <algorithm>
#include <cmath>

namespace ipstep {

FirstOrderPotential::FirstOrderPotential(const IncrementalPotential* potential, const State* state,
                                         bool mass_scaled, bool precise_energy)
    : potential_(potential),
      precise_energy_(precise_energy),
      full_x_(Eigen::VectorXd::Zero(state->num_dofs())),
      full_gradient_(state->num_dofs()) {
  const int dim = state->dimension;
  for (int i = 0; i < state->num_nodes(); ++i) {
    if (!state->is_free(i)) continue;
    for (int k = 0; k < dim; ++k) {
      free_dofs_.push_back(dim * i + k);
      const double h = potential->context().time_step;
      scale_.push_back(mass_scaled ? h / std::sqrt(state->mass[i]) : h);
    }
  }
  cached_parameters_.resize(free_dofs_.size());
}

bool FirstOrderPotential::SetFullPositions(const Eigen::VectorXd& full) {
  full_x_ = full;
  cache_valid_ = false;
  reference_energy_ = 0.0L;
  if (!precise_energy_) return true;
  return potential_->EvaluatePreciseEnergy(full_x_.data(), &reference_energy_);
}

void FirstOrderPotential::ToParameters(const Eigen::VectorXd& full, double* parameters) const {
  for (size_t k = 0; k < free_dofs_.size(); ++k) parameters[k] = full[free_dofs_[k]] / scale_[k];
}

const Eigen::VectorXd& FirstOrderPotential::FromParameters(const double* parameters) const {
  for (size_t k = 0; k < free_dofs_.size(); ++k) full_x_[free_dofs_[k]] = parameters[k] * scale_[k];
  return full_x_;
}

double FirstOrderPotential::energy_scale() const { return potential_->context().potential_weight; }

bool FirstOrderPotential::Evaluate(const double* parameters, double* cost, double* gradient) const {
  FromParameters(parameters);
  cache_valid_ = false;
  double energy = 0.0;
  if (!potential_->Evaluate(full_x_.data(), &energy, full_gradient_.data())) return false;
  const double inverse_weight = 1.0 / energy_scale();
  if (precise_energy_) {
    long double precise = 0.0L;
    if (!potential_->EvaluatePreciseEnergy(full_x_.data(), &precise)) return false;
    energy = static_cast<double>(precise - reference_energy_);
  }
  *cost = energy * inverse_weight;
  // The full gradient is always computed so that the stopping rule can reuse it.
  std::copy(parameters, parameters + free_dofs_.size(), cached_parameters_.begin());
  cache_valid_ = true;
  if (gradient != nullptr) {
    for (size_t k = 0; k < free_dofs_.size(); ++k) {
      gradient[k] = full_gradient_[free_dofs_[k]] * scale_[k] * inverse_weight;
    }
  }
  return true;
}

bool FirstOrderPotential::FullGradient(const double* parameters, Eigen::VectorXd* gradient) const {
  if (!(cache_valid_ &&
        std::equal(cached_parameters_.begin(), cached_parameters_.end(), parameters))) {
    double cost = 0.0;
    if (!Evaluate(parameters, &cost, nullptr)) return false;
  }
  *gradient = full_gradient_;
  return true;
}

}  // namespace ipstep
