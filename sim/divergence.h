// When a run has diverged: the one rule used by the run loop
// (sim/run_trajectory.h) and so by ipstep, ipstep_compare and ipstep_bench.
//
// A run has diverged at a step when
//   1. a position, velocity or the energy is not finite, or
//   2. the total energy moved away from the initial one by more than
//      kEnergyFactor (1e6) times the scene's energy scale E_s(t), or
//   3. a node left the scene's reach by more than kReachFactor (1e3) times.
// The scale and the reach are fixed at the start from the scene, not from the
// initial energy's magnitude: |E_0| is round-off for a body at rest about the
// origin (hanging_square: -5.7e-14 J) and 0 for a clamped rod at rest, and it
// depends on where the origin is (gravity's -m g.x).
//   E_s(t) = K_0 + |U_0 - U_g0| + K_p + W(t) + M |g| (L + v_s t + |g| t^2 / 2)
//   reach(t) = R + v_s t + |g| t^2 / 2
// K_0: initial kinetic energy; U_0 - U_g0: the initial potential energy without
// gravity's part (elastic, contact); K_p: the largest kinetic energy of the
// prescribed (moving) nodes over the run, sampled; W(t): the work the
// prescribed motions did so far, summed in magnitude over the steps
// (StepReport::prescribed_work, measured by the energy balance of variational
// runs; a twisted bar stores 50 times its initial energy); M: total mass; L and R: the
// diagonal and half diagonal of the box holding every node at the start and
// every prescribed position over the run; v_s = max(initial speeds, prescribed
// speeds, sqrt(2 (K_0 + |U_0 - U_g0| + K_p) / M)), the speed the scene's own
// energy could give all of its mass. A physical run stays within a few E_s and
// one reach (dissipation, prescribed work, a fall); an explicit integrator past
// its stability limit grows geometrically (symplectic Euler on the cloth at
// dt = 1/60 s: 1e150 J) and crosses both bounds within a few steps. A scale of
// 0 (at rest, no gravity, nothing moving, nothing stored) leaves only rules 1
// and 3.
#pragma once

#include <string>

#include <Eigen/Core>

#include "core/forces.h"

namespace ipstep {

class Simulation;
struct StepReport;

class DivergenceRule {
 public:
  static constexpr double kEnergyFactor = 1e6;
  static constexpr double kReachFactor = 1e3;
  // The rule in words, for reports.
  static const char* Description();

  // The scale and reach of `sim`'s scene at its current (initial) state, for a
  // run to `t_end` [s] (the prescribed motion is sampled up to it).
  DivergenceRule(const Simulation& sim, double t_end);

  // Empty if the state of `sim` after a step with `report` is physical,
  // otherwise why the run diverged (e.g. "energy 4.1e+12 J is 2.3e+07 energy
  // scales (1.8e+05 J) from the initial 0 J").
  // `work`: W, the prescribed work so far [J].
  std::string Check(const Simulation& sim, const StepReport& report, double work = 0.0) const;

  // E_s(t) [J] (with the prescribed work so far `work`) and reach(t) [m] at
  // time t [s] from the start.
  double EnergyScale(double t, double work = 0.0) const;
  double Reach(double t) const;
  // |energy - E_0| / E_s(time - start) at simulated `time` [s]; 0 for a scale
  // of 0.
  double Drift(double time, double energy, double work = 0.0) const;
  double initial_energy() const { return initial_energies_.total(); }
  const EnergyReport& initial_energies() const { return initial_energies_; }
  double start_time() const { return start_time_; }

 private:
  double start_time_ = 0.0;
  EnergyReport initial_energies_;
  double stored_energy_ = 0.0;  // K_0 + |U_0 - U_g0| + K_p
  double weight_ = 0.0;         // M |g|
  double gravity_ = 0.0;        // |g|
  double diagonal_ = 0.0;       // L
  double speed_ = 0.0;          // v_s
  Eigen::VectorXd center_;
};

}  // namespace ipstep
