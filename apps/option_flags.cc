#include "apps/option_flags.h"

#include <cmath>
#include <map>
#include <stdexcept>
#include <variant>

#include "apps/command_line.h"
#include "core/input_limits.h"
#include "core/option_table.h"
#include "problems/scene_load_option_table.h"
#include "sim/simulation_option_table.h"

namespace ipstep {
namespace {

// What a flag needs of its row, whatever the struct.
struct FlagRow {
  OptionType type = OptionType::kDouble;
  OptionValue default_value;
  std::string default_meaning;
  bool has_range = false;
  double min = 0.0, max = 0.0;
  bool min_open = false;
  std::string unit, doc;
  std::string help, program_help;  // FlagHelp's and ProgramFlagHelp's texts
};

std::string Number(OptionType type, double x) {
  return type == OptionType::kInt ? std::to_string(static_cast<long long>(x))
                                  : limits::FormatLimit(x);
}

template <class Options>
void AddRows(const OptionTable<Options>& table, std::map<std::string, FlagRow>* rows) {
  for (const OptionRow<Options>& r : table) {
    if (r.flag.empty()) continue;
    FlagRow row{r.type,
                r.default_value,
                r.default_meaning,
                r.has_range,
                r.min,
                r.max,
                r.min_open,
                r.unit,
                r.doc,
                "",
                ""};
    row.program_help = r.doc;
    if (r.has_range) {
      row.program_help += std::string(", in ") + (r.min_open ? "(" : "[") + Number(r.type, r.min) +
                          ", " + Number(r.type, r.max) + "]" + (r.unit.empty() ? "" : " " + r.unit);
    }
    row.help =
        row.program_help + (r.default_meaning.empty() ? "" : "; default: " + r.default_meaning);
    if (!rows->emplace(r.flag, std::move(row)).second) {
      throw std::logic_error("two option rows have the flag --" + r.flag);
    }
  }
}

// The rows by flag; std::map keeps each text where it is for the program's life.
const std::map<std::string, FlagRow>& Rows() {
  static const std::map<std::string, FlagRow> rows = [] {
    std::map<std::string, FlagRow> r;
    AddRows(SimulationOptionTable(), &r);
    AddRows(SceneLoadOptionTable(), &r);
    AddRows(RunOptionTable(), &r);
    AddRows(AdaptiveOptionTable(), &r);
    return r;
  }();
  return rows;
}

const FlagRow& RowOf(const char* flag) {
  const auto found = Rows().find(flag);
  if (found == Rows().end()) throw std::logic_error(std::string("no option row has --") + flag);
  return found->second;
}

}  // namespace

const char* FlagHelp(const char* flag) { return RowOf(flag).help.c_str(); }

const char* ProgramFlagHelp(const char* flag) { return RowOf(flag).program_help.c_str(); }

template <>
bool FlagDefault<bool>(const char* flag) {
  return std::get<bool>(RowOf(flag).default_value);
}
template <>
int FlagDefault<int>(const char* flag) {
  return static_cast<int>(std::get<long long>(RowOf(flag).default_value));
}
template <>
double FlagDefault<double>(const char* flag) {
  return std::get<double>(RowOf(flag).default_value);
}
template <>
const char* FlagDefault<const char*>(const char* flag) {
  return std::get<std::string>(RowOf(flag).default_value).c_str();
}

double FlagInRowRange(const char* flag, double value) {
  const FlagRow& row = RowOf(flag);
  if (!row.has_range) throw std::logic_error(std::string("--") + flag + " has no range");
  return CheckFlagRange(flag, value, row.min, row.max, row.unit, row.default_meaning, row.min_open);
}

int FlagInRowRange(const char* flag, int value) {
  const FlagRow& row = RowOf(flag);
  if (!row.has_range) throw std::logic_error(std::string("--") + flag + " has no range");
  return CheckFlagRange(flag, value, static_cast<int>(row.min), static_cast<int>(row.max),
                        row.default_meaning);
}

}  // namespace ipstep
