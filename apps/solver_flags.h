// The gflags shared by the ipstep programs: scene, integrator, optimiser and
// every Ceres option an optimiser sets (see docs/programs.md "Flags").
#pragma once

#include <gflags/gflags.h>

#include "energies/effect_registry.h"
#include "problems/scene_loader.h"
#include "sim/default_effects.h"
#include "sim/simulation.h"

DECLARE_string(scene);
DECLARE_string(integrator);
DECLARE_string(optimizer);
DECLARE_double(dt);
DECLARE_int32(steps);
DECLARE_double(tolerance);
DECLARE_int32(grid_size);

namespace ipstep {

// --max_substeps's default in ipstep (and ipstep_tune's runs): a failed step
// is retried as up to 16 substeps; the library's default is 1
// (SimulationOptions::max_substeps).
constexpr int kProgramMaxSubsteps = 16;

// Reads and validates the flags. Throws InputError naming the flag.
// `registry`: the effects scenes are built with (SimulationOptions::effects;
// it must outlive the simulations).
SimulationOptions SimulationOptionsFromFlags(const EffectRegistry& registry = DefaultEffects());
// `registry`: its user effects are accepted in scenes (SceneLoadOptions::extra_effects).
SceneLoadOptions SceneLoadOptionsFromFlags(const EffectRegistry& registry = DefaultEffects());

}  // namespace ipstep
