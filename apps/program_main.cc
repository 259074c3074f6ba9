#include "apps/program_main.h"

#include <cstdio>
#include <exception>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "solver/allocator_tuning.h"

namespace ipstep {

int ProgramMain(int argc, char** argv, const char* program, const char* usage,
                const std::function<int()>& run) {
  gflags::SetUsageMessage(usage);
  FLAGS_logtostderr = true;
  KeepLargeAllocations();  // solver/allocator_tuning.h
  try {
    CheckCommandLine(argc, argv);
    gflags::ParseCommandLineFlags(&argc, &argv, true);
    google::InitGoogleLogging(argv[0]);
    return run();
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program, e.what());
    return kInputErrorExitCode;
  } catch (const std::exception& e) {
    // Not an input error: a bug. Still one line and an exit code, not an abort.
    std::fprintf(stderr, "%s: internal error: %s\n", program, e.what());
    return 1;
  }
}

}  // namespace ipstep
