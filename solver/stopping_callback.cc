#include "solver/stopping_callback.h"

#include <glog/logging.h>

namespace ipstep {

ceres::CallbackReturnType StoppingCallback::operator()(const ceres::IterationSummary& summary) {
  // A rejected trust-region step leaves the iterate unchanged.
  if (summary.step_is_successful || last_measure_ < 0.0) last_measure_ = measure_();
  const double step = summary.step_size > 0.0 ? summary.step_size : summary.step_norm;
  VLOG(2) << "  iteration " << summary.iteration << " E=" << summary.cost
          << " |g|max=" << summary.gradient_max_norm << " step=" << step
          << " residual=" << last_measure_ << (summary.step_is_successful ? "" : " (rejected)");
  if (sink_ != nullptr && *sink_) {
    IterationRecord r;
    r.iteration = iteration_offset_ + summary.iteration;
    r.energy = summary.cost * energy_scale_;
    r.gradient_norm = summary.gradient_max_norm;
    r.step_size = step;
    r.seconds = summary.cumulative_time_in_seconds;
    r.residual = last_measure_;
    (*sink_)(r);
  }
  return last_measure_ <= tolerance_ ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                     : ceres::SOLVER_CONTINUE;
}

}  // namespace ipstep
