// An integrator only decides what the step minimises: it sets the step weights,
// the predictor x_tilde and the discrete velocity map of the StepContext, gives
// the initial guess, and updates velocities (and accelerations) once the
// optimiser has found x_{n+1}. The energy terms and optimisers are shared.
// Symplectic Euler is the exception: an explicit baseline that only needs forces.
#pragma once

#include <memory>
#include <string>

#include <Eigen/Core>

#include "core/state.h"
#include "core/step_context.h"

namespace ipstep {

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;

  // False for explicit integrators (no optimisation: see Advance).
  virtual bool is_variational() const { return true; }
  // False when the incremental potential has no inertia term (quasi-static).
  virtual bool has_inertia() const { return true; }
  // True when the state's accelerations must hold M^-1 f(x0, v0) before step 1.
  virtual bool needs_initial_acceleration() const { return false; }

  // Weights of the incremental potential for time step h (constant for a run).
  virtual void SetWeights(double h, StepContext* context) const = 0;

  // Before a step from `state`: predictor, velocity map, x_start, and the initial
  // guess for x_{n+1} (entries of constrained nodes are overwritten by the caller).
  // `gravity` has `dimension` entries (zero when the scene has no gravity).
  virtual void Predict(const State& state, const Eigen::VectorXd& gravity, double h,
                       StepContext* context, Eigen::VectorXd* guess) const = 0;

  // After the solve: writes x_{n+1} and the new velocities/accelerations of free
  // nodes into `state` (the caller then sets constrained nodes and time).
  virtual void Update(const Eigen::VectorXd& x_next, double h, State* state) const = 0;

  // As Update, given the impulsive forces at x_next (forces of Term::impulsive
  // terms, the contact barrier and friction: -grad of their weighted energy / w_U).
  // Only integrators that return true from separates_impulses() are given them.
  virtual bool separates_impulses() const { return false; }
  // The share of an impulsive potential (the contact barrier) that the scheme
  // stores as energy: 1, or Newmark's effective barrier stiffness 2 beta kappa
  // (integrators/newmark.h). Energy reports and the energy balance use it.
  virtual double impulsive_energy_factor() const { return 1.0; }
  virtual void UpdateWithImpulses(const Eigen::VectorXd& x_next,
                                  const Eigen::VectorXd& /*impulsive_forces*/, double h,
                                  State* state) const {
    Update(x_next, h, state);
  }

  // Error control (adaptive steps, sim/step_size_controller.h). The order p of
  // the global position error (~ h^p); 0: no time-discretisation error to
  // control (quasi-static).
  virtual int order() const { return 1; }
  // An estimate of the position error [m] that the step of h from `before` to
  // `after` made (largest over free nodes). This default, for the first-order
  // schemes (backward and symplectic Euler, x_{n+1} = x_n + h v_{n+1}), is the
  // distance to the trapezoidal rule's positions with the same velocities,
  //   e = h/2 |v_{n+1} - v_n|,
  // the leading term of the local error h^2/2 |a| (an embedded pair: no extra
  // solve). Contact forces are in it: a body resting on an obstacle has e = 0,
  // an impact raises it (sim/step_size_controller.h treats that as an event).
  virtual double LocalError(const State& before, const State& after, double h) const;

  // Explicit integrators only: advances `state` by h given the forces
  // f(x_n, v_n) (including gravity).
  virtual void Advance(const Eigen::VectorXd& forces, double h, State* state) const;

 protected:
  // The largest |after_i - before_i| over the free nodes of `state` (vectors
  // of its per-node layout: velocities, accelerations), for LocalError.
  static double LargestFreeNodeChange(const State& state, const Eigen::VectorXd& before,
                                      const Eigen::VectorXd& after);
};

struct IntegratorOptions {
  std::string name =
      "backward_euler";  // backward_euler | newmark | quasi_static | symplectic_euler
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
};

// Throws InputError naming the option (IntegratorOptions.name, .newmark_beta,
// .newmark_gamma).
std::unique_ptr<Integrator> MakeIntegrator(const IntegratorOptions& options);
const char* IntegratorNames();  // "backward_euler, newmark, quasi_static, symplectic_euler"

}  // namespace ipstep
