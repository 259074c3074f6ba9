// The table from the library's option names to the programs' flags
// (apps/flag_names.h): every name the library reports has a flag the programs
// define, or is left unmapped deliberately; every row is a name the library
// reports (or an output the programs name); messages are rewritten exactly.
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <gtest/gtest.h>

#include "apps/flag_names.h"
#include "apps/programs.h"
#include "core/input_error.h"
#include "problems/scene_load_option_table.h"
#include "sim/simulation_option_table.h"
#include "solver/optimizer_options.h"

namespace ipstep {
namespace {

namespace fs = std::filesystem;

// The library folders (tools/check_layers.py).
const char* const kLibraryFolders[] = {"core",     "mesh",    "problems", "solver", "integrators",
                                       "energies", "contact", "sim",      "io"};

// Skips spaces and newlines from `at`.
size_t SkipSpace(const std::string& text, size_t at) {
  while (at < text.size() && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  return at;
}

// The string literal starting at `at` (a '"'), without its quotes; moves `at`
// past it. Empty and `at` unchanged if there is none.
std::string Literal(const std::string& text, size_t* at) {
  if (*at >= text.size() || text[*at] != '"') return "";
  const size_t end = text.find('"', *at + 1);
  if (end == std::string::npos) return "";
  const std::string literal = text.substr(*at + 1, end - *at - 1);
  *at = end + 1;
  return literal;
}

// Every `InputError("options", "<name>"` of the library's sources, as
// "options: <name>" (the literal part of the name: up to a '=' or the end of
// the literal, e.g. "options: effect_overrides." for "effect_overrides." + effect).
std::set<std::string> ReportedOptionNames() {
  std::set<std::string> names;
  for (const char* folder : kLibraryFolders) {
    for (const auto& entry :
         fs::recursive_directory_iterator(fs::path(IPSTEP_SOURCE_DIR) / folder)) {
      const std::string extension = entry.path().extension().string();
      if (extension != ".h" && extension != ".cc") continue;
      std::ifstream in(entry.path());
      std::stringstream buffer;
      buffer << in.rdbuf();
      const std::string text = buffer.str();
      for (size_t at = text.find("InputError("); at != std::string::npos;
           at = text.find("InputError(", at + 1)) {
        size_t p = SkipSpace(text, at + 11);
        if (Literal(text, &p) != "options") continue;
        p = SkipSpace(text, p);
        if (p >= text.size() || text[p] != ',') continue;
        p = SkipSpace(text, p + 1);
        const std::string name = Literal(text, &p);
        EXPECT_FALSE(name.empty()) << entry.path() << ": an option name that is not a literal";
        names.insert("options: " + name.substr(0, name.find('=')));
      }
    }
  }
  // The option tables' fields (core/option_table.h reports bad values by them).
  for (const auto& row : SimulationOptionTable()) names.insert("options: " + row.field);
  for (const auto& row : SceneLoadOptionTable()) names.insert("options: " + row.field);
  for (const auto& row : RunOptionTable()) names.insert("options: " + row.field);
  for (const auto& row : AdaptiveOptionTable()) names.insert("options: " + row.field);
  return names;
}

bool Unmapped(const std::string& name) {
  for (const UnmappedName& unmapped : UnmappedNames()) {
    if (name.rfind(unmapped.library_name_prefix, 0) == 0) return true;
  }
  return false;
}

// A program's flags are defined in its object file: these references (volatile:
// kept by the optimiser) link them into the test, so that gflags knows every
// flag of ipstep and ipstep_compare.
int (*volatile ipstep_program)(int, char**) = &RunIpstep;
int (*volatile compare_program)(int, char**) = &RunCompare;

bool LinkPrograms() { return ipstep_program != nullptr && compare_program != nullptr; }

TEST(FlagNames, EveryReportedOptionHasAFlagOrIsUnmappedDeliberately) {
  const std::set<std::string> reported = ReportedOptionNames();
  // The scan finds the names (a sample of each folder that reports some).
  for (const char* name :
       {"options: OptimizerOptions.tolerance", "options: IntegratorOptions.name",
        "options: SimulationOptions.time_step", "options: SceneLoadOptions.grid_size"}) {
    EXPECT_EQ(reported.count(name), 1u) << name;
  }
  for (const std::string& name : reported) {
    EXPECT_TRUE(!FlagFor(name).empty() || Unmapped(name))
        << name << ": neither in FlagNames() nor in UnmappedNames() (apps/flag_names.cc)";
    EXPECT_FALSE(!FlagFor(name).empty() && Unmapped(name)) << name << ": both mapped and unmapped";
  }
}

TEST(FlagNames, EveryRowIsReportedAndItsFlagExists) {
  ASSERT_TRUE(LinkPrograms());
  const std::set<std::string> reported = ReportedOptionNames();
  // The outputs apps/ipstep_program.cc and apps/compare_program.cc name (io/
  // takes the name from its caller).
  const std::set<std::string> outputs = {"output: stats", "output: iterations_log",
                                         "output: positions", "output: frames",
                                         "output: compare_output"};
  std::set<std::string> rows;
  for (const FlagName& row : FlagNames()) {
    EXPECT_TRUE(rows.insert(row.library_name).second) << row.library_name << ": two rows";
    EXPECT_TRUE(reported.count(row.library_name) == 1 || outputs.count(row.library_name) == 1)
        << row.library_name << ": the library reports no such name (a stale row?)";
    gflags::CommandLineFlagInfo info;
    EXPECT_TRUE(gflags::GetCommandLineFlagInfo(row.flag, &info))
        << row.library_name << ": no flag --" << row.flag;
  }
  for (const std::string& output : outputs) EXPECT_EQ(rows.count(output), 1u) << output;
}

TEST(FlagNames, MessagesNameTheFlag) {
  EXPECT_EQ(WithFlagNames("options: OptimizerOptions.tolerance: must be > 0"),
            "flag: --tolerance: must be > 0");
  EXPECT_EQ(WithFlagNames("options: OptimizerOptions.initial_trust_region_radius: x: y"),
            "flag: --trust_region_radius: x: y");
  EXPECT_EQ(WithFlagNames("options: SimulationOptions.time_step: must be in [1e-12, 1e3] s"),
            "flag: --dt: must be in [1e-12, 1e3] s");
  EXPECT_EQ(WithFlagNames("options: IntegratorOptions.name: unknown integrator 'rk4'"),
            "flag: --integrator: unknown integrator 'rk4'");
  // A value named with the option stays with the flag.
  EXPECT_EQ(WithFlagNames("options: OptimizerOptions.optimizer=bfgs: BFGS stores ..."),
            "flag: --optimizer=bfgs: BFGS stores ...");
  EXPECT_EQ(WithFlagNames("output: stats: cannot write 'a/b.csv'"),
            "flag: --stats: cannot write 'a/b.csv'");
  // Unchanged: unmapped names, unknown names, scene files, flags, other text.
  for (const char* message :
       {"options: effect_overrides.friction: the scene has no effect 'friction'",
        "options: OptimizerOptions.no_such_field: x", "output: final positions: cannot write 'x'",
        "problems/cloth.json: grid.nx: must be >= 2", "flag: --dt: must be in [1e-12, 1e3] s",
        "options: OptimizerOptions.tolerance", "no colon at all", ""}) {
    EXPECT_EQ(WithFlagNames(message), message);
  }
}

// From the error's parts (InputError::where, key, detail) the same text as
// from the message, without parsing it: a detail with ": " in it, a value
// named with the option, an unmapped name, a message without parts.
TEST(FlagNames, AnErrorsPartsNameTheFlag) {
  const InputError tolerance("options", "OptimizerOptions.tolerance", "must be > 0: x");
  EXPECT_EQ(tolerance.where(), "options");
  EXPECT_EQ(tolerance.key(), "OptimizerOptions.tolerance");
  EXPECT_EQ(tolerance.detail(), "must be > 0: x");
  EXPECT_EQ(WithFlagNames(tolerance), "flag: --tolerance: must be > 0: x");
  EXPECT_EQ(WithFlagNames(InputError("options", "OptimizerOptions.optimizer=bfgs", "too big")),
            "flag: --optimizer=bfgs: too big");
  EXPECT_EQ(WithFlagNames(InputError("output", "stats", "cannot write 'a'")),
            "flag: --stats: cannot write 'a'");
  const InputError scene("problems/cloth.json", "grid.nx", "must be >= 2");
  EXPECT_EQ(WithFlagNames(scene), scene.what());
  const InputError text("options: OptimizerOptions.tolerance: must be > 0");
  EXPECT_TRUE(text.key().empty());
  EXPECT_EQ(WithFlagNames(text), "flag: --tolerance: must be > 0");
  // Parts and text agree on every mapped name.
  for (const FlagName& row : FlagNames()) {
    const std::string name = row.library_name;
    const InputError e(name.substr(0, name.find(": ")), name.substr(name.find(": ") + 2), "bad");
    EXPECT_EQ(WithFlagNames(e), WithFlagNames(std::string(e.what()))) << name;
    EXPECT_EQ(WithFlagNames(e), "flag: --" + std::string(row.flag) + ": bad") << name;
  }
}

// A library error as the library throws it, as the programs print it.
TEST(FlagNames, ALibraryErrorBecomesAFlagError) {
  OptimizerOptions options;
  options.tolerance = 0.0;
  try {
    ValidateOptimizerOptions(options);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("options: OptimizerOptions.tolerance: must be", 0), 0u)
        << e.what();
    EXPECT_EQ(WithFlagNames(e.what()).rfind("flag: --tolerance: must be", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace ipstep
