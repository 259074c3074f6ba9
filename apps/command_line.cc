#include "apps/command_line.h"

#include <sstream>
#include <string>

#include <gflags/gflags.h>

#include "core/input_error.h"
#include "core/input_limits.h"

namespace ipstep {

void CheckCommandLine(int argc, char** argv) {
  for (int a = 1; a < argc; ++a) {
    std::string arg = argv[a];
    if (arg == "--") break;
    if (arg.size() < 2 || arg[0] != '-') {
      throw InputError("command line", arg, "unexpected argument (flags look like --name=value)");
    }
    arg = arg.substr(arg[1] == '-' ? 2 : 1);
    const size_t eq = arg.find('=');
    std::string name = arg.substr(0, eq);
    gflags::CommandLineFlagInfo info;
    bool negated = false;
    if (!gflags::GetCommandLineFlagInfo(name.c_str(), &info)) {
      if (name.rfind("no", 0) == 0 &&
          gflags::GetCommandLineFlagInfo(name.substr(2).c_str(), &info) && info.type == "bool" &&
          eq == std::string::npos) {
        negated = true;
      } else {
        throw InputError("flag", "--" + name, "unknown flag (see --help)");
      }
    }
    if (negated) continue;
    std::string value;
    if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
    } else if (info.type == "bool") {
      value = "true";
    } else if (a + 1 < argc) {
      value = argv[++a];
    } else {
      throw InputError("flag", "--" + name, "missing value");
    }
    // Validate by parsing into a scratch copy; gflags then parses for real.
    const std::string saved = info.current_value;
    if (gflags::SetCommandLineOption(name.c_str(), value.c_str()).empty()) {
      throw InputError("flag", "--" + name,
                       "invalid value '" + value + "' for a flag of type " + info.type);
    }
    gflags::SetCommandLineOption(name.c_str(), saved.c_str());
  }
}

double CheckFlagRange(const char* name, double value, double min, double max,
                      const std::string& unit, const std::string& when_omitted, bool min_open) {
  if (!(min_open ? value > min : value >= min) || !(value <= max)) {
    throw InputError("flag", std::string("--") + name,
                     "must be in " + limits::RangeText(min, max, unit, min_open) +
                         (when_omitted.empty() ? "" : " (omit the flag for " + when_omitted + ")") +
                         ", got " + limits::FormatLimit(value));
  }
  return value;
}

int CheckFlagRange(const char* name, int value, int min, int max, const std::string& when_omitted) {
  if (value < min || value > max) {
    throw InputError("flag", std::string("--") + name,
                     "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                         "]" +
                         (when_omitted.empty() ? "" : " (omit the flag for " + when_omitted + ")") +
                         ", got " + std::to_string(value));
  }
  return value;
}

bool FlagIsDefault(const char* name) {
  gflags::CommandLineFlagInfo info;
  return !gflags::GetCommandLineFlagInfo(name, &info) || info.is_default;
}

std::vector<std::string> SplitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

}  // namespace ipstep
