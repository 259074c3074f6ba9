// What every integrator has, variational or explicit: its name, the weights of
// the incremental potential's terms, how the energy reports count the state's
// energies, and the order and local error estimate of adaptive steps.
//
// The two kinds step differently and are two interfaces:
//  * VariationalIntegrator (integrators/variational_integrator.h): backward
//    Euler, Newmark, quasi-static. A step minimises the incremental potential;
//    the integrator predicts, the step solver minimises, the integrator updates.
//  * ExplicitIntegrator (integrators/explicit_integrator.h): symplectic Euler.
//    A step advances the state from the forces at its start; no solve.
// MakeIntegrator (integrators/make_integrator.h) says which kind it made, so a
// Simulation chooses its step path once, when it is built, and never asks an
// integrator what it is.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/state.h"
#include "core/step_context.h"

namespace ipstep {

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;

  // Weights of the incremental potential's terms for time step h (constant
  // for a run): a variational step minimises the potential with them; an
  // explicit integrator evaluates the same terms' forces only, and its weights
  // weigh no inertia (the terms read them as they are built, e.g. contact's
  // adaptive barrier stiffness).
  virtual void SetWeights(double h, StepContext* context) const = 0;

  // Energy reports (sim/energy_balance.h, core/forces.h). False when the
  // motion has no inertia (quasi-static): no kinetic energy, and gravity is a
  // potential term instead of being folded into the predictor.
  virtual bool has_inertia() const { return true; }
  // The share of an impulsive potential (the contact barrier) that the scheme
  // stores as energy: 1, or Newmark's effective barrier stiffness 2 beta kappa
  // (integrators/newmark.h).
  virtual double impulsive_energy_factor() const { return 1.0; }

  // Error control (adaptive steps, sim/step_size_controller.h). The order p of
  // the global position error (~ h^p); 0: no time-discretisation error to
  // control (quasi-static).
  virtual int order() const { return 1; }
  // An estimate of the position error [m] that the step of h from `before` to
  // `after` made, per degree of freedom (`error`, the state's per-node
  // layout). This default, for the first-order schemes (backward and
  // symplectic Euler, x_{n+1} = x_n + h v_{n+1}), is the distance to the
  // trapezoidal rule's positions with the same velocities,
  //   e = h/2 (v_{n+1} - v_n),
  // the leading term of the local error h^2/2 a (an embedded pair: no extra
  // solve). Contact forces are in it: a body resting on an obstacle has e = 0,
  // an impact raises it (sim/step_size_controller.h treats that as an event).
  virtual void LocalErrorVector(const State& before, const State& after, double h,
                                Eigen::VectorXd* error) const;
  // The largest |e_i| over the free nodes of LocalErrorVector [m].
  double LocalError(const State& before, const State& after, double h) const;
  // The largest |v_i| over the free nodes of `state` (a vector of its
  // per-node layout).
  static double LargestFreeNodeNorm(const State& state, const Eigen::VectorXd& v);
};

}  // namespace ipstep
