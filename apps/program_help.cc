#include "apps/program_help.h"

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <gflags/gflags_completions.h>

#include "apps/version.h"
#include "core/option_table.h"
#include "integrators/integrator_option_table.h"
#include "problems/scene_loader.h"
#include "solver/optimizer_option_table.h"

namespace ipstep {
namespace {

// The groups of the programs' flags, in the order --help shows them.
struct GroupEntry {
  const char* group;
  const char* title;
  std::vector<const char*> flags;
};

// The flags of a table's rows, in the table's order, then `more`.
template <class Options>
std::vector<const char*> FlagsOf(const OptionTable<Options>& table, std::vector<const char*> more) {
  std::vector<const char*> flags;
  for (const OptionRow<Options>& row : table) {
    if (!row.flag.empty()) flags.push_back(row.flag.c_str());
  }
  flags.insert(flags.end(), more.begin(), more.end());
  return flags;
}

const std::vector<GroupEntry>& Groups() {
  // ipstep's flags, then ipstep_compare's and ipstep_bench's lists. The
  // integrator's and the optimiser's options are their tables' rows
  // (integrators/integrator_option_table.h, solver/optimizer_option_table.h).
  static const auto* const groups = new std::vector<GroupEntry>{
      {"scene",
       "Scene",
       {"scene", "grid_size", "dt", "steps", "scenes", "grid_sizes", "dts", "dt_factors", "t_end"}},
      {"integrator", "Integrator, failed steps and adaptive steps",
       FlagsOf(IntegratorOptionTable(),
               {"energy_tolerance", "max_substeps", "on_failure", "integrators", "adaptive",
                "error_tolerance", "min_dt", "max_dt", "filter_stiff_modes"})},
      {"optimiser", "Optimiser",
       FlagsOf(OptimizerOptionTable(),
               {"optimizers", "tolerances", "reference_optimizer", "reference_tolerance"})},
      {"contact",
       "Contact (scenes with the contact or friction effect)",
       {"contact_kappa", "contact_dhat", "friction_mu", "friction_iterations"}},
      {"output",
       "Output",
       {"stats", "iterations_log", "positions", "frames", "frames_format", "frames_precision",
        "frame_every", "progress", "output", "shard", "merge", "dry_run"}},
  };
  return *groups;
}

std::string FlagValue(const char* name) {
  std::string value;
  gflags::GetCommandLineOption(name, &value);
  return value;
}

bool FlagIsTrue(const char* name) { return FlagValue(name) == "true"; }

// Flags defined by glog or gflags themselves (not by a program).
bool IsLibraryFlag(const gflags::CommandLineFlagInfo& flag) {
  const std::string& file = flag.filename;
  for (const char* library_file :
       {"gflags.cc", "gflags_reporting.cc", "gflags_completions.cc", "logging.cc", "vlog_is_on.cc",
        "utilities.cc", "raw_logging.cc", "signalhandler.cc", "symbolize.cc", "demangle.cc"}) {
    const std::string suffix = std::string("src/") + library_file;
    if (file.size() >= suffix.size() &&
        file.compare(file.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return true;
    }
  }
  return file.find("glog") != std::string::npos || file.find("gflags") != std::string::npos;
}

std::string Join(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

// `text` as lines of at most 80 characters, each indented by `indent`.
std::string Wrapped(const std::string& text, const std::string& indent) {
  std::string result, line;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && indent.size() + line.size() + 1 + word.size() > 80) {
      result += indent + line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    start = end + 1;
  }
  if (!line.empty()) result += indent + line + "\n";
  return result;
}

// The program's flags by group; `library` receives glog's and gflags'.
void ShowGroupedFlags(const char* program, bool full) {
  std::printf("%s %s: %s\n", program, IpstepVersion(), gflags::ProgramUsage());
  std::vector<gflags::CommandLineFlagInfo> all;
  gflags::GetAllFlags(&all);  // sorted by file, then name
  std::map<std::string, gflags::CommandLineFlagInfo> own;
  std::vector<gflags::CommandLineFlagInfo> library;
  for (const gflags::CommandLineFlagInfo& flag : all) {
    if (IsLibraryFlag(flag)) {
      library.push_back(flag);
    } else {
      own.emplace(flag.name, flag);
    }
  }
  for (const GroupEntry& group : Groups()) {
    bool shown = false;
    for (const char* name : group.flags) {
      const auto found = own.find(name);
      if (found == own.end()) continue;
      if (!shown) {
        std::printf("\n%s:\n", group.title);
        if (std::string(group.group) == "scene") {
          std::vector<std::string> names;
          for (const std::string& scene : BuiltinSceneNames()) names.push_back(scene);
          std::printf("%s", Wrapped("built-in scenes: " + Join(names) +
                                        "; or a JSON scene file (docs/scenes.md)",
                                    "  ")
                                .c_str());
        }
        shown = true;
      }
      std::printf("%s", gflags::DescribeOneFlag(found->second).c_str());
      own.erase(found);
    }
  }
  if (!own.empty()) {
    std::printf("\nOther flags of %s:\n", program);
    for (const auto& entry : own) std::printf("%s", gflags::DescribeOneFlag(entry.second).c_str());
  }
  std::printf("\n%s", Wrapped("Logging: quiet by default (no glog or Ceres warnings); -v=1 logs "
                              "every step, -v=2 every optimizer iteration, and both show Ceres's "
                              "warnings (--minloglevel=0 shows the warnings alone).",
                              "")
                          .c_str());
  if (!full) {
    std::printf("glog's and gflags' own flags: --helpfull\n");
    return;
  }
  std::printf("\nFlags of glog and gflags:\n");
  for (const gflags::CommandLineFlagInfo& flag : library) {
    std::printf("%s", gflags::DescribeOneFlag(flag).c_str());
  }
}

std::string XmlEscaped(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '&':
        escaped += "&amp;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

// gflags' --helpxml format.
void ShowFlagsAsXml(const char* program) {
  std::printf("<?xml version=\"1.0\"?>\n<AllFlags>\n<program>%s</program>\n<usage>%s</usage>\n",
              XmlEscaped(program).c_str(), XmlEscaped(gflags::ProgramUsage()).c_str());
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  for (const gflags::CommandLineFlagInfo& f : flags) {
    std::printf(
        "<flag><file>%s</file><name>%s</name><meaning>%s</meaning><default>%s</default>"
        "<current>%s</current><type>%s</type></flag>\n",
        XmlEscaped(f.filename).c_str(), XmlEscaped(f.name).c_str(),
        XmlEscaped(f.description).c_str(), XmlEscaped(f.default_value).c_str(),
        XmlEscaped(f.current_value).c_str(), XmlEscaped(f.type).c_str());
  }
  std::printf("</AllFlags>\n");
}

}  // namespace

const char* IpstepVersion() { return IPSTEP_VERSION_STRING; }

std::string FlagGroup(const std::string& name) {
  for (const GroupEntry& group : Groups()) {
    for (const char* flag : group.flags) {
      if (name == flag) return group.group;
    }
  }
  return "";
}

bool HandleHelpFlags(const char* program) {
  google::HandleCommandLineCompletions();  // --tab_completion_word: prints, exits 0
  if (FlagIsTrue("help") || FlagIsTrue("helpshort") || FlagIsTrue("helppackage")) {
    ShowGroupedFlags(program, /*full=*/false);
  } else if (FlagIsTrue("helpfull")) {
    ShowGroupedFlags(program, /*full=*/true);
  } else if (!FlagValue("helpon").empty()) {
    gflags::ShowUsageWithFlagsRestrict(program, ("/" + FlagValue("helpon") + ".").c_str());
  } else if (!FlagValue("helpmatch").empty()) {
    gflags::ShowUsageWithFlagsRestrict(program, FlagValue("helpmatch").c_str());
  } else if (FlagIsTrue("helpxml")) {
    ShowFlagsAsXml(program);
  } else if (FlagIsTrue("version")) {
    std::printf("%s %s\n", program, IpstepVersion());
  } else {
    return false;
  }
  return true;  // ProgramMain flushes and checks stdout
}

}  // namespace ipstep
