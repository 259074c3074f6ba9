// Strict command-line checking in front of gflags: an unknown flag or a value
// gflags cannot parse becomes one InputError naming the flag (exit code 2),
// instead of gflags' own exit(1). gflags' --flagfile, --fromenv and
// --tryfromenv are expanded here, so that the flags they bring are checked the
// same way (gflags ignores bad lines of a flagfile); --undefok is refused.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace ipstep {

// Expands --flagfile=FILE[,FILE...] (lines --name=value, # comments and blank
// lines; nested flagfiles up to 10 deep), --fromenv=a,b and --tryfromenv=a,b
// (the variables FLAGS_a, FLAGS_b) into the flags they stand for, and checks
// every flag. Returns the arguments to hand to gflags (argv[0] first). Throws
// InputError naming the flag and, for expanded flags, the file and line or the
// variable. Call before gflags::ParseCommandLineNonHelpFlags.
std::vector<std::string> CheckCommandLine(int argc, char** argv);

// Where the value of flag `name` came from when CheckCommandLine took it from
// a flagfile or the environment ("in flagfile f.flags, line 3"); else "".
std::string FlagOrigin(const std::string& name);

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

// The flags given on the command line (not at their defaults), as
// (name, value), in gflags' order, except those defined in the source file
// `except_file` (a program's own flags: __FILE__) and the logging flags
// (v, vmodule, minloglevel, ...): what else a run of the same scene needs.
std::vector<std::pair<std::string, std::string>> GivenFlags(const std::string& except_file);

// The non-empty items of a comma-separated flag value ("a,b,,c" -> a, b, c).
std::vector<std::string> SplitList(const std::string& text);

}  // namespace ipstep
