// Positions of a run at given times ("checkpoints"), whatever its steps:
// fixed or adaptive, they rarely end on those times. The recorder watches the
// run loop (RunOptions::before_step / after_step, sim/run_trajectory.h) and
// takes each checkpoint t_j from the accepted step that crosses it,
// t_n < t_j <= t_{n+1}, as the cubic Hermite polynomial through (x_n, v_n) and
// (x_{n+1}, v_{n+1}): with s = (t_j - t_n) / h,
//   x(t_j) = (2s^3 - 3s^2 + 1) x_n + (s^3 - 2s^2 + s) h v_n
//          + (-2s^3 + 3s^2) x_{n+1} + (s^3 - s^2) h v_{n+1}.
// A checkpoint on a step's end, to round-off (within 1e-9 (h + t): the time
// of a run is a sum of its steps), is that step's x exactly.
//
// Limits: the polynomial is the path only as far as the step's end velocities
// describe it. It reproduces a quadratic exactly and a smooth path to O(h^4)
// with exact end values; with the integrator's own velocities it adds no
// error of a lower order than the run's (backward Euler: O(h), Newmark:
// O(h^2)). A velocity that jumps inside the step (an impact, a contact that
// starts or ends) is not followed: there the interpolated positions are off by
// the order of h |delta v|, and a checkpoint in such a step measures that too.
// Pinned and moving nodes are interpolated like the others (errors are measured
// on free nodes only: sim/reference.h FreeNodes).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep {

class CheckpointRecorder {
 public:
  // `times` [s], absolute (State::time), increasing; an empty list records nothing.
  explicit CheckpointRecorder(std::vector<double> times);

  // Adds the recorder to `options`: before_step and after_step call what they
  // called before, then the recorder. `sim` and the recorder must outlive the
  // run; checkpoints at or before the simulation's current time are taken
  // from its current state.
  void Attach(const Simulation& sim, RunOptions* options);

  const std::vector<double>& times() const { return times_; }
  // The positions at times()[j], for the checkpoints reached so far.
  const std::vector<Eigen::VectorXd>& positions() const { return positions_; }
  // Every checkpoint was reached.
  bool complete() const { return positions_.size() == times_.size(); }

 private:
  void BeforeStep();
  void AfterStep();

  std::vector<double> times_;
  std::vector<Eigen::VectorXd> positions_;
  const Simulation* sim_ = nullptr;
  // The state at the start of the step in progress.
  double start_time_ = 0.0;
  Eigen::VectorXd start_x_, start_v_;
};

// The K times t_start + duration * j / K, j = 1 .. K (the last is the end).
std::vector<double> CheckpointTimes(double t_start, double duration, int count);

}  // namespace ipstep
