// The one table from the names the library gives to bad input to the
// programs' flags.
//
// The library knows options, not flags: it names a bad field of an options
// struct "options: <Struct>.<field>: ..." (e.g. "options: OptimizerOptions.
// tolerance: must be a finite number > 0, got 0"; with the value when it
// matters, "options: OptimizerOptions.optimizer=bfgs: ...") and an output it
// cannot write by the name its caller gave it, "output: <name>: ..." (docs/architecture.md
// "Using ipstep as a library"). The programs (ipstep, ipstep_compare,
// ipstep_bench) print such an error naming the flag instead:
// "flag: --tolerance: must be ...". Flags the programs check themselves
// before the library sees them (apps/solver_flags.cc, apps/contact_flags.cc)
// need no row.
#pragma once

#include <string>
#include <vector>

#include "core/input_error.h"

namespace ipstep {

struct FlagName {
  const char* library_name;  // "options: OptimizerOptions.tolerance", "output: stats"
  const char* flag;          // "tolerance" (without "--")
};

// Every name the library reports (and the outputs the programs name) with its flag.
const std::vector<FlagName>& FlagNames();

// Library names left as they are, deliberately: each a prefix of the name
// ("options: effect_overrides.") and why no flag is named.
struct UnmappedName {
  const char* library_name_prefix;
  const char* reason;
};
const std::vector<UnmappedName>& UnmappedNames();

// The flag (without "--") for a library name such as
// "options: OptimizerOptions.tolerance" (a "=value" after the name is
// ignored); "" when there is none.
std::string FlagFor(const std::string& library_name);

// `message` with the library name it starts with replaced by its flag
// ("options: OptimizerOptions.tolerance: x" -> "flag: --tolerance: x",
// "options: OptimizerOptions.optimizer=bfgs: x" -> "flag: --optimizer=bfgs: x");
// any other message unchanged.
std::string WithFlagNames(const std::string& message);
// The same from the error's parts (InputError::where, key, detail): no
// parsing of the message; one without parts goes through the text.
std::string WithFlagNames(const InputError& error);

}  // namespace ipstep
