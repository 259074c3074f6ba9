// Test helper: a cost function's Jacobian against central differences, block
// by block. `tolerance` is absolute; pass a scale-aware value.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

namespace ipstep::testing {

// Residuals and row-major Jacobian blocks of `cost` at x; false if it fails there.
inline bool EvaluateWithJacobian(const ceres::CostFunction& cost,
                                 const std::vector<std::vector<double>>& x,
                                 std::vector<double>* residuals,
                                 std::vector<std::vector<double>>* jacobian) {
  const int m = cost.num_residuals();
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<const double*> parameters;
  for (const auto& block : x) parameters.push_back(block.data());
  jacobian->assign(sizes.size(), {});
  std::vector<double*> jacobian_blocks;
  for (size_t b = 0; b < sizes.size(); ++b) {
    (*jacobian)[b].resize(m * sizes[b]);
    jacobian_blocks.push_back((*jacobian)[b].data());
  }
  residuals->resize(m);
  return cost.Evaluate(parameters.data(), residuals->data(), jacobian_blocks.data());
}

inline void ExpectJacobianMatchesFiniteDifferences(const ceres::CostFunction& cost,
                                                   std::vector<std::vector<double>> x, double step,
                                                   double tolerance) {
  const int m = cost.num_residuals();
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<double> r;
  std::vector<std::vector<double>> jacobian;
  ASSERT_TRUE(EvaluateWithJacobian(cost, x, &r, &jacobian));
  std::vector<const double*> parameters;
  for (auto& block : x) parameters.push_back(block.data());
  std::vector<double> r_plus(m), r_minus(m);
  for (size_t b = 0; b < sizes.size(); ++b) {
    for (int k = 0; k < sizes[b]; ++k) {
      const double saved = x[b][k];
      x[b][k] = saved + step;
      ASSERT_TRUE(cost.Evaluate(parameters.data(), r_plus.data(), nullptr));
      x[b][k] = saved - step;
      ASSERT_TRUE(cost.Evaluate(parameters.data(), r_minus.data(), nullptr));
      x[b][k] = saved;
      for (int i = 0; i < m; ++i) {
        EXPECT_NEAR(jacobian[b][i * sizes[b] + k], (r_plus[i] - r_minus[i]) / (2 * step), tolerance)
            << "block " << b << " coordinate " << k << " residual " << i;
      }
    }
  }
}

// The largest Jacobian entry of `cost` at x (for relative tolerances).
inline double JacobianScale(const ceres::CostFunction& cost,
                            const std::vector<std::vector<double>>& x) {
  std::vector<double> r;
  std::vector<std::vector<double>> jacobian;
  if (!EvaluateWithJacobian(cost, x, &r, &jacobian)) return 0.0;
  double scale = 1e-12;
  for (const auto& block : jacobian) {
    for (double v : block) scale = std::max(scale, std::abs(v));
  }
  return scale;
}

}  // namespace ipstep::testing
