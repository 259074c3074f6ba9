// Backward Euler with Rayleigh damping: the energy decrease per step is at
// least the discrete dissipation 2 h R(v_{n+1}) = h v^T B v. On the oscillator
// (quadratic U) the balance is exact:
//   E_n - E_{n+1} = h v^T B v + 1/2 m |dv|^2 + 1/2 k |du|^2.
// Quasi-static with damping is the rate problem b u' + k u = 0, discretised as
// u_{n+1} = u_n / (1 + h k / b).
#include <cmath>

#include <gtest/gtest.h>

#include "core/forces.h"
#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;
using testing::OscillatorScene;

TEST(Dissipation, BackwardEulerEnergyBalanceIsExactOnTheOscillator) {
  const double k = 4.0, m = 1.5, alpha = 0.3, beta = 0.05, h = 0.2;
  Scene scene = OscillatorScene(0.2, k, m);
  scene.positions[3] = 0.0;
  scene.velocities[2] = 0.7;  // moving along the spring
  scene.damping = Damping{alpha, beta};
  scene.effects.push_back("damping");
  Simulation sim(scene, Options("backward_euler", "newton", h, 1e-9));
  const double b = alpha * m + beta * k;
  for (int step = 0; step < 30; ++step) {
    const double e_before = sim.Energies().total();
    const double u_before = sim.state().x[2], v_before = sim.state().v[2];
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << r.status;
    double dissipation = 0.0;
    ASSERT_TRUE(ComputeDissipation(sim.potential(), sim.state().x, &dissipation));
    const double v = sim.state().v[2];
    EXPECT_NEAR(dissipation, 0.5 * b * v * v, 1e-12);
    const double du = sim.state().x[2] - u_before, dv = v - v_before;
    const double drop = e_before - r.energies.total();
    EXPECT_GE(drop, 2.0 * h * dissipation - 1e-12);
    EXPECT_NEAR(drop, 2.0 * h * dissipation + 0.5 * m * dv * dv + 0.5 * k * du * du, 1e-11);
  }
}

TEST(Dissipation, EnergyNeverIncreasesOnADampedCloth) {
  Scene scene = testing::ClothScene(6, 1e3);
  scene.damping = Damping{0.5, 0.01};
  scene.effects.push_back("damping");
  Simulation sim(scene, Options("backward_euler", "newton", 0.01, 1e-6));
  double previous = sim.Energies().total();
  for (int step = 0; step < 40; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << "step " << step << ": " << r.status << " residual " << r.residual
                             << " after " << r.iterations << " iterations";
    EXPECT_LE(r.energies.total(), previous + 1e-9);
    previous = r.energies.total();
  }
}

TEST(Dissipation, QuasiStaticRateProblemRelaxesAtTheDiscreteRate) {
  const double k = 3.0, alpha = 2.0, m = 1.0, h = 0.25;
  Scene scene = OscillatorScene(0.1, k, m);
  scene.damping = Damping{alpha, 0.0};
  scene.effects.push_back("damping");
  for (const char* optimizer : {"newton", "lbfgs"}) {
    Simulation sim(scene, Options("quasi_static", optimizer, h, 1e-12));
    double u = 0.1;
    for (int step = 0; step < 10; ++step) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << optimizer << ": " << r.status << " residual " << r.residual;
      u /= 1.0 + h * k / (alpha * m);
      EXPECT_NEAR(sim.state().x[2] - 1.0, u, 1e-10) << optimizer;
    }
  }
}

TEST(QuasiStatic, HangingMassFindsStaticEquilibrium) {
  Scene scene = OscillatorScene(0.0, 100.0, 2.0);
  scene.positions = {0.0, 0.0, 0.0, -1.0};
  scene.gravity = {0.0, -9.81};
  scene.effects = {"gravity", "springs"};
  for (const char* optimizer : {"newton", "dogleg", "lbfgs", "bfgs"}) {
    // Position error = |f| / k = tolerance * m / (h k) = 2e-9.
    Simulation sim(scene, Options("quasi_static", optimizer, 0.1, 1e-8));
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << optimizer << ": " << r.status << " residual " << r.residual;
    EXPECT_NEAR(sim.state().x[3], -1.0 - 2.0 * 9.81 / 100.0, 4e-9) << optimizer;
    EXPECT_NEAR(sim.state().x[2], 0.0, 4e-9) << optimizer;
    EXPECT_EQ(r.energies.kinetic, 0.0);
  }
}

TEST(BoundaryConditions, MovingNodeFollowsItsPrescribedVelocity) {
  Scene scene = OscillatorScene(0.0, 50.0, 1.0);
  scene.pinned.clear();
  scene.moving = {MovingNode{0, {0.5, -0.25}}};
  scene.velocities[0] = 0.5;
  scene.velocities[1] = -0.25;
  for (const char* integrator : {"backward_euler", "newmark", "quasi_static", "symplectic_euler"}) {
    Simulation sim(scene, Options(integrator, "newton", 0.01, 1e-8));
    for (int step = 0; step < 50; ++step) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << integrator << ": " << r.status << " residual " << r.residual;
    }
    EXPECT_NEAR(sim.state().x[0], 0.5 * 0.5, 1e-12) << integrator;
    EXPECT_NEAR(sim.state().x[1], -0.25 * 0.5, 1e-12) << integrator;
    EXPECT_EQ(sim.state().v[0], 0.5);
    // The free node is dragged along (spring rest length 1).
    EXPECT_GT(sim.state().x[2], 1.0 + 0.1) << integrator;
  }
}

}  // namespace
}  // namespace ipstep
