#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "python/bindings.h"
#include "python/interrupt.h"
#include "sim/run_trajectory.h"
#include "sim/simulation_option_table.h"

namespace ipstep::python {
namespace {

// A step's verdict, from its status (docs/programs.md "Step statuses").
enum class StepStatus {
  kConverged,
  kIterationLimit,
  kTimeLimit,
  kStalled,
  kOptimizerFailure,
  kEnergyGrowth,
  kInfeasible,
  kNonFinite,
  kDiverged,
  kFailed,
};

StepStatus Classify(const StepReport& r) {
  if (r.converged) return StepStatus::kConverged;
  const auto starts = [&r](const char* prefix) { return r.status.rfind(prefix, 0) == 0; };
  if (starts("diverged")) return StepStatus::kDiverged;
  if (starts("iteration limit")) return StepStatus::kIterationLimit;
  if (starts("time limit")) return StepStatus::kTimeLimit;
  if (starts("stalled")) return StepStatus::kStalled;
  if (starts("optimizer failure") || starts("aborted") || starts("line search failed") ||
      starts("factorisation failed") || starts("Hessian cannot")) {
    return StepStatus::kOptimizerFailure;
  }
  if (starts("energy growth")) return StepStatus::kEnergyGrowth;
  if (starts("infeasible") || starts("moving boundary")) return StepStatus::kInfeasible;
  if (starts("non-finite") || starts("energy cannot") || starts("forces cannot")) {
    return StepStatus::kNonFinite;
  }
  return StepStatus::kFailed;
}

// A step's report with the names of its diagnostics (the step filters' columns).
struct PyStepReport {
  StepReport report;
  std::vector<std::string> diagnostic_names;
};

py::array_t<double> Nodes(const Eigen::VectorXd& values, int dimension) {
  const py::ssize_t nodes = values.size() / dimension;
  py::array_t<double> array({nodes, static_cast<py::ssize_t>(dimension)});
  std::copy(values.data(), values.data() + values.size(), array.mutable_data());
  return array;
}

class PySimulation {
 public:
  // `adaptive`: run() takes error-controlled steps to adaptive->t_end (from
  // the start); null: the simulation's fixed steps.
  PySimulation(std::shared_ptr<const Scene> scene, const SimulationOptions& options,
               std::optional<AdaptiveOptions> adaptive)
      : scene_(std::move(scene)), adaptive_(std::move(adaptive)) {
    py::gil_scoped_release release;
    sim_ = std::make_unique<Simulation>(*scene_, options);
    start_time_ = sim_->state().time;
  }
  bool adaptive() const { return adaptive_.has_value(); }
  Simulation& sim() { return *sim_; }
  const Simulation& sim() const { return *sim_; }

  PyStepReport Step() {
    PyStepReport r;
    {
      py::gil_scoped_release release;
      r.report = sim_->Step();
    }
    RaisePythonEnergyError();
    r.diagnostic_names = sim_->DiagnosticNames();
    return r;
  }

  RunSummary Run(const py::object& steps, const py::object& on_step, const py::kwargs& keywords) {
    RunOptions options = RunOptionsFrom(keywords);
    if (!steps.is_none()) options.steps = steps.cast<int>();
    if (adaptive_) {
      if (!steps.is_none()) {
        throw py::value_error(
            "Simulation.run: an adaptive simulation's steps follow from its error_tolerance; "
            "give no steps (it runs to its end time)");
      }
      // The rest of the way to the end time (nothing once there).
      const double left = start_time_ + adaptive_->t_end - sim_->state().time;
      if (left > 1e-12 * adaptive_->t_end) {
        options.adaptive = true;
        options.adaptive_options = *adaptive_;
        options.adaptive_options.t_end = left;
      } else {
        options.steps = 0;
      }
    }
    ValidateRunOptions(*sim_, options);
    PythonInterrupt interrupt;
    options.interrupt = interrupt.flag();
    const std::vector<std::string> names = sim_->DiagnosticNames();
    options.after_step = [&](const StepReport& report) {
      if (!on_step.is_none()) {
        py::gil_scoped_acquire gil;
        try {
          on_step(PyStepReport{report, names});
        } catch (py::error_already_set& error) {
          interrupt.Fail(std::move(error));
        }
      }
      interrupt.Check();
    };
    RunSummary summary;
    {
      py::gil_scoped_release release;
      summary = RunTrajectory(*sim_, options);
    }
    RaisePythonEnergyError();
    interrupt.RaiseIfInterrupted();
    return summary;
  }

