// Every energy's Jacobian against central finite differences, with probes that
// stay inside each energy's domain. Tolerance: relative 1e-6 of the Jacobian
// scale (central differences with step 1e-6 have error ~1e-10 here).
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include "core/step_context.h"
#include "core/term.h"
#include "energies/gravity_potential.h"
#include "energies/hookean_spring.h"
#include "energies/inertia.h"
#include "energies/quartic_spring.h"
#include "energies/rayleigh_mass_damping.h"
#include "energies/rayleigh_stiffness_damping.h"
#include "energies/squared_strain_spring.h"
#include "tests/support/finite_differences.h"

namespace ipstep {
namespace {

// The analytic (autodiff) Jacobian of `cost` at `x` (one block per node) against
// central differences, to 1e-6 of the Jacobian's largest entry.
void ExpectJacobianMatchesFiniteDifferences(const ceres::CostFunction& cost,
                                            const std::vector<std::vector<double>>& x) {
  testing::ExpectJacobianMatchesFiniteDifferences(cost, x, 1e-6,
                                                  1e-6 * testing::JacobianScale(cost, x));
}

template <int D>
std::vector<double> RandomPoint(std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> p(D);
  for (double& v : p) v = u(*rng);
  return p;
}

template <int D>
void CheckSprings() {
  std::mt19937 rng(7 + D);
  for (int trial = 0; trial < 20; ++trial) {
    auto xi = RandomPoint<D>(&rng);
    auto xj = RandomPoint<D>(&rng);
    xj[0] += 2.5;  // keep |d| well away from 0
    ceres::AutoDiffCostFunction<HookeanSpring<D>, 1, D, D> hookean(new HookeanSpring<D>(1e4, 1.3));
    ExpectJacobianMatchesFiniteDifferences(hookean, {xi, xj});
    ceres::AutoDiffCostFunction<SquaredStrainSpring<D>, 1, D, D> strain(
        new SquaredStrainSpring<D>(2e4, 0.7));
    ExpectJacobianMatchesFiniteDifferences(strain, {xi, xj});
    ceres::AutoDiffCostFunction<QuarticSpring<D>, 1, D, D> quartic(new QuarticSpring<D>(3.0, 1.1));
    ExpectJacobianMatchesFiniteDifferences(quartic, {xi, xj});
  }
}

TEST(EnergyDerivatives, Springs2D) { CheckSprings<2>(); }
TEST(EnergyDerivatives, Springs3D) { CheckSprings<3>(); }

TEST(EnergyDerivatives, SpringEnergiesHaveTheirDefinitions) {
  // e = 1/2 r^2 reproduces each model's energy.
  const double xi[2] = {0.0, 0.0}, xj[2] = {1.5, 0.0};
  const double* p[2] = {xi, xj};
  double r = 0.0;
  ceres::AutoDiffCostFunction<HookeanSpring<2>, 1, 2, 2> hookean(new HookeanSpring<2>(8.0, 1.0));
  ASSERT_TRUE(hookean.Evaluate(p, &r, nullptr));
  EXPECT_NEAR(0.5 * r * r, 0.5 * 8.0 * 0.25, 1e-14);
  ceres::AutoDiffCostFunction<SquaredStrainSpring<2>, 1, 2, 2> strain(
      new SquaredStrainSpring<2>(8.0, 1.0));
  ASSERT_TRUE(strain.Evaluate(p, &r, nullptr));
  EXPECT_NEAR(0.5 * r * r, 0.5 * 8.0 * 1.0 * std::pow(2.25 - 1.0, 2), 1e-13);
  ceres::AutoDiffCostFunction<QuarticSpring<2>, 1, 2, 2> quartic(new QuarticSpring<2>(8.0, 1.0));
  ASSERT_TRUE(quartic.Evaluate(p, &r, nullptr));
  EXPECT_NEAR(0.5 * r * r, 8.0 * std::pow(0.5, 4), 1e-14);
}

TEST(EnergyDerivatives, CollapsedHookeanSpringIsInfeasible) {
  const double xi[2] = {0.3, 0.3};
  const double* p[2] = {xi, xi};
  double r = 0.0;
  ceres::AutoDiffCostFunction<HookeanSpring<2>, 1, 2, 2> hookean(new HookeanSpring<2>(1.0, 1.0));
  EXPECT_FALSE(hookean.Evaluate(p, &r, nullptr));
}

TEST(EnergyDerivatives, InertiaDampingAndGravity) {
  StepContext context;
  context.Resize(3, 2);
  context.x_tilde << 0.1, 0.2, 0.3, -0.4, 0.5, 0.6;
  context.x_base << 1.0, 1.1, 1.2, 1.3, 1.4, 1.5;
  context.v_base << 0.3, -0.2, 0.1, 0.0, 0.7, -0.5;
  context.x_start << 0.0, 0.0, 0.0, 1.0, 0.5, 0.2;
  context.velocity_slope = 37.0;
  std::mt19937 rng(3);
  for (int trial = 0; trial < 10; ++trial) {
    auto xi = RandomPoint<3>(&rng), xj = RandomPoint<3>(&rng);
    ceres::AutoDiffCostFunction<InertiaResidual<3>, 3, 3> inertia(
        new InertiaResidual<3>(&context, 1, 2.5));
    ExpectJacobianMatchesFiniteDifferences(inertia, {xj});
    ceres::AutoDiffCostFunction<RayleighMassDamping<3>, 3, 3> mass_damping(
        new RayleighMassDamping<3>(&context, 0, 0.8));
    ExpectJacobianMatchesFiniteDifferences(mass_damping, {xi});
    ceres::AutoDiffCostFunction<RayleighStiffnessDamping<3>, 1, 3, 3> stiffness_damping(
        new RayleighStiffnessDamping<3>(&context, 0, 1, 40.0));
    ExpectJacobianMatchesFiniteDifferences(stiffness_damping, {xi, xj});
    const double g[3] = {0.0, -9.81, 0.0};
    ceres::AutoDiffCostFunction<GravityPotential<3>, 1, 3> gravity(
        new GravityPotential<3>(&context, 1, 2.0, g, 100.0));
    ExpectJacobianMatchesFiniteDifferences(gravity, {xi});
  }
}

TEST(EnergyDerivatives, GravityPotentialDiffersFromMinusMgxByAConstant) {
  StepContext context;
  context.Resize(2, 1);
  const double g[2] = {0.0, -9.81};
  ceres::AutoDiffCostFunction<GravityPotential<2>, 1, 2> gravity(
      new GravityPotential<2>(&context, 0, 2.0, g, 100.0));
  auto energy = [&](double x, double y) {
    const double p[2] = {x, y};
    const double* params[1] = {p};
    double r = 0.0;
    EXPECT_TRUE(gravity.Evaluate(params, &r, nullptr));
    return 0.5 * r * r;
  };
  // -m g.x = 2 * 9.81 * y
  EXPECT_NEAR(energy(0.3, 1.0) - energy(-0.2, 0.0), 2.0 * 9.81 * 1.0, 1e-9);
}

TEST(EnergyDerivatives, WeightedCostScalesEnergyByWeight) {
  double weight = 0.04;
  ceres::AutoDiffCostFunction<HookeanSpring<2>, 1, 2, 2> spring(new HookeanSpring<2>(3.0, 1.0));
  WeightedCostFunction weighted(&spring, &weight);
  const double xi[2] = {0.0, 0.0}, xj[2] = {1.2, 0.5};
  const double* p[2] = {xi, xj};
  double r = 0.0, rw = 0.0;
  ASSERT_TRUE(spring.Evaluate(p, &r, nullptr));
  ASSERT_TRUE(weighted.Evaluate(p, &rw, nullptr));
  EXPECT_NEAR(rw * rw, weight * r * r, 1e-15);
  ExpectJacobianMatchesFiniteDifferences(weighted, {{0.0, 0.0}, {1.2, 0.5}});
}

}  // namespace
}  // namespace ipstep
