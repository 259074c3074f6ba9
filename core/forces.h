// Forces and energies from the same energy terms as the incremental potential.
#pragma once

#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

// The gravity force and energy below come from the gravity vector g: the
// uniform-gravity terms (Term::uniform_gravity, the quasi-static linear
// potential, whose value carries an offset) are left out of them.
//
// f(x, v) = -grad U(x) - B v + M g on every node (zero rows for nodes without
// terms). Temporarily points the context's velocity map at (x, v); restores it.
// Returns false if a term cannot be evaluated at x.
// Without `impulsive`, the impulsive terms (Term::impulsive: contact) are
// left out.
bool ComputeForces(IncrementalPotential* potential, const State& state,
                   const Eigen::VectorXd& gravity, Eigen::VectorXd* forces, bool impulsive = true);

// Accelerations M^-1 f(x, v) for free nodes, zero for constrained ones
// (`impulsive` as for ComputeForces: an integrator that separates impulses,
// Newmark, keeps them out of its accelerations).
bool ComputeAccelerations(IncrementalPotential* potential, const State& state,
                          const Eigen::VectorXd& gravity, Eigen::VectorXd* accelerations,
                          bool impulsive = true);

struct EnergyReport {
  double kinetic = 0.0;
  double potential = 0.0;  // U(x) - sum m g.x
  double total() const { return kinetic + potential; }
};

// Kinetic energy (0 when `has_inertia` is false) and potential energy, the
// impulsive potential terms (Term::impulsive: the contact barrier) counted
// `impulsive_factor` times (Integrator::impulsive_energy_factor). With
// `gradient` (not null): the gradient of the potential energy, gravity's
// -m g included, on every node.
bool ComputeEnergies(const IncrementalPotential& potential, const State& state,
                     const Eigen::VectorXd& gravity, bool has_inertia, double impulsive_factor,
                     EnergyReport* report, Eigen::VectorXd* gradient = nullptr);

// Rayleigh dissipation function R(v) at the context's current velocity map,
// evaluated at positions x (unweighted).
bool ComputeDissipation(const IncrementalPotential& potential, const Eigen::VectorXd& x,
                        double* dissipation);

}  // namespace ipstep
