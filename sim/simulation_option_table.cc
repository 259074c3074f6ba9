#include "sim/simulation_option_table.h"

#include "core/input_limits.h"
#include "integrators/integrator_option_table.h"
#include "solver/optimizer_option_table.h"

namespace ipstep {
namespace {

using Row = OptionRow<SimulationOptions>;

Row Own(const char* name, const char* flag, OptionType type, OptionValue value, const char* doc) {
  return MakeOptionRow<SimulationOptions>(name, std::string("SimulationOptions.") + name, flag,
                                          type, std::move(value), doc);
}

// A parameter of an effect, set as SimulationOptions::effect_overrides[effect][key].
Row Override(const char* name, const char* effect, const char* key, OptionType type, double min,
             double max, const char* unit, bool min_open, const char* doc) {
  Row row = WithRange(MakeOptionRow<SimulationOptions>(
                          name, std::string("effect_overrides.") + effect + "." + key, name, type,
                          type == OptionType::kInt ? OptionValue(0LL) : OptionValue(0.0), doc),
                      min, max, unit, std::string("the scene's ") + key, min_open);
  const std::string effect_name = effect, key_name = key;
  row.set = [effect_name, key_name](const OptionValue& v, SimulationOptions* o) {
    if (const long long* i = std::get_if<long long>(&v)) {
      o->effect_overrides[effect_name][key_name] = *i;
    } else {
      o->effect_overrides[effect_name][key_name] = std::get<double>(v);
    }
  };
  return row;
}

// The rows of SimulationOptions' own fields.
OptionTable<SimulationOptions> BuildOwn() {
  OptionTable<SimulationOptions> t;
  Row time_step =
      WithRange(Own("time_step", "dt", OptionType::kDouble, 0.0, "Time step"), limits::kMinTimeStep,
                limits::kMaxTimeStep, "s", "the scene's time_step");
  BindField(&SimulationOptions::time_step, &time_step);
  t.push_back(time_step);
  Row steps = WithRange(Own("steps", "steps", OptionType::kInt, -1LL, "Number of steps"), 0,
                        limits::kMaxSteps, "", "the scene's steps");
  BindField(&SimulationOptions::steps, &steps);
  t.push_back(steps);
  Row t_end = WithRange(Own("t_end", "t_end", OptionType::kDouble, 0.0,
                            "End time, not with steps: t_end / dt steps (a whole number, or an "
                            "error names a dt that fits)"),
                        0.0, limits::kMaxSteps * limits::kMaxTimeStep, "s", "the scene's steps",
                        /*min_open=*/true);
  BindField(&SimulationOptions::t_end, &t_end);
  t.push_back(t_end);
  Row energy = WithRange(Own("energy_tolerance", "energy_tolerance", OptionType::kDouble, 0.1,
                             "A step whose energy grows by more than this fraction of the energy "
                             "in motion fails with status 'energy growth' (variational "
                             "integrators; 0: no check)"),
                         0.0, 100.0, "");
  BindField(&SimulationOptions::energy_tolerance, &energy);
  t.push_back(energy);
  Row substeps = WithRange(
      Own("max_substeps", "max_substeps", OptionType::kInt,
          static_cast<long long>(SimulationOptions().max_substeps),
          "A failed step is retried from its start as 2, 4, ... substeps, up to this many (1: "
          "no retry)"),
      1, limits::kMaxSubsteps, "");
  BindField(&SimulationOptions::max_substeps, &substeps);
  t.push_back(substeps);
  return t;
}

const OptionTable<SimulationOptions>& OwnRows() {
  static const OptionTable<SimulationOptions> table = BuildOwn();
  return table;
}

OptionTable<SimulationOptions> Build() {
  OptionTable<SimulationOptions> t =
      LiftOptions(IntegratorOptionTable(), &SimulationOptions::integrator);
  const OptionTable<SimulationOptions> optimizer =
      LiftOptions(OptimizerOptionTable(), &SimulationOptions::optimizer);
  t.insert(t.end(), optimizer.begin(), optimizer.end());
  t.insert(t.end(), OwnRows().begin(), OwnRows().end());
  t.push_back(Override(
      "contact_kappa", "contact", "kappa", OptionType::kDouble, 0.0, limits::kMaxKappa, "", true,
      "Fixed barrier stiffness kappa for scenes with contact (adaptive when neither the "
      "scene nor this option gives one)"));
  t.push_back(Override("contact_dhat", "contact", "dhat", OptionType::kDouble, limits::kMinDhat,
                       limits::kMaxDhat, "m", false,
                       "Barrier activation distance d_hat for scenes with contact"));
  t.push_back(Override("friction_mu", "friction", "mu", OptionType::kDouble, 0.0,
                       limits::kMaxFrictionMu, "", false,
                       "Friction coefficient for scenes with friction"));
  t.push_back(
      Override("friction_iterations", "friction", "iterations", OptionType::kInt, 1,
               limits::kMaxFrictionIterations, "", false,
               "Friction lag iterations per step for scenes with friction (a scene's default is "
               "1)"));
  return t;
}

}  // namespace

const OptionTable<SimulationOptions>& SimulationOptionTable() {
  static const OptionTable<SimulationOptions> table = Build();
  return table;
}

void CheckSimulationOptionRanges(const SimulationOptions& options) {
  CheckOptionRanges(OwnRows(), options);
}

const OptionTable<RunOptions>& RunOptionTable() {
  static const OptionTable<RunOptions> table = [] {
    OptionTable<RunOptions> t;
    OptionRow<RunOptions> stop = MakeOptionRow<RunOptions>(
        "stop_on_failure", "RunOptions.stop_on_failure", "", OptionType::kBool, false,
        "Stop at the first step that fails (also as substeps); otherwise failed steps are "
        "counted and the run goes on (the ipstep program sets it unless told to continue)");
    BindField(&RunOptions::stop_on_failure, &stop);
    t.push_back(stop);
    OptionRow<RunOptions> diverge = MakeOptionRow<RunOptions>(
        "stop_on_divergence", "RunOptions.stop_on_divergence", "", OptionType::kBool, true,
        "Stop at the first diverged step (sim/divergence.h)");
    BindField(&RunOptions::stop_on_divergence, &diverge);
    t.push_back(diverge);
    OptionRow<RunOptions> wall =
        WithRange(MakeOptionRow<RunOptions>(
                      "max_wall_seconds", "RunOptions.max_wall_seconds", "", OptionType::kDouble,
                      0.0, "Stop once the run has taken this long [s] with steps left"),
                  0.0, limits::kMaxTimeLimit, "s", "no limit", /*min_open=*/true);
    BindField(&RunOptions::max_wall_seconds, &wall);
    t.push_back(wall);
    return t;
  }();
  return table;
}

const OptionTable<AdaptiveOptions>& AdaptiveOptionTable() {
  static const OptionTable<AdaptiveOptions> table = [] {
    using Row = OptionRow<AdaptiveOptions>;
    const auto own = [](const char* name, const char* flag, double value, const char* doc) {
      return MakeOptionRow<AdaptiveOptions>(name, std::string("AdaptiveOptions.") + name, flag,
                                            OptionType::kDouble, value, doc);
    };
    OptionTable<AdaptiveOptions> t;
    Row tolerance = WithRange(own("error_tolerance", "error_tolerance", 0.0,
                                  "Adaptive runs: the position error to reach at the end time"),
                              0.0, 1e6, "m", "none: an adaptive run must give it",
                              /*min_open=*/true);
    BindField(&AdaptiveOptions::error_tolerance, &tolerance);
    t.push_back(tolerance);
    Row min_h =
        WithRange(own("min_time_step", "min_dt", 0.0, "Adaptive runs: the smallest step"),
                  limits::kMinTimeStep, limits::kMaxTimeStep, "s", "max(1e-12, 1e-9 t_end)");
    BindField(&AdaptiveOptions::min_time_step, &min_h);
    t.push_back(min_h);
    Row max_h = WithRange(own("max_time_step", "max_dt", 0.0, "Adaptive runs: the largest step"),
                          limits::kMinTimeStep, limits::kMaxTimeStep, "s", "t_end / 10");
    BindField(&AdaptiveOptions::max_time_step, &max_h);
    t.push_back(max_h);
    Row safety = WithRange(own("safety", "", 0.9, "The controller's safety factor s"), 0.0, 1.0, "",
                           "", /*min_open=*/true);
    BindField(&AdaptiveOptions::safety, &safety);
    t.push_back(safety);
    Row growth =
        WithRange(own("max_growth", "", 2.0, "The largest growth h'/h after an accepted step"), 1.0,
                  10.0, "");
    BindField(&AdaptiveOptions::max_growth, &growth);
    t.push_back(growth);
    // (0, 1): a rejection shrinks the step; ValidateAdaptiveOptions refuses 1.
    Row shrink =
        WithRange(own("max_shrink", "", 0.2, "The smallest factor h'/h of a rejected step"), 0.0,
                  1.0, "", "", /*min_open=*/true);
    BindField(&AdaptiveOptions::max_shrink, &shrink);
    t.push_back(shrink);
    Row filter = MakeOptionRow<AdaptiveOptions>(
        "filter_stiff_modes", "AdaptiveOptions.filter_stiff_modes", "filter_stiff_modes",
        OptionType::kBool, AdaptiveOptions{}.filter_stiff_modes,
        "Adaptive runs: judge the local error estimate through the step's own matrix, "
        "(M + c K)^-1 M e, so that modes the step does not resolve count by their amplitude, "
        "not their acceleration (sim/stiff_mode_filter.h); false: the raw estimate");
    BindField(&AdaptiveOptions::filter_stiff_modes, &filter);
    t.push_back(filter);
    return t;
  }();
  return table;
}

void CheckOptionsApply(const SimulationOptions& options, const std::vector<std::string>& given) {
  for (const std::string& name : given) {
    const Row* row = FindOption(SimulationOptionTable(), name);
    if (row == nullptr || !row->applies) continue;
    const std::string why = row->applies(options, "");
    // A table's field (tests/apps/flag_names_test.cc counts them as reported).
    if (!why.empty()) throw InputError("options: " + row->field + ": " + why);
  }
}

}  // namespace ipstep
