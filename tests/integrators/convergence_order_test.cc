// Convergence order on the stiff spring pendulum q'' = -C (|q| - 1) q/|q| - (0, 1)
// (C = 1000, q0 = (0.9, 0.1), v0 = 0) against an RK4 reference with a tiny step:
// backward Euler is first order, Newmark(1/4, 1/2) second order.
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "sim/simulation.h"
#include "tests/support/test_scenes.h"

namespace ipstep {
namespace {

using State4 = std::array<double, 4>;  // q, v

State4 Rhs(const State4& s) {
  const double r = std::hypot(s[0], s[1]);
  const double f = -1000.0 * (r - 1.0) / r;
  return {s[2], s[3], f * s[0], f * s[1] - 1.0};
}

State4 Reference(double t_end) {
  State4 s = {0.9, 0.1, 0.0, 0.0};
  const int n = static_cast<int>(std::lround(t_end / 1e-5));
  const double h = t_end / n;
  auto axpy = [](const State4& a, double c, const State4& b) {
    State4 r;
    for (int i = 0; i < 4; ++i) r[i] = a[i] + c * b[i];
    return r;
  };
  for (int i = 0; i < n; ++i) {
    const State4 k1 = Rhs(s), k2 = Rhs(axpy(s, h / 2, k1)), k3 = Rhs(axpy(s, h / 2, k2)),
                 k4 = Rhs(axpy(s, h, k3));
    for (int j = 0; j < 4; ++j) s[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
  }
  return s;
}

double FittedSlope(const std::vector<double>& h, const std::vector<double>& error) {
  const int n = static_cast<int>(h.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (int i = 0; i < n; ++i) {
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double FinalError(const std::string& integrator, double h, double t_end, const State4& exact) {
  Simulation sim(testing::SpringPendulumScene(), testing::Options(integrator, "newton", h, 1e-7));
  const int steps = static_cast<int>(std::lround(t_end / h));
  for (int i = 0; i < steps; ++i) {
    const StepReport r = sim.Step();
    EXPECT_TRUE(r.converged) << r.status << " residual " << r.residual;
  }
  return std::hypot(sim.state().x[2] - exact[0], sim.state().x[3] - exact[1]);
}

TEST(ConvergenceOrder, BackwardEulerIsFirstOrderNewmarkSecondOrder) {
  const double t_end = 0.4;
  const State4 exact = Reference(t_end);
  std::vector<double> hs = {4e-4, 2e-4, 1e-4, 5e-5}, errors;
  for (double h : hs) errors.push_back(FinalError("backward_euler", h, t_end, exact));
  const double be_slope = FittedSlope(hs, errors);
  EXPECT_NEAR(be_slope, 1.0, 0.2);

  hs = {2e-3, 1e-3, 5e-4, 2.5e-4};
  errors.clear();
  for (double h : hs) errors.push_back(FinalError("newmark", h, t_end, exact));
  const double newmark_slope = FittedSlope(hs, errors);
  EXPECT_NEAR(newmark_slope, 2.0, 0.2);
  RecordProperty("backward_euler_slope", std::to_string(be_slope));
  RecordProperty("newmark_slope", std::to_string(newmark_slope));
}

}  // namespace
}  // namespace ipstep
