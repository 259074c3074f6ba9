// Exact discrete laws of each integrator on the linear oscillator (omega = 1,
// so Omega = omega h = h). The node moves along the spring, where the Hookean
// energy k/2 (|d| - L)^2 is exactly quadratic in the displacement u.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/input_error.h"
#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::Options;
using testing::OscillatorScene;

struct Phase {
  double u, v;
};

Phase Read(const Simulation& sim, double rest_length) {
  return {sim.state().x[2] - rest_length, sim.state().v[2]};
}

TEST(OscillatorLaws, BackwardEulerEnergyRatioIsOneOverOnePlusOmegaSquared) {
  for (double omega_h : {0.1, 0.5, 1.0, 3.0}) {
    Simulation sim(OscillatorScene(), Options("backward_euler", "newton", omega_h, 1e-12));
    const double e0 = sim.Energies().total();
    double previous = e0;
    // Until the displacement is too small to resolve next to the rest length 1.
    while (previous > 1e-8 * e0) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << r.status;
      // The energy is quadratic along the spring: Newton is exact in one iteration.
      EXPECT_LE(r.iterations, 1) << "Omega " << omega_h;
      const double ratio = r.energies.total() / previous;
      EXPECT_NEAR(ratio, 1.0 / (1.0 + omega_h * omega_h), 1e-9) << "Omega " << omega_h;
      previous = r.energies.total();
    }
  }
}

// The same law in 3D, with the spring along a diagonal: exercises the 3D code
// paths of every energy, integrator and optimiser.
TEST(OscillatorLaws, BackwardEulerLawHoldsIn3DAlongADiagonal) {
  Scene scene = OscillatorScene();
  scene.dimension = 3;
  const double c = 1.1 / std::sqrt(3.0);
  scene.positions = {0.0, 0.0, 0.0, c, c, c};
  scene.velocities.assign(6, 0.0);
  const double omega_h = 0.5;
  for (const char* optimizer : {"newton", "dogleg", "lbfgs", "bfgs", "ncg", "gradient_descent"}) {
    const bool exact = std::string(optimizer) == "newton";
    Simulation sim(scene, Options("backward_euler", optimizer, omega_h, exact ? 1e-12 : 1e-8));
    double previous = sim.Energies().total();
    for (int step = 0; step < 10; ++step) {
      const StepReport r = sim.Step();
      ASSERT_TRUE(r.converged) << optimizer << ": " << r.status;
      EXPECT_NEAR(r.energies.total() / previous, 1.0 / (1.0 + omega_h * omega_h),
                  exact ? 1e-9 : 1e-6)
          << optimizer;
      previous = r.energies.total();
      // The node stays on the diagonal.
      EXPECT_NEAR(sim.state().x[3], sim.state().x[4], 1e-12);
      EXPECT_NEAR(sim.state().x[3], sim.state().x[5], 1e-12);
    }
  }
}

TEST(OscillatorLaws, NewmarkTrapezoidalConservesEnergyAndElongatesThePeriod) {
  for (double omega_h : {0.1, 0.7, 2.0, 5.0}) {
    for (const char* optimizer : {"newton", "lbfgs"}) {
      // Large steps with the constant-acceleration guess would cross the anchor of
      // a short spring (a different energy basin): use a long one.
      Simulation sim(OscillatorScene(0.1, 1.0, 1.0, 100.0),
                     Options("newmark", optimizer, omega_h, 1e-9));
      const double e0 = sim.Energies().total();
      Phase p = Read(sim, 100.0);
      const double expected_angle = 2.0 * std::atan(omega_h / 2.0);
      for (int step = 0; step < 50; ++step) {
        const StepReport r = sim.Step();
        ASSERT_TRUE(r.converged) << r.status;
        if (std::string(optimizer) == "newton") {
          EXPECT_LE(r.iterations, 1) << "Omega " << omega_h;
        }
        EXPECT_NEAR(r.energies.total() / e0, 1.0, 1e-8) << optimizer << " Omega " << omega_h;
        // The step is an exact rotation of (u, v) by 2 atan(Omega/2).
        const Phase q = Read(sim, 100.0);
        const double angle = std::atan2(p.v * q.u - p.u * q.v, p.u * q.u + p.v * q.v);
        EXPECT_NEAR(angle, expected_angle, 1e-7) << optimizer << " Omega " << omega_h;
        p = q;
      }
      // Hence the period is longer by Omega / (2 atan(Omega / 2)).
      const double period_ratio = (2.0 * M_PI / expected_angle) * omega_h / (2.0 * M_PI);
      EXPECT_NEAR(period_ratio, omega_h / (2.0 * std::atan(omega_h / 2.0)), 1e-14);
      if (omega_h == 0.7) {
        // Count the steps of one numerical period directly: the first return of the
        // phase angle past 2 pi.
        Simulation again(OscillatorScene(), Options("newmark", "newton", omega_h, 1e-9));
        double total_angle = 0.0;
        Phase a = Read(again, 1.0);
        int steps = 0;
        while (total_angle < 2.0 * M_PI) {
          again.Step();
          const Phase b = Read(again, 1.0);
          total_angle += std::atan2(a.v * b.u - a.u * b.v, a.u * b.u + a.v * b.v);
          a = b;
          ++steps;
        }
        const double numerical_period = steps * omega_h;  // within one step
        const double predicted = 2.0 * M_PI * omega_h / (2.0 * std::atan(omega_h / 2.0));
        EXPECT_LE(std::abs(numerical_period - predicted), omega_h);
      }
    }
  }
}

