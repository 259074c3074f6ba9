// The library's option tables (core/option_table.h: solver/, integrators/,
// problems/, sim/) against the programs' flags (apps/solver_flags.cc,
// apps/contact_flags.cc, apps/ipstep_program.cc): every shared flag has a row,
// every row's flag exists with the row's default, so the two lists cannot
// drift apart. The deliberate differences are listed here with their reason.
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include <gflags/gflags.h>
#include <gtest/gtest.h>

#include "apps/contact_flags.h"
#include "apps/programs.h"
#include "apps/solver_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "integrators/integrator_option_table.h"
#include "problems/scene_load_option_table.h"
#include "sim/simulation_option_table.h"
#include "solver/optimizer_option_table.h"

namespace ipstep {
namespace {

// The flags are defined in objects of a static library: these references
// link them in (solver_flags.cc, contact_flags.cc, ipstep_program.cc).
const void* volatile kLinkedFlags[] = {
    reinterpret_cast<const void*>(&SimulationOptionsFromFlags),
    reinterpret_cast<const void*>(&AddContactFlagOverrides),
    reinterpret_cast<const void*>(static_cast<int (*)(int, char**)>(&RunIpstep))};

struct FlaggedRow {
  std::string name, flag;
  OptionType type;
  OptionValue default_value;
};

std::vector<FlaggedRow> AllRows() {
  std::vector<FlaggedRow> rows;
  for (const auto& r : SimulationOptionTable())
    rows.push_back({r.name, r.flag, r.type, r.default_value});
  for (const auto& r : SceneLoadOptionTable())
    rows.push_back({r.name, r.flag, r.type, r.default_value});
  for (const auto& r : RunOptionTable()) rows.push_back({r.name, r.flag, r.type, r.default_value});
  for (const auto& r : AdaptiveOptionTable())
    rows.push_back({r.name, r.flag, r.type, r.default_value});
  return rows;
}

// Flags whose program default is not the struct's, and why.
const std::map<std::string, std::string>& ProgramDefaults() {
  static const std::map<std::string, std::string> defaults = {
      // ipstep retries a failed step as substeps; a library Simulation does
      // not unless asked (SimulationOptions::max_substeps = 1).
      {"max_substeps", "16"},
      // --adaptive asks for 1 mm unless told; AdaptiveOptions has no default
      // tolerance (a library or Python adaptive run must give one).
      {"error_tolerance", "0.001"},
  };
  return defaults;
}

// Flags of the shared files that are not options of a struct.
const std::set<std::string>& NotOptions() {
  static const std::set<std::string> flags = {
      "scene",  // the scene itself (LoadScene's name or path), not an option
  };
  return flags;
}

bool SameDefault(const FlaggedRow& row, const std::string& flag_default) {
  switch (row.type) {
    case OptionType::kBool:
      return flag_default == (std::get<bool>(row.default_value) ? "true" : "false");
    case OptionType::kInt:
      return std::stoll(flag_default) == std::get<long long>(row.default_value);
    case OptionType::kDouble:
      return std::strtod(flag_default.c_str(), nullptr) == std::get<double>(row.default_value);
    case OptionType::kString:
      return flag_default == std::get<std::string>(row.default_value);
  }
  return false;
}

TEST(OptionTable, EveryRowsFlagExistsWithTheRowsDefault) {
  for (const void* linked : kLinkedFlags) ASSERT_NE(linked, nullptr);
  int flagged = 0;
  for (const FlaggedRow& row : AllRows()) {
    if (row.flag.empty()) continue;
    ++flagged;
    gflags::CommandLineFlagInfo info;
    ASSERT_TRUE(gflags::GetCommandLineFlagInfo(row.flag.c_str(), &info)) << row.flag;
    const auto program = ProgramDefaults().find(row.flag);
    if (program != ProgramDefaults().end()) {
      EXPECT_EQ(info.default_value, program->second) << row.flag;
      EXPECT_FALSE(SameDefault(row, info.default_value)) << row.flag << ": no longer differs";
    } else {
      EXPECT_TRUE(SameDefault(row, info.default_value))
          << row.name << ": table " << OptionValueText(row.default_value) << ", --" << row.flag
          << " " << info.default_value;
    }
    const std::map<OptionType, std::string> gflags_type = {{OptionType::kBool, "bool"},
                                                           {OptionType::kInt, "int32"},
                                                           {OptionType::kDouble, "double"},
                                                           {OptionType::kString, "string"}};
    EXPECT_EQ(info.type, gflags_type.at(row.type)) << row.flag;
  }
  EXPECT_GE(flagged, 28);
}

TEST(OptionTable, EveryFlagOfTheSharedFilesHasARow) {
  std::set<std::string> in_table;
  for (const FlaggedRow& row : AllRows()) in_table.insert(row.flag);
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  int shared = 0;
  for (const auto& info : flags) {
    const std::string& file = info.filename;
    const bool is_shared = file.find("apps/solver_flags.cc") != std::string::npos ||
                           file.find("apps/contact_flags.cc") != std::string::npos;
    if (!is_shared && info.name != "max_substeps") continue;
    ++shared;
    if (NotOptions().count(info.name) > 0) continue;
    EXPECT_EQ(in_table.count(info.name), 1u) << "--" << info.name << " (" << file << ") has no row";
  }
  EXPECT_GE(shared, 28);
}

// The help text of a row's flag (what --help prints) is made from the row:
// its doc, its range, and what the unset flag means (not where the program's
// default differs: gflags prints that default), so neither can restate the
// other.
template <class Options>
void ExpectHelpIsTheRows(const OptionTable<Options>& table, int* compared) {
  for (const OptionRow<Options>& row : table) {
    if (row.flag.empty()) continue;
    gflags::CommandLineFlagInfo info;
    ASSERT_TRUE(gflags::GetCommandLineFlagInfo(row.flag.c_str(), &info)) << row.flag;
    const auto number = [&row](double x) {
      return row.type == OptionType::kInt ? std::to_string(static_cast<long long>(x))
                                          : limits::FormatLimit(x);
    };
    std::string expected = row.doc;
    if (row.has_range) {
      expected += std::string(", in ") + (row.min_open ? "(" : "[") + number(row.min) + ", " +
                  number(row.max) + "]" + (row.unit.empty() ? "" : " " + row.unit);
    }
    if (!row.default_meaning.empty() && ProgramDefaults().count(row.flag) == 0) {
      expected += "; default: " + row.default_meaning;
    }
    EXPECT_EQ(info.description, expected) << "--" << row.flag;
    ++*compared;
  }
}

TEST(OptionTable, EveryFlagsHelpIsItsRow) {
  int compared = 0;
  ExpectHelpIsTheRows(SimulationOptionTable(), &compared);
  ExpectHelpIsTheRows(SceneLoadOptionTable(), &compared);
  ExpectHelpIsTheRows(RunOptionTable(), &compared);
  ExpectHelpIsTheRows(AdaptiveOptionTable(), &compared);
  EXPECT_GE(compared, 32);
}

TEST(OptionTable, NamesAreUniqueAndEveryRowCanBeSet) {
  std::set<std::string> names;
  for (const FlaggedRow& row : AllRows()) EXPECT_TRUE(names.insert(row.name).second) << row.name;
  // Setting each row's own default works where the default is in range, and
  // is an error naming the field where it is a sentinel (as an explicit
  // --dt=0 is).
  for (const auto& row : SimulationOptionTable()) {
    SimulationOptions options;
    const bool sentinel =
        row.has_range && row.type != OptionType::kString && row.type != OptionType::kBool && [&] {
          const double x = row.type == OptionType::kInt
                               ? static_cast<double>(std::get<long long>(row.default_value))
                               : std::get<double>(row.default_value);
          return x < row.min || x > row.max || (row.min_open && x == row.min);
        }();
    if (sentinel) {
      try {
        SetOption(row, row.default_value, &options);
        ADD_FAILURE() << row.name << ": the sentinel was accepted";
      } catch (const InputError& error) {
        EXPECT_EQ(std::string(error.what()).rfind("options: " + row.field + ": must be in", 0), 0u)
            << error.what();
      }
    } else {
      EXPECT_NO_THROW(SetOption(row, row.default_value, &options)) << row.name;
    }
  }
}

TEST(OptionTable, ValuesAreCheckedAndStored) {
  SimulationOptions o;
  SetOption(*FindOption(SimulationOptionTable(), "optimizer"), OptionValue(std::string("lbfgs")),
            &o);
  EXPECT_EQ(o.optimizer.optimizer, Optimizer::kLbfgs);
  SetOption(*FindOption(SimulationOptionTable(), "lbfgs_rank"), OptionValue(7LL), &o);
  EXPECT_EQ(o.optimizer.lbfgs_rank, 7);
  SetOption(*FindOption(SimulationOptionTable(), "time_step"), OptionValue(2LL), &o);  // int: float
  EXPECT_EQ(o.time_step, 2.0);
  SetOption(*FindOption(SimulationOptionTable(), "contact_kappa"), OptionValue(1e5), &o);
  EXPECT_EQ(o.effect_overrides.at("contact").at("kappa").get<double>(), 1e5);
  EXPECT_THROW(SetOption(*FindOption(SimulationOptionTable(), "lbfgs_rank"), OptionValue(0LL), &o),
               InputError);
  EXPECT_THROW(SetOption(*FindOption(SimulationOptionTable(), "tolerance"),
                         OptionValue(std::string("x")), &o),
               InputError);
  try {
    SetOption(*FindOption(SimulationOptionTable(), "optimizer"), OptionValue(std::string("newtn")),
              &o);
    FAIL();
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()).rfind("options: OptimizerOptions.optimizer", 0), 0u);
  }
  // An option of another optimiser family is an error, as its flag is.
  SimulationOptions newton;
  try {
    CheckOptionsApply(newton, {"tolerance", "lbfgs_rank"});
    FAIL();
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "options: OptimizerOptions.lbfgs_rank: applies to lbfgs, bfgs, ncg and "
              "gradient_descent, not to optimizer=newton");
  }
  EXPECT_NO_THROW(CheckOptionsApply(o, {"lbfgs_rank"}));
}

