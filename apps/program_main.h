// The common main() of the ipstep programs: strict flag checking, gflags and
// glog set-up, and the translation of input errors into one line and exit code 2.
#pragma once

#include <functional>

namespace ipstep {

// Logging is quiet by default: -v=1 logs every step, -v=2 every optimizer
// iteration. Returns run()'s exit code, or kInputErrorExitCode after printing
// "<program>: error: <message>" for an InputError (1 and "internal error" for any
// other exception).
// --help and its variants print and return 0 (gflags would exit with 1).
int ProgramMain(int argc, char** argv, const char* program, const char* usage,
                const std::function<int()>& run);

}  // namespace ipstep
