// A variational integrator only decides what the step minimises: it sets the
// step weights, the predictor x_tilde and the discrete velocity map of the
// StepContext, gives the initial guess, and updates velocities (and
// accelerations) once the step solver has found x_{n+1}. The energy terms and
// optimisers are shared. Backward Euler, Newmark and quasi-static are
// variational; the potential has inertia terms when the weights weigh them
// (w_I > 0: not quasi-static).
#pragma once

#include <functional>

#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "core/step_context.h"
#include "integrators/integrator.h"

namespace ipstep {

// The impulsive forces [N] at x (forces of Term::impulsive terms, the contact
// barrier and friction: -grad of their weighted energy / w_U,
// Simulation::ImpulsiveForces); false when there are none.
using ImpulsiveForcesAt = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd* forces)>;

class VariationalIntegrator : public Integrator {
 public:
  // Once, before the first step, with the potential built: what the scheme
  // keeps in the state besides positions and velocities (Newmark: a_0).
  // False when the energies cannot be evaluated at the initial state.
  virtual bool InitializeState(IncrementalPotential* /*potential*/,
                               const Eigen::VectorXd& /*gravity*/, State* /*state*/) const {
    return true;
  }

  // Before a step from `state`: predictor, velocity map, x_start, and the initial
  // guess for x_{n+1} (entries of constrained nodes are overwritten by the caller).
  // `gravity` has `dimension` entries (zero when the scene has no gravity).
  virtual void Predict(const State& state, const Eigen::VectorXd& gravity, double h,
                       StepContext* context, Eigen::VectorXd* guess) const = 0;

  // After the solve: writes x_{n+1} and the new velocities/accelerations of free
  // nodes into `state` (the caller then sets constrained nodes and time).
  // `impulsive_forces` gives the impulsive forces at x_next to a scheme that
  // treats them apart (Newmark); the others do not ask for them.
  virtual void Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt& impulsive_forces,
                      double h, State* state) const = 0;
};

}  // namespace ipstep
