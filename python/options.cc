#include <pybind11/stl.h>

#include "core/input_limits.h"
#include "core/near_miss.h"
#include "problems/scene_load_option_table.h"
#include "python/bindings.h"
#include "sim/simulation_option_table.h"

namespace ipstep::python {
namespace {

template <class Options>
std::vector<std::string> Names(const OptionTable<Options>& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.push_back(row.name);
  return names;
}

// "unknown option 'tolerence' (did you mean tolerance?)"
[[noreturn]] void Unknown(const std::string& where, const std::string& name,
                          const std::vector<std::string>& names) {
  const std::string near = NearMiss(name, names);
  throw py::value_error(where + ": unknown option '" + ClipInput(name) + "'" +
                        (near.empty() ? "" : " (did you mean " + near + "?)") +
                        "; ipstep.options() lists them");
}

template <class Options>
py::list Rows(const OptionTable<Options>& table, const char* owner) {
  py::list rows;
  for (const auto& row : table) {
    py::dict d;
    d["name"] = row.name;
    d["field"] = row.field;
    d["flag"] = row.flag.empty() ? py::object(py::none()) : py::object(py::str("--" + row.flag));
    d["type"] = OptionTypeName(row.type);
    d["default"] = std::visit([](const auto& v) { return py::cast(v); }, row.default_value);
    d["default_meaning"] = row.default_meaning;
    d["range"] =
        row.has_range
            ? py::object(py::str(limits::RangeText(row.min, row.max, row.unit, row.min_open)))
            : py::object(py::none());
    d["unit"] = row.unit;
    d["doc"] = row.doc;
    d["where"] = owner;
    rows.append(d);
  }
  return rows;
}

}  // namespace

OptionValue ToOptionValue(const std::string& field, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<long long>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  // numpy scalars and other numbers
  if (py::hasattr(value, "__index__"))
    return py::int_(py::reinterpret_borrow<py::object>(value)).cast<long long>();
  if (py::hasattr(value, "__float__"))
    return py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
  throw InputError("options: " + field + ": must be a bool, int, float or str, got " +
                   ClipInput(py::repr(value).cast<std::string>()));
}

SimulationOptions SimulationOptionsFrom(const py::dict& keywords) {
  SimulationOptions options;
  options.effects = &Effects();
  const auto& table = SimulationOptionTable();
  std::vector<std::string> given;
  // The optimiser first: options that depend on it are checked against it.
  for (const char* first : {"integrator", "optimizer"}) {
    if (keywords.contains(first) && !keywords[first].is_none()) {
      SetOption(*FindOption(table, first), ToOptionValue(first, keywords[first]), &options);
    }
  }
  for (const auto& item : keywords) {
    const std::string name = item.first.cast<std::string>();
    const auto* row = FindOption(table, name);
    if (row == nullptr) {
      std::vector<std::string> names = Names(table);
      names.push_back("dt");
      Unknown("Simulation", name, names);
    }
    if (item.second.is_none()) continue;  // None: the default
    if (name != "integrator" && name != "optimizer") {
      SetOption(*row, ToOptionValue(row->field, item.second), &options);
    }
    given.push_back(name);
  }
  CheckOptionsApply(options, given);
  return options;
}

RunOptions RunOptionsFrom(const py::dict& keywords) {
  RunOptions options;
  for (const auto& item : keywords) {
    const std::string name = item.first.cast<std::string>();
    const auto* row = FindOption(RunOptionTable(), name);
    if (row == nullptr) Unknown("Simulation.run", name, Names(RunOptionTable()));
    if (item.second.is_none()) continue;
    SetOption(*row, ToOptionValue(row->field, item.second), &options);
  }
  return options;
}

void BindOptions(py::module_& m) {
  m.def(
      "options",
      [] {
        py::list rows = Rows(SimulationOptionTable(), "Simulation");
        for (const auto& row : Rows(SceneLoadOptionTable(), "load_scene")) rows.append(row);
        for (const auto& row : Rows(RunOptionTable(), "Simulation.run")) rows.append(row);
        return rows;
      },
      "Every keyword option (the library's option tables): name, field, the programs' flag, "
      "type, default, what the default means, range, unit, doc, and which call takes it.");
}

}  // namespace ipstep::python
