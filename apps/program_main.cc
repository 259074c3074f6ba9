#include "apps/program_main.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/command_line.h"
#include "apps/flag_names.h"
#include "apps/program_help.h"
#include "core/input_error.h"
#include "io/output_file.h"
#include "solver/allocator_tuning.h"

namespace ipstep {
namespace {

// Quiet by default: nothing glog or Ceres logs reaches a normal run — neither
// Ceres's warnings ("Restarting non-linear conjugate gradients", "Error in
// evaluating the ResidualBlock", ...) nor its errors ("Terminating: Residual
// and Jacobian evaluation failed."), whose news is the step's status; only a
// fatal error (an abort) is still logged. The programs' own messages are
// printed, not logged. -v=1 or more (ipstep's step and iteration logs) or an
// explicit --minloglevel brings the log back.
void QuietLogging() {
  if (FLAGS_v <= 0 && FlagIsDefault("minloglevel")) FLAGS_minloglevel = google::GLOG_FATAL;
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

void CheckStdout() {
  // A write that failed earlier (a full buffer) left no errno: the flush of
  // what stdio still holds gives the reason again.
  const bool failed = std::ferror(stdout) != 0;
  std::clearerr(stdout);
  errno = 0;
  if (std::fflush(stdout) != 0 || failed) {
    throw OutputError("output: stdout", "", OutputError::Kind::kWrite,
                      errno > 0 ? std::strerror(errno) : "the stream failed");
  }
}

std::string ProgramName(int argc, char** argv, const char* fallback) {
  if (argc < 1 || argv == nullptr || argv[0] == nullptr || argv[0][0] == '\0') return fallback;
  const std::string path = argv[0];
  const std::string name = path.substr(path.find_last_of('/') + 1);
  return name.empty() ? fallback : name;
}

int ProgramMain(int argc, char** argv, const char* program, const char* usage,
                const std::function<int()>& run) {
  // gflags aborts on a second usage message and glog on a second
  // initialisation (a program that initialised glog itself, or called a Run*
  // entry point before).
  static bool usage_set = false;
  if (!usage_set) gflags::SetUsageMessage(usage);
  usage_set = true;
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
    if (HandleHelpFlags(program)) {
      CheckStdout();
      return 0;
    }
    QuietLogging();
    if (!google::IsGoogleLoggingInitialized()) {
      google::InitGoogleLogging(argc > 0 ? argv[0] : program);
    }
    const int code = run();
    try {
      CheckStdout();  // the tables and summaries are the programs' data
    } catch (const OutputError& e) {
      std::fprintf(stderr, "%s: error: %s\n", program, e.what());
      return code != 0 ? code : kStepFailureExitCode;
    }
    return code;
  } catch (const OutputError& e) {
    // A path that cannot be written is bad input (2); a write that failed
    // (a full disk) is not: the run stopped there (3).
    std::fprintf(stderr, "%s: error: %s\n", program, WithFlagNames(e.what()).c_str());
    return e.kind() == OutputError::Kind::kOpen ? kInputErrorExitCode : kStepFailureExitCode;
  } catch (const InputError& e) {
    // The library names options, the programs name flags (apps/flag_names.h).
    const std::string message = WithFlagNames(e);
    std::fprintf(stderr, "%s: error: %s%s\n", program, message.c_str(),
                 OriginNote(message).c_str());
    return kInputErrorExitCode;
  } catch (const std::exception& e) {
    // Not an input error: a bug. Still one line and an exit code, not an abort.
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace ipstep
