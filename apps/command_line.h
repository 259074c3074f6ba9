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

// The value of a flag given on the command line, checked against its range:
// throws InputError "flag: --name: must be in [min, max] unit (omit the flag
// for <when_omitted>), got value". `when_omitted` says what the unset flag
// means (e.g. "the scene's time_step"); empty: no such note. `min_open`:
// (min, max]. Use for flags whose unset value is a sentinel ("0: the
// default"): call only when !FlagIsDefault(name), so that an explicit
// sentinel is an error, not the default.
double CheckFlagRange(const char* name, double value, double min, double max,
                      const std::string& unit, const std::string& when_omitted,
                      bool min_open = false);
int CheckFlagRange(const char* name, int value, int min, int max, const std::string& when_omitted);

// The non-empty items of a comma-separated flag value ("a,b,,c" -> a, b, c).
std::vector<std::string> SplitList(const std::string& text);

}  // namespace ipstep
