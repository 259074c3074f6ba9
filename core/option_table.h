// Option tables: one row per option of a library options struct
// (OptimizerOptions, IntegratorOptions, SimulationOptions, SceneLoadOptions,
// RunOptions), with its name, type, default, range, unit and meaning, and how
// to set it on the struct. Each table lives next to its struct
// (solver/optimizer_option_table.h, ...). Whatever sets options by name (the
// Python module, python/) goes through them, so no option is listed twice;
// tests/apps/option_table_test.cc compares them with the programs' flags.
//
// Setting a value checks its type and range and throws InputError naming the
// struct's field ("options: OptimizerOptions.lbfgs_rank: must be in [1, 1000]
// (omit it for the rank 20), got 0"), as the library's own checks do.
#pragma once

#include <functional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/input_error.h"

namespace ipstep {

enum class OptionType { kBool, kInt, kDouble, kString };
// "bool", "int", "float", "str" (the Python names).
const char* OptionTypeName(OptionType type);

using OptionValue = std::variant<bool, long long, double, std::string>;
// The value as text: true/false, 12, 1e-05 (shortest round trip), the string.
std::string OptionValueText(const OptionValue& value);

template <class Options>
struct OptionRow {
  std::string name;   // the option's name: the field's, unique over the tables ("tolerance")
  std::string field;  // as errors name it: "OptimizerOptions.tolerance"
  std::string flag;   // the programs' flag (without "--"); "" when they have none
  OptionType type = OptionType::kDouble;
  OptionValue default_value;    // the struct's default
  std::string default_meaning;  // what the default stands for ("the scene's time_step"); "" itself
  // Numbers: the accepted range, [min, max] ((min, max] with min_open);
  // without it the library's own validation decides.
  bool has_range = false;
  double min = 0.0;
  double max = 0.0;
  bool min_open = false;
  std::string unit;
  std::string doc;
  // Stores a value of `type` (already checked) in the struct; may throw
  // InputError (an unknown name of a choice).
  std::function<void(const OptionValue& value, Options* options)> set;
  // Reads the option's value from the struct, for the library's own range
  // check (CheckOptionRanges); set with `set` by BindField. Null: the row's
  // value is not a plain field (effect overrides).
  std::function<OptionValue(const Options& options)> get;
  // "" or why the option, given, does not apply to `options` ("applies to
  // newton, dogleg, gauss_newton and projected_newton, not to optimizer=lbfgs"),
  // with the options it names spelled after `prefix`: "" for the library's
  // and Python's names, "--" for the programs' flags ("not to
  // --optimizer=lbfgs").
  std::function<std::string(const Options& options, const std::string& prefix)> applies;
};

template <class Options>
using OptionTable = std::vector<OptionRow<Options>>;

// `value` checked against the row (type: an int is taken for a float; range)
// and converted to the row's type; throws InputError naming row.field.
OptionValue CheckOptionValue(const std::string& field, OptionType type, bool has_range, double min,
                             double max, bool min_open, const std::string& unit,
                             const std::string& default_meaning, const OptionValue& value);

// `value` (an option's current value in its struct) against its row's range:
// in range, or the struct's default when that is a sentinel (`default_meaning`
// says what it stands for: max_iterations 0, "the optimizer's default");
// otherwise throws InputError naming `field` ("must be in [1, 1000] (0: the
// rank 20), got -1"). Non-finite numbers are out of every range.
void CheckOptionRange(const std::string& field, bool min_open, double min, double max,
                      const std::string& unit, const OptionValue& default_value,
                      const std::string& default_meaning, const OptionValue& value);

// The library's validation of a struct's ranged options: every row with a
// range and a `get`, checked as CheckOptionRange does. The range, unit and
// sentinel meaning of an option are its row's, written once.
template <class Options>
void CheckOptionRanges(const OptionTable<Options>& table, const Options& options) {
  for (const OptionRow<Options>& row : table) {
    if (!row.has_range || !row.get) continue;
    CheckOptionRange(row.field, row.min_open, row.min, row.max, row.unit, row.default_value,
                     row.default_meaning, row.get(options));
  }
}

// Sets option `row` on `options` (checked as above).
template <class Options>
void SetOption(const OptionRow<Options>& row, const OptionValue& value, Options* options) {
  row.set(CheckOptionValue(row.field, row.type, row.has_range, row.min, row.max, row.min_open,
                           row.unit, row.default_meaning, value),
          options);
}

// The row named `name`, or null.
template <class Options>
const OptionRow<Options>* FindOption(const OptionTable<Options>& table, const std::string& name) {
  for (const OptionRow<Options>& row : table) {
    if (row.name == name) return &row;
  }
  return nullptr;
}

// The rows of a table over `Inner`, as rows over `Outer` that holds it in
// `member` (OptimizerOptions inside SimulationOptions::optimizer).
template <class Outer, class Inner>
OptionTable<Outer> LiftOptions(const OptionTable<Inner>& rows, Inner Outer::*member) {
  OptionTable<Outer> lifted;
  for (const OptionRow<Inner>& row : rows) {
    OptionRow<Outer> r;
    r.name = row.name;
    r.field = row.field;
    r.flag = row.flag;
    r.type = row.type;
    r.default_value = row.default_value;
    r.default_meaning = row.default_meaning;
    r.has_range = row.has_range;
    r.min = row.min;
    r.max = row.max;
    r.min_open = row.min_open;
    r.unit = row.unit;
    r.doc = row.doc;
    const auto set = row.set;
    r.set = [set, member](const OptionValue& value, Outer* outer) {
      set(value, &(outer->*member));
    };
    if (row.get) {
      const auto get = row.get;
      r.get = [get, member](const Outer& outer) { return get(outer.*member); };
    }
    if (row.applies) {
      const auto applies = row.applies;
      r.applies = [applies, member](const Outer& outer, const std::string& prefix) {
        return applies(outer.*member, prefix);
      };
    }
    lifted.push_back(std::move(r));
  }
  return lifted;
}

// Row makers for a plain field. `meaning`: what the default stands for ("").
template <class Options, class Field>
std::function<void(const OptionValue&, Options*)> SetField(Field Options::*member) {
  return [member](const OptionValue& value, Options* options) {
    if constexpr (std::is_same_v<Field, std::string>) {
      options->*member = std::get<std::string>(value);
    } else if constexpr (std::is_same_v<Field, bool>) {
      options->*member = std::get<bool>(value);
    } else if constexpr (std::is_integral_v<Field>) {
      options->*member = static_cast<Field>(std::get<long long>(value));
    } else {
      options->*member = std::get<double>(value);
    }
  };
}

template <class Options, class Field>
std::function<OptionValue(const Options&)> GetField(Field Options::*member) {
  return [member](const Options& options) -> OptionValue {
    if constexpr (std::is_same_v<Field, std::string> || std::is_same_v<Field, bool>) {
      return options.*member;
    } else if constexpr (std::is_integral_v<Field>) {
      return static_cast<long long>(options.*member);
    } else {
      return static_cast<double>(options.*member);
    }
  };
}

// The row reads and writes `member` (set and get).
template <class Options, class Field>
void BindField(Field Options::*member, OptionRow<Options>* row) {
  row->set = SetField(member);
  row->get = GetField(member);
}

template <class Options>
OptionRow<Options> MakeOptionRow(const std::string& name, const std::string& field,
                                 const std::string& flag, OptionType type,
                                 OptionValue default_value, const std::string& doc) {
  OptionRow<Options> row;
  row.name = name;
  row.field = field;
  row.flag = flag;
  row.type = type;
  row.default_value = std::move(default_value);
  row.doc = doc;
  return row;
}

// The row with a numeric range and what its default (outside it: a sentinel)
// stands for.
template <class Options>
OptionRow<Options> WithRange(OptionRow<Options> row, double min, double max,
                             const std::string& unit, const std::string& default_meaning = "",
                             bool min_open = false) {
  row.has_range = true;
  row.min = min;
  row.max = max;
  row.unit = unit;
  row.default_meaning = default_meaning;
  row.min_open = min_open;
  return row;
}

}  // namespace ipstep
