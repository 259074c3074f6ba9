#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "bench/bench_runner.h"
#include "io/comparison_csv.h"
#include "io/csv_fields.h"
#include "io/output_file.h"
#include "python/bindings.h"
#include "python/interrupt.h"
#include "sim/comparison.h"

namespace ipstep::python {
namespace {

// A CSV row as a record with the header's names: integers and numbers as
// such, an empty number as NaN, text as str.
py::dict Record(const std::vector<std::string>& columns, const std::string& line,
                const std::set<std::string>& text_columns,
                const std::set<std::string>& int_columns) {
  const std::vector<std::string> fields = CsvFields(line);
  py::dict record;
  for (size_t i = 0; i < columns.size() && i < fields.size(); ++i) {
    const std::string& f = fields[i];
    if (text_columns.count(columns[i]) > 0) {
      record[py::str(columns[i])] = f;
      continue;
    }
    if (f.empty()) {
      record[py::str(columns[i])] = std::nan("");
      continue;
    }
    size_t used = 0;
    try {
      if (int_columns.count(columns[i]) > 0) {
        const long long n = std::stoll(f, &used);
        if (used == f.size()) {
          record[py::str(columns[i])] = n;
          continue;
        }
      }
      const double x = std::stod(f, &used);
      if (used == f.size()) {
        record[py::str(columns[i])] = x;
        continue;
      }
    } catch (const std::exception&) {
    }
    record[py::str(columns[i])] = f;
  }
  return record;
}

std::vector<std::string> Strings(const py::object& list, const std::vector<std::string>& fallback) {
  if (list.is_none()) return fallback;
  if (py::isinstance<py::str>(list)) return {list.cast<std::string>()};
  return list.cast<std::vector<std::string>>();
}

py::list Compare(const py::object& scene_argument, const py::object& integrators,
                 const py::object& optimizers, const py::object& csv, double reference_tolerance,
                 const py::kwargs& keywords) {
  py::dict options_left = keywords;
  const std::shared_ptr<const Scene> scene = SceneArgument(scene_argument, &options_left);
  const SimulationOptions base = SimulationOptionsFrom(options_left);
  ComparisonOptions options = DefaultComparisonOptions();
  options.integrators = Strings(integrators, options.integrators);
  options.optimizers = Strings(optimizers, options.optimizers);
  options.reference_tolerance = reference_tolerance;
  PythonInterrupt interrupt;
  options.interrupt = interrupt.flag();
  options.after_step = [&interrupt](const StepReport&) { interrupt.Check(); };
  std::unique_ptr<OutputFile> file;
  if (!csv.is_none()) {
    file = std::make_unique<OutputFile>(py::str(csv).cast<std::string>(), "output: csv");
  }
  Comparison comparison;
  {
    py::gil_scoped_release release;
    comparison = RunComparison(*scene, base, options);
  }
  RaisePythonEnergyError();
  interrupt.RaiseIfInterrupted();
  py::list records;
  const std::set<std::string> text = {"scene", "integrator", "optimizer", "termination",
                                      "reference"};
  if (file) file->stream() << ComparisonCsvHeader() << '\n';
  for (const ComparisonRow& row : comparison.rows) {
    const std::string line = ComparisonCsvRow(scene->name, comparison, row);
    records.append(
        Record(ComparisonColumns(), line, text, {"steps", "failed_steps", "diverged_at"}));
    if (file) {
      file->stream() << line << '\n';
      file->EndRow();
    }
  }
  if (file) file->Close();
  return records;
}

py::list Bench(const py::object& scene_argument, const py::object& integrators,
               const py::object& optimizers, const py::object& dts, int steps, double t_end,
               double tolerance, int repeats, int warmup, bool errors,
               const std::string& reference_optimizer, double reference_tolerance, int grid_size,
               const py::object& csv) {
  // ipstep_bench's runs load their scene by name or path (bench/bench_runner.h).
  if (py::isinstance<py::dict>(scene_argument) || py::isinstance<Scene>(scene_argument)) {
    throw py::value_error("bench: scene must be a built-in scene name or a JSON file's path");
  }
  const std::string scene_name =
      py::module_::import("os").attr("fspath")(scene_argument).cast<std::string>();
  const Scene scene = *LoadSceneObject(scene_argument, SceneLoadOptions{});
  const std::vector<std::string> integrator_names =
      Strings(integrators, {"backward_euler", "newmark"});
  const std::vector<std::string> optimizer_names =
      Strings(optimizers, {"newton", "lbfgs", "projected_newton"});
  std::vector<double> dt_list =
      dts.is_none() ? std::vector<double>{scene.time_step} : dts.cast<std::vector<double>>();
  if (dt_list.empty()) throw py::value_error("bench: dts lists no time step");
  if (steps > 0 && t_end > 0.0) throw py::value_error("bench: give steps or t_end, not both");
  if (repeats < 1 || warmup < 0) throw py::value_error("bench: repeats >= 1, warmup >= 0");
  std::map<std::string, bench::OptimizerSpec> specs;
  for (const std::string& text : optimizer_names) {
    specs[text] = bench::ParseOptimizerSpec(text, tolerance);
  }
  std::vector<bench::RunConfig> configs;
  for (const std::string& integrator : integrator_names) {
    const bool explicit_method = integrator == "symplectic_euler";
    for (const double dt : dt_list) {
      for (const std::string& optimizer : optimizer_names) {
        bench::RunConfig c;
        c.id = static_cast<int>(configs.size());
        c.scene = scene_name;
        c.grid_size = grid_size;
        c.integrator = integrator;
        c.optimizer = explicit_method ? "none" : optimizer;
        c.dt = dt;
        c.steps = steps > 0 ? steps
                            : static_cast<int>(std::llround(
                                  (t_end > 0.0 ? t_end : scene.time_step * scene.steps) / dt));
        c.tolerance = tolerance;
        c.repeats = repeats;
        c.warmup = warmup;
        c.effects = &Effects();
        configs.push_back(c);
        if (explicit_method) break;
      }
    }
  }
  if (specs.count("none") == 0) specs["none"] = bench::ParseOptimizerSpec("none", tolerance);
  std::unique_ptr<OutputFile> file;
  if (!csv.is_none()) {
    file = std::make_unique<OutputFile>(py::str(csv).cast<std::string>(), "output: csv");
    file->stream() << bench::CsvHeader() << '\n';
  }
  const double dt_min = *std::min_element(dt_list.begin(), dt_list.end());
  bench::ReferenceCache references(reference_optimizer, reference_tolerance, &Effects());
  const std::string header = bench::CsvHeader();
  const std::vector<std::string> columns = CsvFields(header);
  const std::set<std::string> text = {"scene",     "integrator", "optimizer", "status",
                                      "reference", "shard",      "commit"};
  py::list records;
  PythonInterrupt interrupt;
  for (const bench::RunConfig& config : configs) {
    bench::RunRow row;
    row.config = config;
    row.shard = "0/1";
    row.configurations = static_cast<int>(configs.size());
    {
      py::gil_scoped_release release;
      for (int run = 0; run < config.warmup + config.repeats; ++run) {
        bench::OptimizerSpec spec = specs.at(config.optimizer);
        spec.options.tolerance = config.tolerance;
        row.result = bench::RunConfiguration(config, spec);
        const bool complete = row.result.steps_done == config.steps;
        if (run >= config.warmup || !complete) row.wall.push_back(row.result.loop_seconds);
        if (!complete) break;
      }
      row.position_error = row.reference_error = row.reference_dt = std::nan("");
      if (errors && row.result.steps_done == config.steps) {
        const ReferenceSolution& ref = references.Get(
            config.scene, config.grid_size, config.integrator, dt_min, config.dt * config.steps);
        row.reference = ref.exact ? "exact" : ref.description;
        row.reference_dt = ref.exact ? std::nan("") : ref.dt;
        row.reference_error = ref.error;
        row.position_error =
            MaxNodeDistance(row.result.final_x, ref.x, row.result.free_nodes, row.result.dimension);
      }
      interrupt.Check();
    }
    RaisePythonEnergyError();
    interrupt.RaiseIfInterrupted();
    const std::string line = bench::CsvRow(row);
    records.append(Record(columns, line, text,
                          {"id", "grid_size", "nodes", "free_dofs", "steps", "repeats", "warmup",
                           "max_step_iterations", "failed_steps", "steps_done", "configurations"}));
    if (file) {
      file->stream() << line << '\n';
      file->Flush();
    }
  }
  if (file) file->Close();
  return records;
}

}  // namespace

void BindStudies(py::module_& m) {
  m.def("compare", &Compare, py::arg("scene"), py::arg("integrators") = py::none(),
        py::arg("optimizers") = py::none(), py::arg("csv") = py::none(),
        py::arg("reference_tolerance") = 1e-7,
        "compare(scene, integrators=None, optimizers=None, csv=None, **options) -> list of dict: "
        "what ipstep_compare prints (sim/comparison.h), one record per configuration with the "
        "columns of ipstep_compare --compare_output (io/comparison_csv.h); csv=PATH writes that "
        "file. Defaults: ipstep_compare's lists. options: as Simulation's.");
  m.def("bench", &Bench, py::arg("scene"), py::arg("integrators") = py::none(),
        py::arg("optimizers") = py::none(), py::arg("dts") = py::none(), py::arg("steps") = 0,
        py::arg("t_end") = 0.0, py::arg("tolerance") = 1e-6, py::arg("repeats") = 1,
        py::arg("warmup") = 0, py::arg("errors") = true,
        py::arg("reference_optimizer") = "projected_newton", py::arg("reference_tolerance") = 1e-8,
        py::arg("grid_size") = 0, py::arg("csv") = py::none(),
        "bench(scene, integrators, optimizers (ipstep_bench's specs, e.g. 'lbfgs+rank=5'), "
        "dts, steps=0, t_end=0 (steps or t_end / dt steps; neither: the scene's end time / dt), "
        "tolerance=1e-6, repeats=1, warmup=0, "
        "errors=True, ...) -> list of dict: ipstep_bench's rows (bench/bench_runner.h), the "
        "same columns as its CSV; csv=PATH writes that file.");
}

}  // namespace ipstep::python
