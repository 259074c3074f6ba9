// The trapezoidal rule (Newmark 1/4, 1/2) on a stiff nonlinear problem at
// omega h >> 1: energy-conserving on linear problems, it is not energy-stable
// on nonlinear ones (Simo & Tarnow 1992, "The discrete energy-momentum
// method"), and the energy guard (sim/energy_balance.h) is what catches it.
//
// A chain of 5 unit masses on squared-strain springs (k = 10^4, rest length
// 1; axial frequencies 200-400 rad/s) hangs from a pinned node and is released
// straight and at rest along x, under gravity (0, -1). No work is done on it:
// the exact total energy (kinetic + springs + gravity, zero at the start) is 0
// at every time. Measured with the Newton optimiser at tolerance 1e-5:
//  * h = 0.1 s (omega h = 20-40), no guard: the energy stays within a few J for
//    175 steps, then jumps to 3.5 kJ (the swing's largest kinetic energy is
//    14.9 J);
//  * h = 0.01 and 0.005 s: |E| <= 0.019 and 0.0048 J, second order;
//  * gamma = 0.6, beta = (gamma + 1/2)^2 / 4 at h = 0.1 s, and backward Euler:
//    E only decreases (numerical dissipation);
//  * with the guard (10 %) and substeps: every step converges, 8 of 200 in
//    substeps, and the energy never exceeds 0.15 J.
// The same happens on the self-contact cloths (squared-strain k = 2000 on
// 0.17 g nodes, omega h ~ 50 at 5 ms): docs/self_contact.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

Scene StiffChain() {
  Scene s;
  s.name = s.source = "test_stiff_chain";
  s.dimension = 2;
  const int n = 6;
  for (int i = 0; i < n; ++i) {
    s.positions.push_back(i);
    s.positions.push_back(0.0);
    s.masses.push_back(1.0);
  }
  s.velocities.assign(s.positions.size(), 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    s.springs.push_back(Spring{i, i + 1, SpringModel::kSquaredStrain, 1e4, 1.0});
  }
  s.pinned = {0};
  s.gravity = {0.0, -1.0};
  s.effects = {"gravity", "springs"};
  return s;
}

struct RunSummary {
  double max_energy = -INFINITY;
  double largest_deviation = 0.0;  // max |E|
  double max_kinetic = 0.0;
  int failed = 0;
  int substepped = 0;
};

RunSummary Simulate(double h, int steps, double energy_tolerance, int max_substeps = 1,
                    double beta = 0.25, double gamma = 0.5, const char* integrator = "newmark") {
  SimulationOptions options = testing::Options(integrator, "newton", h, 1e-5);
  options.integrator.newmark_beta = beta;
  options.integrator.newmark_gamma = gamma;
  options.energy_tolerance = energy_tolerance;
  options.max_substeps = max_substeps;
  Simulation sim(StiffChain(), options);
  EXPECT_EQ(sim.Energies().total(), 0.0);
  RunSummary run;
  for (int step = 0; step < steps; ++step) {
    const StepReport r = sim.Step();
    run.failed += !r.converged;
    run.substepped += r.substeps > 1;
    const double e = sim.Energies().total();
    run.max_energy = std::max(run.max_energy, e);
    run.largest_deviation = std::max(run.largest_deviation, std::abs(e));
    run.max_kinetic = std::max(run.max_kinetic, sim.Energies().kinetic);
  }
  std::printf(
      "%s beta %g gamma %g h %g, %d steps, guard %g: max E %.3g J, max |E| %.3g J, "
      "max kinetic %.3g J, %d failed, %d substepped\n",
      integrator, beta, gamma, h, steps, energy_tolerance, run.max_energy, run.largest_deviation,
      run.max_kinetic, run.failed, run.substepped);
  return run;
}

TEST(NewmarkStiffEnergy, TrapezoidalRuleCreatesEnergyAtLargeSteps) {
  const RunSummary run = Simulate(0.1, 200, 0.0);
  EXPECT_EQ(run.failed, 0);  // nothing checks the energy: every step "converges"
  // The exact energy is 0; the real swing never has more than ~15 J in motion.
  EXPECT_GT(run.max_energy, 100.0);
}

TEST(NewmarkStiffEnergy, EnergyErrorIsSecondOrderAtResolvedSteps) {
  const RunSummary coarse = Simulate(0.01, 2000, 0.0);
  const RunSummary fine = Simulate(0.005, 4000, 0.0);
  EXPECT_EQ(coarse.failed + fine.failed, 0);
  EXPECT_GT(coarse.max_kinetic, 10.0);  // the chain did swing down
  EXPECT_LT(coarse.largest_deviation, 0.05);
  // Halving h divides the energy error by ~4 (measured 3.95).
  EXPECT_NEAR(coarse.largest_deviation / fine.largest_deviation, 4.0, 0.6);
}

TEST(NewmarkStiffEnergy, NumericalDissipationOnlyRemovesEnergy) {
  const double gamma = 0.6, beta = (gamma + 0.5) * (gamma + 0.5) / 4.0;
  const RunSummary dissipative = Simulate(0.1, 200, 0.0, 1, beta, gamma);
  const RunSummary backward_euler = Simulate(0.1, 200, 0.0, 1, 0.25, 0.5, "backward_euler");
  for (const RunSummary& run : {dissipative, backward_euler}) {
    EXPECT_EQ(run.failed, 0);
    EXPECT_GT(run.max_kinetic, 5.0);
    EXPECT_LT(run.max_energy, 1e-6);
  }
}

TEST(NewmarkStiffEnergy, GuardCatchesTheGrowthAndSubstepsRecover) {
  const RunSummary run = Simulate(0.1, 200, 0.1, 16);
  EXPECT_EQ(run.failed, 0);
  EXPECT_GT(run.substepped, 0);
  // Within the tolerance (10 %) of the energy in motion over the run.
  EXPECT_LT(run.max_energy, 0.1 * 4 * run.max_kinetic);
  EXPECT_LT(run.max_energy, 1.0);
}

}  // namespace
}  // namespace ipstep