// Newmark's parameters are bounded where the method is defined and solvable
// (integrators/newmark.h): beta in [1e-3, 1], gamma in [1/2, 1]. beta = 1e-300
// used to be accepted, and every step "converged" to a wrong motion.
TEST(OscillatorLaws, NewmarkParametersOutsideTheirRangeAreInputErrors) {
  const auto message = [](double beta, double gamma) -> std::string {
    try {
      MakeIntegrator({"newmark", beta, gamma});
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  for (double beta : {1e-300, 0.0, 9e-4, -0.25, 1.5, std::nan("")}) {
    const std::string m = message(beta, 0.5);
    EXPECT_EQ(m.rfind("flag: --newmark_beta: must be in [1e-3, 1]", 0), 0u) << beta << ": " << m;
  }
  for (double gamma : {0.0, 0.4, 0.4999, 1.5, std::numeric_limits<double>::infinity()}) {
    const std::string m = message(0.25, gamma);
    EXPECT_EQ(m.rfind("flag: --newmark_gamma: must be in [0.5, 1]", 0), 0u) << gamma << ": " << m;
  }
  for (double beta : {1e-3, 0.25, 1.0}) {
    for (double gamma : {0.5, 0.75, 1.0}) EXPECT_EQ(message(beta, gamma), "");
  }
}

// Newmark on the oscillator is the linear recurrence
//   (1 + beta h^2) u' = (1 - (1/2 - beta) h^2) u + h v,
//   v' = v - h (1 - gamma) u - h gamma u'      (a = -u).
TEST(OscillatorLaws, NewmarkMatchesItsRecurrenceAndDissipatesForGammaAboveOneHalf) {
  const double h = 0.8;
  const double gamma = 0.6, beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  SimulationOptions options = Options("newmark", "newton", h, 1e-9);
  options.integrator.newmark_beta = beta;
  options.integrator.newmark_gamma = gamma;
  Simulation sim(OscillatorScene(), options);
  double u = 0.1, v = 0.0;
  const double e0 = sim.Energies().total();
  for (int step = 0; step < 60; ++step) {
    const StepReport r = sim.Step();
    ASSERT_TRUE(r.converged) << r.status;
    const double u_next = ((1.0 - (0.5 - beta) * h * h) * u + h * v) / (1.0 + beta * h * h);
    v = v - h * (1.0 - gamma) * u - h * gamma * u_next;
    u = u_next;
    const Phase p = Read(sim, 1.0);
    EXPECT_NEAR(p.u, u, 1e-11);
    EXPECT_NEAR(p.v, v, 1e-11);
  }
  EXPECT_LT(sim.Energies().total(), 0.2 * e0);
  // Spectral radius of the amplification matrix is below one.
  const double a11 = (1.0 - (0.5 - beta) * h * h) / (1.0 + beta * h * h);
  const double a12 = h / (1.0 + beta * h * h);
  const double a21 = -h * (1.0 - gamma) - h * gamma * a11;
  const double a22 = 1.0 - h * gamma * a12;
  const double det = a11 * a22 - a12 * a21;
  EXPECT_LT(std::sqrt(det), 1.0);  // complex pair: |lambda|^2 = det
}

// Symplectic Euler conserves Q = u^2 + v^2 - Omega u v, so from (u0, 0) the
// energy stays below E0 / (1 - Omega/2) for Omega < 2; above 2 the amplification
// matrix (trace 2 - Omega^2, det 1) has a real eigenvalue of modulus > 1.
TEST(OscillatorLaws, SymplecticEulerIsBoundedBelowOmegaTwoAndGrowsAbove) {
  for (double omega_h : {0.5, 1.9}) {
    Simulation sim(OscillatorScene(), Options("symplectic_euler", "newton", omega_h));
    const double e0 = sim.Energies().total();
    double e_max = 0.0;
    for (int step = 0; step < 2000; ++step) {
      sim.Step();
      const Phase p = Read(sim, 1.0);
      EXPECT_NEAR(p.u * p.u + p.v * p.v - omega_h * p.u * p.v, 0.01, 1e-12);
      e_max = std::max(e_max, sim.Energies().total());
    }
    EXPECT_LE(e_max / e0, 1.0 / (1.0 - omega_h / 2.0) + 1e-9);
    EXPECT_GE(e_max / e0, 0.99 / (1.0 - omega_h / 2.0));  // and the bound is reached
  }
  // Omega = 2.1: |u| grows by rho per step. A long spring keeps the motion linear.
  const double omega_h = 2.1;
  Scene scene = OscillatorScene(0.1);
  scene.positions[2] = 1e6 + 0.1;
  scene.springs[0].rest_length = 1e6;
  Simulation sim(scene, Options("symplectic_euler", "newton", omega_h));
  const double t = 2.0 - omega_h * omega_h;
  const double rho = std::abs((t - std::sqrt(t * t - 4.0)) / 2.0);
  std::vector<double> u;
  for (int step = 0; step < 20; ++step) {
    sim.Step();
    u.push_back(sim.state().x[2] - 1e6);
  }
  EXPECT_NEAR(std::abs(u[19] / u[14]), std::pow(rho, 5), 1e-6 * std::pow(rho, 5));
  EXPECT_GT(std::abs(u[19]), 1e4 * 0.1);
}

}  // namespace
}  // namespace ipstep