 private:
  std::shared_ptr<const Scene> scene_;  // the simulation points into its copy
  std::optional<AdaptiveOptions> adaptive_;
  double start_time_ = 0.0;
  std::unique_ptr<Simulation> sim_;
};

// The adaptive keywords of Simulation(...) (AdaptiveOptionTable and
// adaptive=True), taken out of `keywords`; null without adaptive=True. The
// end time is t_end, or steps x dt, or the scene's steps x time_step; the
// options of the simulation are then set as ipstep --adaptive sets them.
std::optional<AdaptiveOptions> AdaptiveFrom(py::dict* keywords) {
  bool adaptive = false;
  if (keywords->contains("adaptive")) {
    const py::object value = (*keywords)["adaptive"];
    if (!value.is_none()) {
      if (!py::isinstance<py::bool_>(value)) {
        throw py::value_error("Simulation: adaptive must be True or False");
      }
      adaptive = value.cast<bool>();
    }
    PyDict_DelItemString(keywords->ptr(), "adaptive");
  }
  AdaptiveOptions options;
  std::vector<std::string> given;
  for (const auto& row : AdaptiveOptionTable()) {
    if (!keywords->contains(row.name)) continue;
    const py::object value = (*keywords)[row.name.c_str()];
    PyDict_DelItemString(keywords->ptr(), row.name.c_str());
    if (value.is_none()) continue;
    SetOption(row, ToOptionValue(row.field, value), &options);
    given.push_back(row.name);
  }
  if (!adaptive) {
    if (!given.empty()) {
      throw py::value_error("Simulation: " + given.front() + " applies with adaptive=True only");
    }
    return std::nullopt;
  }
  return options;
}

py::dict Energies(const EnergyReport& e) {
  py::dict d;
  d["kinetic"] = e.kinetic;
  d["potential"] = e.potential;
  d["total"] = e.total();
  return d;
}

}  // namespace

void BindSimulation(py::module_& m) {
  py::enum_<StepStatus>(m, "StepStatus",
                        "A step's verdict (StepReport.status; its message says more)")
      .value("CONVERGED", StepStatus::kConverged)
      .value("ITERATION_LIMIT", StepStatus::kIterationLimit)
      .value("TIME_LIMIT", StepStatus::kTimeLimit)
      .value("STALLED", StepStatus::kStalled)
      .value("OPTIMIZER_FAILURE", StepStatus::kOptimizerFailure)
      .value("ENERGY_GROWTH", StepStatus::kEnergyGrowth)
      .value("INFEASIBLE", StepStatus::kInfeasible)
      .value("NON_FINITE", StepStatus::kNonFinite)
      .value("DIVERGED", StepStatus::kDiverged)
      .value("FAILED", StepStatus::kFailed);

  py::class_<PyStepReport>(m, "StepReport", "What one step did (sim/simulation.h StepReport)")
      .def_property_readonly("status", [](const PyStepReport& r) { return Classify(r.report); })
      .def_property_readonly("message", [](const PyStepReport& r) { return r.report.status; })
      .def_property_readonly("converged", [](const PyStepReport& r) { return r.report.converged; })
      .def_property_readonly("step", [](const PyStepReport& r) { return r.report.step; })
      .def_property_readonly("time", [](const PyStepReport& r) { return r.report.time; })
      .def_property_readonly("time_step", [](const PyStepReport& r) { return r.report.time_step; })
      .def_property_readonly("iterations",
                             [](const PyStepReport& r) { return r.report.iterations; })
      .def_property_readonly("evaluations",
                             [](const PyStepReport& r) { return r.report.evaluations; })
      .def_property_readonly(
          "residual", [](const PyStepReport& r) { return r.report.residual; },
          "the stopping measure at the step's end [m/s]")
      .def_property_readonly("wall_seconds",
                             [](const PyStepReport& r) { return r.report.wall_seconds; })
      .def_property_readonly("substeps", [](const PyStepReport& r) { return r.report.substeps; })
      .def_property_readonly("retry_reason",
                             [](const PyStepReport& r) { return r.report.retry_reason; })
      .def_property_readonly("energy_growth",
                             [](const PyStepReport& r) { return r.report.energy_growth; })
      .def_property_readonly(
          "energies", [](const PyStepReport& r) { return Energies(r.report.energies); },
          "{'kinetic', 'potential', 'total'} [J] at the step's end")
      .def_property_readonly(
          "diagnostics",
          [](const PyStepReport& r) {
            py::dict d;
            for (size_t i = 0; i < r.diagnostic_names.size() && i < r.report.diagnostics.size();
                 ++i) {
              d[py::str(r.diagnostic_names[i])] = r.report.diagnostics[i];
            }
            return d;
          },
          "the step filters' columns (contact: min_distance, active_contacts, ...)")
      .def("__repr__", [](const PyStepReport& r) {
        return "<ipstep.StepReport step " + std::to_string(r.report.step) + ": " + r.report.status +
               ", " + std::to_string(r.report.iterations) + " iterations>";
      });

  py::class_<RunSummary>(m, "RunSummary", "How a run went (sim/run_trajectory.h RunSummary)")
      .def_readonly("steps_planned", &RunSummary::steps_planned)
      .def_readonly("steps_done", &RunSummary::steps_done)
      .def_readonly("failed", &RunSummary::failed)
      .def_readonly("substepped", &RunSummary::substepped)
      .def_readonly("adaptive", &RunSummary::adaptive)
      .def_readonly("rejected", &RunSummary::rejected,
                    "an adaptive run's rejected attempts (error over budget or a failed solve)")
      .def_readonly("over_budget", &RunSummary::over_budget,
                    "an adaptive run's steps taken at min_time_step over their error budget")
      .def_readonly("contact_kappa", &RunSummary::contact_kappa,
                    "the barrier stiffness at the end (0 without contact)")
      .def_readonly("contact_kappa_adaptive", &RunSummary::contact_kappa_adaptive,
                    "whether it adapted (it then follows the step size)")
      .def_readonly("iterations", &RunSummary::iterations)
      .def_readonly("evaluations", &RunSummary::evaluations)
      .def_readonly("max_step_iterations", &RunSummary::max_step_iterations)
      .def_readonly("worst_residual", &RunSummary::worst_residual)
      .def_readonly("wall_seconds", &RunSummary::wall_seconds)
      .def_readonly("step_seconds", &RunSummary::step_seconds)
      .def_readonly("max_energy_drift", &RunSummary::max_energy_drift,
                    "max |E - E0| / E_s over the steps, in energy scales (sim/divergence.h)")
      .def_readonly("energy_scale", &RunSummary::energy_scale)
      .def_readonly("first_failed_step", &RunSummary::first_failed_step)
      .def_readonly("first_failure", &RunSummary::first_failure)
      .def_readonly("diverged_at", &RunSummary::diverged_at)
      .def_readonly("divergence", &RunSummary::divergence)
      .def_readonly("message", &RunSummary::message)
      .def_property_readonly(
          "termination", [](const RunSummary& s) { return RunTerminationName(s.termination); },
          "completed | step failed | diverged | timeout | step limit | interrupted")
      .def_property_readonly("initial_energies",
                             [](const RunSummary& s) { return Energies(s.initial_energies); })
      .def_property_readonly("final_energies",
                             [](const RunSummary& s) { return Energies(s.final_energies); })
      .def_property_readonly("iterations_per_step", &RunSummary::iterations_per_step)
      .def_property_readonly("ms_per_step", &RunSummary::ms_per_step)
      .def_property_readonly("diverged", &RunSummary::diverged)
      .def("__repr__", [](const RunSummary& s) { return "<ipstep.RunSummary " + s.message + ">"; });

  py::class_<PySimulation>(m, "Simulation",
                           "A scene with an integrator and an optimiser, built once; step() and "
                           "run() advance it (docs/python.md).")
      .def(py::init([](const py::object& scene, const py::object& integrator,
                       const py::object& optimizer, const py::object& dt, py::kwargs keywords) {
             if (!dt.is_none()) {
               if (keywords.contains("time_step")) {
                 throw py::value_error("Simulation: give dt or time_step, not both");
               }
               keywords["time_step"] = dt;
             }
             keywords["integrator"] = integrator;
             keywords["optimizer"] = optimizer;
             const std::shared_ptr<const Scene> loaded = SceneArgument(scene, &keywords);
             std::optional<AdaptiveOptions> adaptive = AdaptiveFrom(&keywords);
             if (adaptive && keywords.contains("max_substeps") &&
                 !keywords["max_substeps"].is_none()) {
               throw py::value_error(
                   "Simulation: an adaptive simulation retries failed steps smaller itself; "
                   "give no max_substeps");
             }
             SimulationOptions options = SimulationOptionsFrom(keywords);
             if (adaptive) {
               const double dt = options.time_step > 0.0 ? options.time_step : loaded->time_step;
               adaptive->t_end = options.t_end > 0.0  ? options.t_end
                                 : options.steps >= 0 ? dt * options.steps
                                                      : dt * loaded->steps;
               adaptive->initial_time_step = dt;
               // The steps follow from the error: t_end need not be a whole
               // number of dt (as ipstep --adaptive --t_end).
               options.t_end = 0.0;
               const bool tolerance_given =
                   keywords.contains("tolerance") && !keywords["tolerance"].is_none();
               ConfigureAdaptiveSimulation(*adaptive, tolerance_given, &options);
             }
             return std::make_unique<PySimulation>(loaded, options, std::move(adaptive));
           }),
           py::arg("scene"), py::arg("integrator") = py::none(), py::arg("optimizer") = py::none(),
           py::arg("dt") = py::none(),
           "Simulation(scene, integrator='backward_euler', optimizer='newton', dt=None (the "
           "scene's), **options): scene is a Scene or what load_scene takes; options are the "
           "library's (ipstep.options()). adaptive=True with error_tolerance=E [m] (and "
           "min_time_step, max_time_step, safety, max_growth, max_shrink, filter_stiff_modes): "
           "run() takes "
           "error-controlled steps to the end time (t_end, steps x dt or the scene's), dt the "
           "first, as ipstep --adaptive. Bad input raises ValueError.")
      .def("step", &PySimulation::Step,
           "One step of dt (retried as substeps up to max_substeps). A failed step is a status "
           "(StepReport.status), not an exception. The GIL is released while it runs.")
      .def("run", &PySimulation::Run, py::arg("steps") = py::none(),
           py::arg("on_step") = py::none(),
           "run(steps=None (the rest), on_step=None, stop_on_failure=False, "
           "stop_on_divergence=True, max_wall_seconds=None) -> RunSummary: the library's run "
           "loop (sim/run_trajectory.h). on_step(report) is called after every step. Ctrl-C "
           "stops after the step in progress and raises KeyboardInterrupt.")
      .def_property_readonly(
          "positions",
          [](const PySimulation& s) { return Nodes(s.sim().state().x, s.sim().state().dimension); },
          "positions [m], (nodes, dimension): a copy")
      .def_property_readonly(
          "velocities",
          [](const PySimulation& s) { return Nodes(s.sim().state().v, s.sim().state().dimension); },
          "velocities [m/s], (nodes, dimension): a copy")
      .def_property_readonly("time", [](const PySimulation& s) { return s.sim().state().time; })
      .def_property_readonly("dt", [](const PySimulation& s) { return s.sim().time_step(); })
      .def_property_readonly(
          "steps", [](const PySimulation& s) { return s.sim().steps(); },
          "the steps planned (steps, t_end or the scene's)")
      .def_property_readonly("steps_taken",
                             [](const PySimulation& s) { return s.sim().steps_taken(); })
      .def_property_readonly("adaptive", &PySimulation::adaptive,
                             "run() takes error-controlled steps (Simulation(adaptive=True))")
      .def_property_readonly("integrator",
                             [](const PySimulation& s) { return s.sim().integrator().name(); })
      .def_property_readonly("effects",
                             [](const PySimulation& s) { return s.sim().effect_summaries(); })
      .def_property_readonly("diagnostic_names",
                             [](const PySimulation& s) { return s.sim().DiagnosticNames(); })
      .def(
          "energies", [](const PySimulation& s) { return Energies(s.sim().Energies()); },
          "{'kinetic', 'potential', 'total'} [J] now");
}

}  // namespace ipstep::python
