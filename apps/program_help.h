// The programs' help: --help, --helpshort and --helpfull list the program's own
// flags first, grouped (scene, integrator, optimiser, contact, output, and the
// program's remaining flags), with the built-in scene names; --helpfull adds
// glog's and gflags' flags. --version prints the project version. gflags'
// other help flags (--helpon, --helpmatch, --helpxml, --helppackage) keep
// gflags' formats.
#pragma once

#include <string>

namespace ipstep {

// Answers a help flag on stdout and returns true (exit code 0), or returns
// false when none was given. Call after gflags has parsed the command line.
bool HandleHelpFlags(const char* program);

// The version of ipstep (CMake's project version), e.g. "0.1.0".
const char* IpstepVersion();

// The group a flag of the programs belongs to ("scene", "integrator",
// "optimiser", "contact", "output"), or "" for flags not in the table (shown
// under "other flags of <program>").
std::string FlagGroup(const std::string& name);

}  // namespace ipstep