// The library validates a struct's ranged options by its table's rows
// (CheckOptionRanges): each ranged optimizer option past its row's maximum is
// an error naming the row's field, its maximum and its sentinel default are not.
TEST(OptionTable, TheLibrarysRangeChecksAreTheRows) {
  int checked = 0;
  for (const OptionRow<OptimizerOptions>& row : OptimizerOptionTable()) {
    if (!row.has_range || !row.get) continue;
    ++checked;
    const auto value = [&row](double x) {
      return row.type == OptionType::kInt ? OptionValue(static_cast<long long>(x)) : OptionValue(x);
    };
    OptimizerOptions options;
    row.set(value(row.max * 2.0), &options);
    try {
      ValidateOptimizerOptions(options);
      ADD_FAILURE() << row.name << " above its maximum was accepted";
    } catch (const InputError& error) {
      EXPECT_EQ(error.key(), row.field) << error.what();
      EXPECT_NE(error.detail().find("must be in"), std::string::npos) << error.what();
    }
    row.set(value(row.max), &options);
    EXPECT_NO_THROW(ValidateOptimizerOptions(options)) << row.name;
    row.set(row.default_value, &options);
    EXPECT_NO_THROW(ValidateOptimizerOptions(options)) << row.name;
  }
  EXPECT_EQ(checked, 5);  // max_iterations, time_limit, num_threads, radius, lbfgs_rank
}

}  // namespace
}  // namespace ipstep
