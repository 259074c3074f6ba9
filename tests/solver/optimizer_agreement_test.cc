// Every optimiser reaches the same step on the cloth within the tolerance, and
// no optimiser reports convergence it did not reach.
#include <cmath>

#include <gtest/gtest.h>

#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using testing::ClothScene;
using testing::Options;

Eigen::VectorXd OneStep(const std::string& integrator, const std::string& optimizer,
                        double tolerance, StepReport* report) {
  Simulation sim(ClothScene(10), Options(integrator, optimizer, 1.0 / 60.0, tolerance));
  *report = sim.Step();
  return sim.state().x;
}

TEST(OptimizerAgreement, AllOptimizersReachTheSameClothStep) {
  // Tolerances sit above the precision floor of cost-based acceptance (~1e-7 m/s
  // here: docs/optimisers.md "Precision floor").
  const double tolerance = 1e-6, reference_tolerance = 1e-7, h = 1.0 / 60.0;
  for (const char* integrator : {"backward_euler", "newmark"}) {
    StepReport reference_report;
    const Eigen::VectorXd reference =
        OneStep(integrator, "newton", reference_tolerance, &reference_report);
    ASSERT_TRUE(reference_report.converged)
        << reference_report.status << " residual " << reference_report.residual;
    for (const char* optimizer : {"newton", "dogleg", "gauss_newton", "lbfgs", "bfgs", "ncg",
                                  "gradient_descent", "projected_newton"}) {
      StepReport r;
      const Eigen::VectorXd x = OneStep(integrator, optimizer, tolerance, &r);
      EXPECT_TRUE(r.converged) << integrator << " " << optimizer << ": " << r.status;
      EXPECT_LE(r.residual, tolerance);
      // The position error is about M^-1 grad E = (w_U / h^2) h residual <= h residual
      // (w_U = h^2 for backward Euler, beta h^2 for Newmark); 4x for safety.
      const double bound = 4.0 * h * (tolerance + reference_tolerance);
      EXPECT_LE((x - reference).lpNorm<Eigen::Infinity>(), bound) << integrator << " " << optimizer;
    }
  }
}

TEST(OptimizerAgreement, GradientDescentReportsTheIterationLimit) {
  SimulationOptions options = Options("backward_euler", "gradient_descent", 1.0 / 60.0, 1e-8);
  options.optimizer.max_iterations = 5;
  Simulation sim(ClothScene(10), options);
  const StepReport r = sim.Step();
  EXPECT_FALSE(r.converged);
  EXPECT_GT(r.residual, 1e-8);
  EXPECT_EQ(r.status, "iteration limit (5)");
}

// Ceres compares costs in double precision; on the 20x20 cloth its trust
// region alone stalled near 2e-6 m/s (the precision floor). Rejected trial
// points re-tested with the extended-precision energy let newton converge
// at 1e-8 m/s on every step (solver/trust_region_solver.h).
TEST(OptimizerAgreement, NewtonConvergesBelowTheDoublePrecisionFloor) {
  Simulation sim(ClothScene(20), Options("backward_euler", "newton", 1.0 / 60.0, 1e-8));
  for (int step = 0; step < 10; ++step) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << "step " << r.step << ": " << r.status << " " << r.residual;
  }
}

TEST(OptimizerAgreement, UnreachableToleranceIsReportedAsStallNotConvergence) {
  for (const char* optimizer : {"lbfgs", "newton"}) {
    Simulation sim(ClothScene(6), Options("backward_euler", optimizer, 1.0 / 60.0, 1e-300));
    const StepReport r = sim.Step();
    EXPECT_FALSE(r.converged) << optimizer;
    EXPECT_GT(r.residual, 1e-300);
    EXPECT_NE(r.status, "converged");
  }
}

TEST(OptimizerAgreement, EveryIntegratorTimesOptimizerRunsTheCloth) {
  for (const char* integrator : {"backward_euler", "newmark", "quasi_static", "symplectic_euler"}) {
    for (const char* optimizer : {"newton", "dogleg", "lbfgs", "bfgs", "ncg", "gradient_descent"}) {
      const std::string name = integrator;
      const double h = name == "symplectic_euler" ? 1e-4 : 1.0 / 60.0;
      const double tolerance = 1e-6;
      Simulation sim(ClothScene(5, 1e3), Options(integrator, optimizer, h, tolerance));
      for (int step = 0; step < 3; ++step) {
        const StepReport r = sim.Step();
        EXPECT_TRUE(r.converged) << integrator << " " << optimizer << ": " << r.status
                                 << " residual " << r.residual;
      }
      EXPECT_TRUE(sim.state().x.allFinite());
    }
  }
}

}  // namespace
}  // namespace ipstep
