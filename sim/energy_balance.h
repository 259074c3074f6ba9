// The energy balance of one step: the guard against energy created from
// nothing.
//
// E = kinetic + potential energy (core/forces.h: every potential term, the
// contact barrier at the integrator's impulsive factor, gravity as -m g.x).
// Over a step from x_n to x_{n+1}
//   growth = E_{n+1} - E_n - W,
// W the work of prescribed motions:
//  * moving (and pinned) nodes: sum_i 1/2 (F_i(x_n) + F_i(x_{n+1})) . (x_{n+1,i} - x_{n,i}),
//    F_i = dU/dx_i, the force the prescribed motion exerts against the
//    potential (trapezoidal rule along the straight path);
//  * step filters' own prescribed motions, StepFilter::PrescribedWork (moving
//    obstacles: the barrier's rate at fixed positions, and friction against
//    their moving surface, h F . u at the step's end, core/term.h
//    frame_velocity).
// Damping, friction and the integrators' numerical dissipation only remove
// energy, so an exact step has growth <= 0 up to the integrator's energy error
// (zero for Newmark(1/4, 1/2) on linear forces). The step filters' work
// includes what they change at BeginStep (contact: the barrier energy of the
// step's pairs and stiffness at x_n), so a raised barrier stiffness is not
// counted as growth.
//
// The tolerance is relative to the energy in motion at the start of the step
// plus the work done on the system during it,
//   scale = K_n + |U'_n| + |W| + |W_g|,
// U' the potential energy without gravity (kinetic and elastic energy, which
// does not depend on where gravity's potential is zero) and
// W_g = sum_i m_i g . (x_{n+1,i} - x_{n,i}) the work gravity does over the step
// (a body released from rest has K_n = U'_n = 0 and still moves). The end of
// the step is not in the scale: energy a step creates would otherwise widen its
// own allowance. On top of that comes what the stopping rule leaves open: a
// converged step may keep a force imbalance of up to m_i tau / h on every free
// node (core/stopping_rule.h), whose work over the step's displacement is at most
//   floor = sum_i m_i tau / h |x_{n+1,i} - x_{n,i}|.
// A step with growth > tolerance * scale + floor is not converged: status
// "energy growth".
//
// Over the run (RunEnergyBalance) the steps' growths and floors add up, and the
// scale is the largest step scale less the growth accumulated before that step
// (energy created earlier is in motion too, but must not widen the allowance for
// more): a closed system ends within the tolerance of the energy in motion it
// had, not of what it grew to.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/forces.h"
#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

// The energies at one end of a step.
struct EnergyPoint {
  EnergyReport energy;
  double potential_without_gravity = 0.0;
  Eigen::VectorXd x;         // positions
  Eigen::VectorXd gradient;  // dU/dx on every node (only with prescribed motion)
};

// False if the energies cannot be evaluated at the state (or are not finite).
// `prescribed_motion`: the scene moves nodes (the gradient is needed).
bool MeasureEnergy(const IncrementalPotential& potential, const State& state,
                   const Eigen::VectorXd& gravity, bool has_inertia, double impulsive_factor,
                   bool prescribed_motion, EnergyPoint* point);

struct EnergyBalance {
  double start = 0.0;  // E_n
  double end = 0.0;    // E_{n+1}
  double work = 0.0;   // W
  double scale = 0.0;  // energy in motion
  double floor = 0.0;  // what the stopping rule leaves open
  double growth() const { return end - start - work; }
  bool Exceeds(double tolerance) const { return growth() > tolerance * scale + floor; }
  // "energy growth: +G J (P % of the energy in motion, S J)".
  std::string Describe() const;
};

// `filter_work`: the sum of the step filters' PrescribedWork; `gravity`: the
// acceleration of gravity (one entry per dimension); `tolerance_per_h`: the
// stopping tolerance tau over the step's h.
EnergyBalance BalanceOf(const EnergyPoint& start, const EnergyPoint& end, const State& state,
                        const Eigen::VectorXd& gravity, double filter_work, double tolerance_per_h);

// The balance over the steps done so far.
struct RunEnergyBalance {
  double growth = 0.0;  // sum of the steps' growth
  double scale = 0.0;   // largest step scale less the growth before that step
  double floor = 0.0;   // sum of the steps' floors
  // The run's balance once `step` is added.
  RunEnergyBalance After(const EnergyBalance& step) const;
  bool Exceeds(double tolerance) const { return growth > tolerance * scale + floor; }
  // "energy growth over the run: +G J (P % of the energy in motion, S J)".
  std::string Describe() const;
};

}  // namespace ipstep
