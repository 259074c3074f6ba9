// The programs' flags from the library's option rows (core/option_table.h):
// a flag that sets an option of a library struct takes its help text, its
// default and its range from that option's row, so each is written once.
//
//   DEFINE_double(dt, FlagDefault<double>("dt"), FlagHelp("dt"));
//
// The rows are those of SimulationOptionTable() (with the integrator's and
// optimiser's rows and the contact overrides), SceneLoadOptionTable(),
// RunOptionTable() and AdaptiveOptionTable(). These functions may run during
// static initialisation (the tables are built on first use).
#pragma once

#include <string>

namespace ipstep {

// The help text of the flag `flag` (without "--"): the row's doc, its range
// ("in [1e-12, 1e3] s") and what its unset value means ("default: the
// scene's time_step"). The text lives as long as the program. Throws
// std::logic_error if no row has the flag.
const char* FlagHelp(const char* flag);
// The same for a flag whose program default is not the struct's (ipstep's
// --max_substeps, --error_tolerance): without the row's "default:" part,
// since gflags prints the program's default.
const char* ProgramFlagHelp(const char* flag);

// The row's default, as the flag's type (bool, int, double, const char*).
template <class T>
T FlagDefault(const char* flag);

// A given flag's value checked against its row's range: throws InputError
// "flag: --name: must be in [min, max] unit (omit the flag for <what the
// unset flag means>), got value" (apps/command_line.h CheckFlagRange).
double FlagInRowRange(const char* flag, double value);
int FlagInRowRange(const char* flag, int value);

}  // namespace ipstep
