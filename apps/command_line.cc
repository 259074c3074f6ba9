#include "apps/command_line.h"

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gflags/gflags.h>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/near_miss.h"

namespace ipstep {

namespace {

namespace fs = std::filesystem;

// Flagfiles are small text files.
constexpr std::uintmax_t kMaxFlagfileBytes = 1 << 20;
constexpr int kMaxFlagfileDepth = 10;

// One argument and where it came from ("" for the command line).
struct Argument {
  std::string text;
  std::string origin;
};

// "--name=value" / "-name" -> name, value. False if `text` is not a flag.
bool SplitFlag(const std::string& text, std::string* name, std::string* value, bool* has_value) {
  if (text.size() < 2 || text[0] != '-' || text == "--") return false;
  const std::string body = text.substr(text[1] == '-' ? 2 : 1);
  const size_t eq = body.find('=');
  *name = body.substr(0, eq);
  *has_value = eq != std::string::npos;
  *value = *has_value ? body.substr(eq + 1) : "";
  return true;
}

std::string ReadFlagfile(const std::string& path) {
  const auto fail = [&path](const std::string& what) {
    throw InputError("flag", "--flagfile", "cannot read '" + ClipInput(path) + "': " + what);
  };
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status)) fail("no such file");
  if (!fs::is_regular_file(status)) fail("not a regular file");
  if (fs::file_size(path, error) > kMaxFlagfileBytes) fail("larger than 1 MiB");
  std::ifstream file(path, std::ios::binary);
  if (!file) fail(std::strerror(errno));
  std::string text;
  std::vector<char> buffer(1 << 16);
  while (file.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) ||
         file.gcount() > 0) {
    text.append(buffer.data(), static_cast<size_t>(file.gcount()));
    if (text.size() > kMaxFlagfileBytes) fail("larger than 1 MiB");
  }
  if (text.find('\0') != std::string::npos) fail("contains a NUL byte");
  return text;
}

// The flags of a flagfile, as gflags reads it: one flag per line, leading
// (and here also trailing) blanks ignored, # comments and blank lines skipped.
// gflags' "program-name sections" (lines not starting with '-') are refused.
std::vector<Argument> FlagfileArguments(const std::string& path) {
  const std::string text = ReadFlagfile(path);
  std::vector<Argument> arguments;
  int line_number = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find_first_of("\r\n", start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    ++line_number;
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') {
      ++end;
    }
    start = end + 1;
    const size_t first = line.find_first_not_of(" \t\f\v");
    if (first == std::string::npos) continue;
    line = line.substr(first, line.find_last_not_of(" \t\f\v") + 1 - first);
    const std::string origin =
        "in flagfile " + ClipInput(path) + ", line " + std::to_string(line_number);
    if (line[0] == '#') continue;
    if (line[0] != '-') {
      throw InputError("flag", "--flagfile",
                       "'" + ClipInput(line) + "' is not a flag (" + origin +
                           "; lines must be --name=value, # comments or blank: gflags' "
                           "program-name sections are not supported)");
    }
    arguments.push_back({line, origin});
  }
  return arguments;
}

void Expand(const std::vector<Argument>& in, int depth, std::vector<Argument>* out) {
  for (size_t a = 0; a < in.size(); ++a) {
    const Argument& argument = in[a];
    std::string name, value;
    bool has_value = false;
    if (argument.text == "--") {
      out->insert(out->end(), in.begin() + static_cast<std::ptrdiff_t>(a), in.end());
      return;
    }
    if (!SplitFlag(argument.text, &name, &value, &has_value) ||
        (name != "flagfile" && name != "fromenv" && name != "tryfromenv" && name != "undefok")) {
      out->push_back(argument);
      continue;
    }
    const std::string where = argument.origin.empty() ? "" : " (" + argument.origin + ")";
    if (name == "undefok") {
      throw InputError("flag", "--undefok",
                       "not supported: every unknown flag is an error" + where);
    }
    if (!has_value) {
      if (!argument.origin.empty() || a + 1 >= in.size()) {
        throw InputError("flag", "--" + name, "missing value" + where);
      }
      value = in[++a].text;
    }
    if (name == "flagfile") {
      if (depth >= kMaxFlagfileDepth) {
        throw InputError("flag", "--flagfile",
                         "flagfiles nested more than " + std::to_string(kMaxFlagfileDepth) +
                             " deep (does one include itself?)" + where);
      }
      for (const std::string& path : SplitList(value)) {
        Expand(FlagfileArguments(path), depth + 1, out);
      }
      continue;
    }
    // --fromenv / --tryfromenv: FLAGS_<name> for each listed flag.
    for (const std::string& flag : SplitList(value)) {
      gflags::CommandLineFlagInfo info;
      if (!gflags::GetCommandLineFlagInfo(flag.c_str(), &info) || flag == "flagfile" ||
          flag == "fromenv" || flag == "tryfromenv" || flag == "undefok") {
        throw InputError("flag", "--" + name,
                         "'" + ClipInput(flag) +
                             "' is not a flag that can be read from the "
                             "environment (see --help)" +
                             where);
      }
      const std::string variable = "FLAGS_" + flag;
      const char* text = std::getenv(variable.c_str());
      if (text == nullptr) {
        if (name == "tryfromenv") continue;
        throw InputError(
            "flag", "--fromenv",
            variable + " is not set in the environment (--tryfromenv allows that)" + where);
      }
      out->push_back({"--" + flag + "=" + text, "from the environment variable " + variable});
    }
  }
}

