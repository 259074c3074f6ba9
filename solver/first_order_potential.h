// The incremental potential as a ceres::FirstOrderFunction over the free
// degrees of freedom, evaluated directly from the terms' cost functions (no
// residual-block machinery: the line-search optimisers only need E and grad E).
//
// Scaling. Ceres's line searches and L-BFGS use absolute thresholds (e.g. the
// secant condition s^T y > 1e-14), so the function is handed to Ceres in units
// where they mean something:
//   objective   F = E / w_U                      (joules for every integrator)
//   parameters  z = sqrt(m_i) x / h  per node    (kinetic-energy metric)
// Then dF/dz_i = sqrt(m_i) * (h |f_i| / m_i): the mass-weighted velocity error of
// the stopping rule, and the inertia Hessian is the identity (backward Euler).
// Without mass scaling, z = x / h.
//
// Precision. With `precise_energy`, F is E(x) - E(x_start) summed from term
// residuals in extended precision (long double) before rounding to double: the
// decreases a line search must see near convergence are far below double
// round-off of E itself (docs/optimisers.md "Precision floor"). The gradient is the
// double-precision autodiff gradient.
#pragma once

#include <vector>

#include <ceres/first_order_function.h>
#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

class FirstOrderPotential : public ceres::FirstOrderFunction {
 public:
  FirstOrderPotential(const IncrementalPotential* potential, const State* state, bool mass_scaled,
                      bool precise_energy);

  bool Evaluate(const double* parameters, double* cost, double* gradient) const override;
  // E = F * energy_scale().
  double energy_scale() const;
  int NumParameters() const override { return static_cast<int>(free_dofs_.size()); }

  // Full positions <-> optimiser parameters. `full` supplies constrained entries
  // and is the reference point of F. Returns false if E cannot be evaluated there.
  bool SetFullPositions(const Eigen::VectorXd& full);
  void ToParameters(const Eigen::VectorXd& full, double* parameters) const;
  const Eigen::VectorXd& FromParameters(const double* parameters) const;

  // Full-length gradient at `parameters`; reuses the last evaluation when it was
  // at the same point. Returns false at infeasible points.
  bool FullGradient(const double* parameters, Eigen::VectorXd* gradient) const;

 private:
  const IncrementalPotential* potential_;
  std::vector<int> free_dofs_;
  std::vector<double> scale_;  // x = z * scale: h / sqrt(m) (or h)
  bool precise_energy_;
  long double reference_energy_ = 0.0L;
  mutable Eigen::VectorXd full_x_;
  mutable Eigen::VectorXd full_gradient_;
  mutable std::vector<double> cached_parameters_;
  mutable bool cache_valid_ = false;
};

}  // namespace ipstep
