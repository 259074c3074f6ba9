#include "core/option_table.h"

#include <cmath>

#include "core/input_limits.h"

namespace ipstep {

const char* OptionTypeName(OptionType type) {
  switch (type) {
    case OptionType::kBool:
      return "bool";
    case OptionType::kInt:
      return "int";
    case OptionType::kDouble:
      return "float";
    case OptionType::kString:
      return "str";
  }
  return "?";
}

std::string OptionValueText(const OptionValue& value) {
  if (const bool* b = std::get_if<bool>(&value)) return *b ? "true" : "false";
  if (const long long* i = std::get_if<long long>(&value)) return std::to_string(*i);
  if (const double* d = std::get_if<double>(&value)) return limits::FormatLimit(*d);
  return std::get<std::string>(value);
}

OptionValue CheckOptionValue(const std::string& field, OptionType type, bool has_range, double min,
                             double max, bool min_open, const std::string& unit,
                             const std::string& default_meaning, const OptionValue& value) {
  // `field` is a table's (tests/apps/flag_names_test.cc counts the tables'
  // fields among the names the library reports).
  const auto fail = [&](const std::string& what) {
    throw InputError("options: " + field + ": " + what + ", got " +
                     ClipInput(OptionValueText(value)));
  };
  OptionValue checked = value;
  switch (type) {
    case OptionType::kBool:
      if (!std::holds_alternative<bool>(value)) fail("must be true or false");
      return checked;
    case OptionType::kString:
      if (!std::holds_alternative<std::string>(value)) fail("must be a string");
      return checked;
    case OptionType::kInt:
      if (!std::holds_alternative<long long>(value)) fail("must be an integer");
      break;
    case OptionType::kDouble:
      if (const long long* i = std::get_if<long long>(&value)) {
        checked = static_cast<double>(*i);
      } else if (!std::holds_alternative<double>(value)) {
        fail("must be a number");
      }
      if (!std::isfinite(std::get<double>(checked))) fail("must be a finite number");
      break;
  }
  if (!has_range) return checked;
  const double x = type == OptionType::kInt ? static_cast<double>(std::get<long long>(checked))
                                            : std::get<double>(checked);
  if (x < min || x > max || (min_open && x == min)) {
    fail("must be in " + limits::RangeText(min, max, unit, min_open) +
         (default_meaning.empty() ? "" : " (omit it for " + default_meaning + ")"));
  }
  return checked;
}

void CheckOptionRange(const std::string& field, bool min_open, double min, double max,
                      const std::string& unit, const OptionValue& default_value,
                      const std::string& default_meaning, const OptionValue& value) {
  if (!default_meaning.empty() && value == default_value) return;  // the sentinel
  const double x = std::holds_alternative<long long>(value)
                       ? static_cast<double>(std::get<long long>(value))
                       : std::get<double>(value);
  if (x >= min && x <= max && !(min_open && x == min)) return;
  // The field is a table's row's (tests/apps/flag_names_test.cc counts the
  // tables' fields among the names the library reports).
  const std::string where = "options";
  throw InputError(where, field,
                   "must be in " + limits::RangeText(min, max, unit, min_open) +
                       (default_meaning.empty() ? ""
                                                : " (" + OptionValueText(default_value) + ": " +
                                                      default_meaning + ")") +
                       ", got " + OptionValueText(value));
}

}  // namespace ipstep
