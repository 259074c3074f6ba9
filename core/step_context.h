// What changes between steps, read by the energy terms through a pointer so
// that the ceres::Problem is built once per scene and reused.
//
// The incremental potential of a step is
//   E(x) = w_I/2 |x - x_tilde|_M^2 + w_U U(x) + w_R R(v(x))
// where the integrator sets the predictor x_tilde, the weights w_I, w_U, w_R and
// the discrete velocity as an affine map of the unknown positions
//   v(x) = v_base + velocity_slope (x - x_base).
// Stationarity gives M (x - x_tilde) w_I + w_U grad U + w_R slope B v = 0: each
// integrator chooses weights so this is its own update (see integrators/).
#pragma once

#include <Eigen/Core>

namespace ipstep {

struct StepContext {
  int dimension = 2;
  double time_step = 0.0;

  double inertia_weight = 1.0;      // w_I: 1 for dynamics, 0 for quasi-static
  double potential_weight = 1.0;    // w_U
  double dissipation_weight = 0.0;  // w_R
  double velocity_slope = 0.0;      // dv/dx

  // Sized once (dimension * nodes) and never reallocated: terms keep pointers.
  Eigen::VectorXd x_tilde;  // predictor (gravity folded in for dynamic integrators)
  Eigen::VectorXd x_base;   // see v(x) above
  Eigen::VectorXd v_base;
  Eigen::VectorXd x_start;  // positions at the start of the step (lagged quantities)

  void Resize(int dimension, int num_nodes);

  // Velocity of node `i` at positions x_i (templated for autodiff).
  template <typename T>
  void Velocity(int i, const T* x_i, T* v_i) const {
    for (int k = 0; k < dimension; ++k) {
      const int d = dimension * i + k;
      v_i[k] = v_base[d] + velocity_slope * (x_i[k] - x_base[d]);
    }
  }
};

}  // namespace ipstep
