#include "apps/program_main.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <gflags/gflags_completions.h>
#include <glog/logging.h>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "solver/allocator_tuning.h"

namespace ipstep {
namespace {

std::string FlagValue(const char* name) {
  std::string value;
  gflags::GetCommandLineOption(name, &value);
  return value;
}

bool FlagIsTrue(const char* name) { return FlagValue(name) == "true"; }

// The program's own flags: those defined under apps/ or bench/ (not glog's or
// gflags'), grouped by file as gflags does.
void ShowOwnFlags(const char* program) {
  std::printf("%s: %s\n", program, gflags::ProgramUsage());
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);  // sorted by file, then name
  std::string file;
  for (const gflags::CommandLineFlagInfo& flag : flags) {
    if (flag.filename.find("apps/") == std::string::npos &&
        flag.filename.find("bench/") == std::string::npos) {
      continue;
    }
    if (flag.filename != file) {
      file = flag.filename;
      std::printf("\n  Flags from %s:\n", file.c_str());
    }
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

// gflags' help flags, which gflags itself answers with exit code 1. Returns
// true (exit code 0) if one was given and answered.
bool HandleHelpFlags(const char* program) {
  google::HandleCommandLineCompletions();  // --tab_completion_word: prints, exits 0
  if (FlagIsTrue("helpshort") || FlagIsTrue("helppackage")) {
    ShowOwnFlags(program);
  } else if (FlagIsTrue("help") || FlagIsTrue("helpfull")) {
    gflags::ShowUsageWithFlags(program);
  } else if (!FlagValue("helpon").empty()) {
    gflags::ShowUsageWithFlagsRestrict(program, ("/" + FlagValue("helpon") + ".").c_str());
  } else if (!FlagValue("helpmatch").empty()) {
    gflags::ShowUsageWithFlagsRestrict(program, FlagValue("helpmatch").c_str());
  } else if (FlagIsTrue("helpxml")) {
    ShowFlagsAsXml(program);
  } else if (FlagIsTrue("version")) {
    const std::string version = gflags::VersionString();
    std::printf("%s%s\n", program, version.empty() ? "" : (" version " + version).c_str());
  } else {
    return false;
  }
  std::fflush(stdout);
  return true;
}

// " (in flagfile f, line 3)" for an error "flag: --name: ..." about a flag
// whose value came from a flagfile or the environment, if not said already.
std::string OriginNote(const std::string& message) {
  const std::string prefix = "flag: --";
  if (message.rfind(prefix, 0) != 0) return "";
  const size_t end = message.find_first_of(":=", prefix.size());
  const std::string origin = FlagOrigin(message.substr(prefix.size(), end - prefix.size()));
  if (origin.empty() || message.find(origin) != std::string::npos) return "";
  return " (" + origin + ")";
}

}  // namespace

int ProgramMain(int argc, char** argv, const char* program, const char* usage,
                const std::function<int()>& run) {
  gflags::SetUsageMessage(usage);
  FLAGS_logtostderr = true;
  KeepLargeAllocations();  // solver/allocator_tuning.h
  try {
    // The checked (and expanded: --flagfile, --fromenv) arguments; gflags only
    // parses them, and the help flags are answered here with exit code 0.
    std::vector<std::string> arguments = CheckCommandLine(argc, argv);
    std::vector<char*> pointers;
    for (std::string& argument : arguments) pointers.push_back(argument.data());
    pointers.push_back(nullptr);
    int count = static_cast<int>(arguments.size());
    char** parsed = pointers.data();
    gflags::ParseCommandLineNonHelpFlags(&count, &parsed, true);
    if (HandleHelpFlags(program)) return 0;
    google::InitGoogleLogging(argc > 0 ? argv[0] : program);
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s%s\n", program, e.what(), OriginNote(e.what()).c_str());
    return kInputErrorExitCode;
  } catch (const std::exception& e) {
    // Not an input error: a bug. Still one line and an exit code, not an abort.
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace ipstep
