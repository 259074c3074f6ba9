// Test helper: a cost function's Jacobian against central differences, block
// by block. `tolerance` is absolute; pass a scale-aware value.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <ceres/cost_function.h>
#include <gtest/gtest.h>

namespace ipstep::testing {

inline void ExpectJacobianMatchesFiniteDifferences(const ceres::CostFunction& cost,
                                                   std::vector<std::vector<double>> x, double step,
                                                   double tolerance) {
  const int m = cost.num_residuals();
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<const double*> parameters;
  for (auto& block : x) parameters.push_back(block.data());
  std::vector<std::vector<double>> jacobian(sizes.size());
  std::vector<double*> jacobian_blocks;
  for (size_t b = 0; b < sizes.size(); ++b) {
    jacobian[b].resize(m * sizes[b]);
    jacobian_blocks.push_back(jacobian[b].data());
  }
  std::vector<double> r(m), r_plus(m), r_minus(m);
  ASSERT_TRUE(cost.Evaluate(parameters.data(), r.data(), jacobian_blocks.data()));
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
inline double JacobianScale(const ceres::CostFunction& cost, std::vector<std::vector<double>> x) {
  const int m = cost.num_residuals();
  const auto& sizes = cost.parameter_block_sizes();
  std::vector<const double*> parameters;
  for (auto& block : x) parameters.push_back(block.data());
  std::vector<std::vector<double>> jacobian(sizes.size());
  std::vector<double*> jacobian_blocks;
  for (size_t b = 0; b < sizes.size(); ++b) {
    jacobian[b].resize(m * sizes[b]);
    jacobian_blocks.push_back(jacobian[b].data());
  }
  std::vector<double> r(m);
  if (!cost.Evaluate(parameters.data(), r.data(), jacobian_blocks.data())) return 0.0;
  double scale = 1e-12;
  for (const auto& block : jacobian) {
    for (double v : block) scale = std::max(scale, std::abs(v));
  }
  return scale;
}

}  // namespace ipstep::testing