// Flag name -> where its (last) value came from, when not the command line.
std::map<std::string, std::string>& Origins() {
  static auto* const origins = new std::map<std::string, std::string>;
  return *origins;
}

void NoteOrigin(const std::string& name, const std::string& origin) {
  if (origin.empty()) {
    Origins().erase(name);
  } else {
    Origins()[name] = origin;
  }
}

// " (did you mean --optimizer?)" for a near miss of a defined flag's name.
std::string FlagSuggestion(const std::string& name) {
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  std::vector<std::string> names;
  for (const gflags::CommandLineFlagInfo& flag : flags) names.push_back(flag.name);
  const std::string near = NearMiss(name, names);
  return near.empty() ? "" : " (did you mean --" + near + "?)";
}

// Checks one flag argument (and the next one when it is the value); returns
// the index of the last argument used.
size_t CheckArgument(const std::vector<Argument>& arguments, size_t a) {
  std::string arg = arguments[a].text;
  const bool from_command_line = arguments[a].origin.empty();
  if (arg.size() < 2 || arg[0] != '-') {
    throw InputError("command line", arg, "unexpected argument (flags look like --name=value)");
  }
  arg = arg.substr(arg[1] == '-' ? 2 : 1);
  const size_t eq = arg.find('=');
  std::string name = arg.substr(0, eq);
  gflags::CommandLineFlagInfo info;
  if (!gflags::GetCommandLineFlagInfo(name.c_str(), &info)) {
    if (name.rfind("no", 0) == 0 && gflags::GetCommandLineFlagInfo(name.substr(2).c_str(), &info) &&
        info.type == "bool" && eq == std::string::npos) {
      NoteOrigin(name.substr(2), arguments[a].origin);
      return a;  // --noflag
    }
    throw InputError("flag", "--" + name, "unknown flag" + FlagSuggestion(name) + " (see --help)");
  }
  std::string value;
  if (eq != std::string::npos) {
    value = arg.substr(eq + 1);
  } else if (info.type == "bool") {
    value = "true";
  } else if (from_command_line && a + 1 < arguments.size() && arguments[a + 1].origin.empty()) {
    value = arguments[++a].text;
  } else {
    throw InputError("flag", "--" + name,
                     from_command_line ? "missing value" : "missing value (write --name=value)");
  }
  // Validate by parsing into a scratch copy; gflags then parses for real.
  const std::string saved = info.current_value;
  if (gflags::SetCommandLineOption(name.c_str(), value.c_str()).empty()) {
    throw InputError("flag", "--" + name,
                     "invalid value '" + ClipInput(value) + "' for a flag of type " + info.type);
  }
  gflags::SetCommandLineOption(name.c_str(), saved.c_str());
  NoteOrigin(name, arguments[a].origin);
  return a;
}

}  // namespace

std::vector<std::string> CheckCommandLine(int argc, char** argv) {
  std::vector<Argument> given;
  for (int a = 1; a < argc; ++a) given.push_back({argv[a], ""});
  std::vector<Argument> arguments;
  Expand(given, 0, &arguments);
  for (size_t a = 0; a < arguments.size(); ++a) {
    if (arguments[a].text == "--") break;
    try {
      a = CheckArgument(arguments, a);
    } catch (const InputError& error) {
      if (arguments[a].origin.empty()) throw;
      throw InputError(std::string(error.what()) + " (" + arguments[a].origin + ")");
    }
  }
  std::vector<std::string> result{argc > 0 ? argv[0] : "ipstep"};
  for (const Argument& argument : arguments) result.push_back(argument.text);
  return result;
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

std::string FlagOrigin(const std::string& name) {
  const auto found = Origins().find(name);
  return found == Origins().end() ? "" : found->second;
}

bool FlagIsDefault(const char* name) {
  gflags::CommandLineFlagInfo info;
  return !gflags::GetCommandLineFlagInfo(name, &info) || info.is_default;
}

std::vector<std::pair<std::string, std::string>> GivenFlags(const std::string& except_file) {
  static const std::set<std::string> logging = {
      "v",       "vmodule",  "minloglevel", "logtostderr", "alsologtostderr", "stderrthreshold",
      "log_dir", "flagfile", "fromenv",     "tryfromenv"};
  std::vector<gflags::CommandLineFlagInfo> flags;
  gflags::GetAllFlags(&flags);
  std::vector<std::pair<std::string, std::string>> given;
  for (const gflags::CommandLineFlagInfo& flag : flags) {
    if (flag.is_default || flag.filename == except_file || logging.count(flag.name)) continue;
    given.emplace_back(flag.name, flag.current_value);
  }
  return given;
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
