// Strict command-line checking in front of gflags: an unknown flag or a value
// gflags cannot parse becomes one InputError naming the flag (exit code 2),
// instead of gflags' own exit(1).
#pragma once

#include <string>
#include <vector>

namespace ipstep {

// Throws InputError. Call before gflags::ParseCommandLineFlags.
void CheckCommandLine(int argc, char** argv);

// True if the flag `name` (without dashes) was not given on the command line.
bool FlagIsDefault(const char* name);

// The non-empty items of a comma-separated flag value ("a,b,,c" -> a, b, c).
std::vector<std::string> SplitList(const std::string& text);

}  // namespace ipstep
