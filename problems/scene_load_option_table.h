// The option table of SceneLoadOptions (core/option_table.h): grid_size, the
// programs' --grid_size (apps/solver_flags.cc). extra_effects comes from the
// effect registry, not from an option.
#pragma once

#include "core/option_table.h"
#include "problems/scene_loader.h"

namespace ipstep {

const OptionTable<SceneLoadOptions>& SceneLoadOptionTable();

}  // namespace ipstep
