// An explicit integrator advances the state from the forces at the step's
// start, f(x_n, v_n), with no optimisation: symplectic Euler, the baseline the
// variational integrators are compared with. The forces come from the same
// energy terms (core/forces.h), evaluated by the caller.
#pragma once

#include <Eigen/Core>

#include "core/state.h"
#include "integrators/integrator.h"

namespace ipstep {

class ExplicitIntegrator : public Integrator {
 public:
  // Advances `state` by h given the forces f(x_n, v_n) (including gravity):
  // positions, velocities and accelerations of free nodes (the caller then
  // sets constrained nodes and time).
  virtual void Advance(const Eigen::VectorXd& forces, double h, State* state) const = 0;
};

}  // namespace ipstep
