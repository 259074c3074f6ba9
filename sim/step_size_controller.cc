#include "sim/step_size_controller.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/simulation_option_table.h"

namespace ipstep {
namespace {

// Empty if `value` is finite and > 0 (>= 0 with `zero_allowed`), else why not.
std::string NotPositive(double value, bool zero_allowed) {
  if (std::isfinite(value) && value >= 0.0 && (zero_allowed || value > 0.0)) return "";
  return std::string("must be a finite number ") + (zero_allowed ? ">= 0" : "> 0") + ", got " +
         limits::FormatLimit(value);
}

}  // namespace

void ValidateAdaptiveOptions(const AdaptiveOptions& o) {
  // error_tolerance, min/max_time_step, safety, max_growth, max_shrink: their rows.
  CheckOptionRanges(AdaptiveOptionTable(), o);
  // The row's default 0 is no tolerance: an adaptive run must give one.
  const OptionRow<AdaptiveOptions>& tolerance =
      *FindOption(AdaptiveOptionTable(), "error_tolerance");
  if (o.error_tolerance == 0.0) {
    throw InputError(
        "options", "AdaptiveOptions.error_tolerance",
        "must be in " +
            limits::RangeText(tolerance.min, tolerance.max, tolerance.unit, tolerance.min_open) +
            ": an adaptive run must give it, got 0");
  }
  std::string why;
  if (!(why = NotPositive(o.t_end, false)).empty()) {
    throw InputError("options", "AdaptiveOptions.t_end", why);
  }
  if (!(why = NotPositive(o.initial_time_step, true)).empty()) {
    throw InputError("options", "AdaptiveOptions.initial_time_step", why);
  }
  if (o.min_time_step > 0.0 && o.max_time_step > 0.0 && o.min_time_step > o.max_time_step) {
    throw InputError("options", "AdaptiveOptions.min_time_step",
                     "the smallest step " + limits::FormatLimit(o.min_time_step) +
                         " s must not exceed the largest, " + limits::FormatLimit(o.max_time_step) +
                         " s");
  }
  // The row's range is (0, 1]; a rejection must shrink the step.
  if (o.max_shrink == 1.0) {
    throw InputError("options", "AdaptiveOptions.max_shrink", "must be < 1, got 1");
  }
}

double AdaptiveSolverTolerance(const AdaptiveOptions& o) {
  return 0.1 * o.error_tolerance / o.t_end;
}

double AdaptiveStallResidual(const AdaptiveOptions& o) { return 0.5 * o.error_tolerance / o.t_end; }

StepSizeController::StepSizeController(const AdaptiveOptions& options, int order)
    : options_(options), order_(std::max(1, order)) {
  ValidateAdaptiveOptions(options);
  min_h_ = options.min_time_step > 0.0 ? options.min_time_step
                                       : std::max(limits::kMinTimeStep, 1e-9 * options.t_end);
  max_h_ = options.max_time_step > 0.0 ? options.max_time_step : options.t_end / 10.0;
  max_h_ = std::min(max_h_, limits::kMaxTimeStep);
  min_h_ = std::min(min_h_, max_h_);
}

double StepSizeController::Budget(double h) const {
  return options_.error_tolerance * h / options_.t_end;
}

double StepSizeController::ImpactBudget() const { return options_.error_tolerance / 8.0; }

double StepSizeController::Clamp(double h) const { return std::clamp(h, min_h_, max_h_); }

StepSizeController::Decision StepSizeController::Judge(double h, double error, double impact_error,
                                                       double contact_error) {
  Decision decision;
  // In contact (the contact forces make half the estimate or more) the step
  // gets the absolute budget; r: the error in budgets; a vanishing estimate
  // (free flight under Newmark) grows the step as fast as allowed.
  const bool impact = std::max(impact_error, contact_error) > 0.0 &&
                      std::max(impact_error, contact_error) >= 0.5 * error;
  const double budget = impact ? std::max(Budget(h), ImpactBudget()) : Budget(h);
  const double ratio = std::max({error / budget, impact_error / ImpactBudget(), 1e-10});
  const double p = order_;
  decision.over_budget = ratio > 1.0;
  if (ratio <= 1.0 || h <= min_h_) {
    decision.accept = true;
    double factor =
        options_.safety * std::pow(ratio, -0.7 / p) * std::pow(previous_ratio_, 0.4 / p);
    factor = std::clamp(factor, options_.max_shrink, after_rejection_ ? 1.0 : options_.max_growth);
    decision.next_time_step = Clamp(h * factor);
    previous_ratio_ =
        std::max(ratio, 1e-2);  // a vanishing estimate (an exact step) predicts nothing
    after_rejection_ = false;
    return decision;
  }
  const double factor = std::max(options_.max_shrink, options_.safety * std::pow(ratio, -1.0 / p));
  decision.next_time_step = Clamp(h * std::min(factor, 0.9));
  after_rejection_ = true;
  return decision;
}

StepSizeController::Decision StepSizeController::Failed(double h) {
  Decision decision;
  after_rejection_ = true;
  if (h <= min_h_) {
    decision.accept = true;
    decision.next_time_step = min_h_;
    return decision;
  }
  decision.next_time_step = Clamp(0.25 * h);
  return decision;
}

}  // namespace ipstep
