// The common main() of the ipstep programs: strict flag checking, gflags and
// glog set-up, and the translation of input errors into one line and exit code 2.
#pragma once

#include <functional>
#include <string>

namespace ipstep {

// Logging is quiet by default: nothing glog or Ceres logs is shown (warnings
// and errors alike; a fatal error still is); -v=1 logs every step, -v=2 every
// optimizer iteration, and both show Ceres's log (so does an explicit
// --minloglevel). Returns run()'s exit code, or kInputErrorExitCode after
// printing "<program>: error: <message>" for an InputError, an option the
// library names printed as its flag (apps/flag_names.h) (1 and "internal
// error" for any other exception). An OutputError (io/output_file.h) is one
// such line too, with exit code 2 for a path that cannot be written and 3 for
// a failed write; so is a failed write to stdout (checked when run() returns,
// exit code 3 unless run() returned another non-zero code).
// --help and its variants print and return 0 (gflags would exit with 1;
// apps/program_help.h).
int ProgramMain(int argc, char** argv, const char* program, const char* usage,
                const std::function<int()>& run);

// Flushes stdout; throws OutputError ("output: stdout: write failed: ...",
// kWrite) if a write to it failed. ProgramMain calls it when run() returns; a
// program calls it too where a lost stdout should stop it early (after its
// header).
void CheckStdout();

// The name of the running program for messages: the file name of argv[0], or
// `fallback` when there is none.
std::string ProgramName(int argc, char** argv, const char* fallback);

}  // namespace ipstep
