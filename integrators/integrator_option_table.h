// The option table of IntegratorOptions (core/option_table.h): the integrator
// and Newmark's parameters, as the programs' flags --integrator,
// --newmark_beta and --newmark_gamma (apps/solver_flags.cc).
#pragma once

#include "core/option_table.h"
#include "integrators/integrator_options.h"

namespace ipstep {

// Names: "integrator" (IntegratorOptions.name), "newmark_beta", "newmark_gamma".
const OptionTable<IntegratorOptions>& IntegratorOptionTable();

}  // namespace ipstep
