// Ceres iteration callback that applies the stopping rule at every accepted
// iterate (ending the solve with USER_SUCCESS) and reports iterations.
#pragma once

#include <functional>

#include <ceres/iteration_callback.h>

#include "solver/step_solver.h"

namespace ipstep {

class StoppingCallback : public ceres::IterationCallback {
 public:
  // `measure` evaluates the stopping measure at the solver's current iterate
  // (update_state_every_iteration is on) and returns it; infinity if unknown.
  // `energy_scale` converts Ceres's cost to the incremental potential E.
  StoppingCallback(double tolerance, std::function<double()> measure, const IterationSink* sink,
                   double energy_scale = 1.0)
      : tolerance_(tolerance),
        measure_(std::move(measure)),
        sink_(sink),
        energy_scale_(energy_scale) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;
  // `iteration_offset` is added to reported iteration numbers (a solver that
  // restarts Ceres continues its count).
  void Reset(int iteration_offset = 0) {
    last_measure_ = -1.0;
    iteration_offset_ = iteration_offset;
  }

 private:
  double tolerance_;
  std::function<double()> measure_;
  const IterationSink* sink_;
  double energy_scale_;
  double last_measure_ = -1.0;
  int iteration_offset_ = 0;
};

}  // namespace ipstep
