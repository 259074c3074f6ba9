#include "sim/checkpoint_recorder.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ipstep {

CheckpointRecorder::CheckpointRecorder(std::vector<double> times) : times_(std::move(times)) {}

void CheckpointRecorder::Attach(const Simulation& sim, RunOptions* options) {
  sim_ = &sim;
  positions_.clear();
  const State& state = sim.state();
  while (positions_.size() < times_.size() && times_[positions_.size()] <= state.time) {
    positions_.push_back(state.x);
  }
  auto before = std::move(options->before_step);
  options->before_step = [this, before](int step) {
    if (before) before(step);
    BeforeStep();
  };
  auto after = std::move(options->after_step);
  options->after_step = [this, after](const StepReport& report) {
    if (after) after(report);
    AfterStep();
  };
}

void CheckpointRecorder::BeforeStep() {
  if (complete()) return;
  const State& state = sim_->state();
  start_time_ = state.time;
  start_x_ = state.x;
  start_v_ = state.v;
}

void CheckpointRecorder::AfterStep() {
  if (complete()) return;
  const State& end = sim_->state();
  const double h = end.time - start_time_;
  if (!(h > 0.0)) return;
  // Round-off: a fixed run's time is a sum of its steps and may end a little
  // short of its last checkpoint (64000 steps of 1/64000 s end at 1 - 9e-13 s).
  const double slack = 1e-9 * (h + std::abs(end.time));
  while (!complete() && times_[positions_.size()] <= end.time + slack) {
    const double t = times_[positions_.size()];
    if (t >= end.time - slack) {  // on the step's end
      positions_.push_back(end.x);
      continue;
    }
    const double s = std::max(0.0, (t - start_time_) / h);
    const double s2 = s * s, s3 = s2 * s;
    positions_.push_back((2 * s3 - 3 * s2 + 1) * start_x_ + ((s3 - 2 * s2 + s) * h) * start_v_ +
                         (-2 * s3 + 3 * s2) * end.x + ((s3 - s2) * h) * end.v);
  }
}

std::vector<double> CheckpointTimes(double t_start, double duration, int count) {
  std::vector<double> times;
  for (int j = 1; j <= count; ++j) times.push_back(t_start + duration * j / count);
  return times;
}

}  // namespace ipstep
