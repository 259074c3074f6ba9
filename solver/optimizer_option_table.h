// The option table of OptimizerOptions (core/option_table.h): every field the
// programs expose as a flag (apps/solver_flags.cc), with its default, range and
// the optimisers it applies to.
#pragma once

#include "core/option_table.h"
#include "solver/optimizer_options.h"

namespace ipstep {

const OptionTable<OptimizerOptions>& OptimizerOptionTable();

}  // namespace ipstep
