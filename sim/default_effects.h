// The default effect registry: gravity, springs and damping
// (energies/builtin_effects.cc), elasticity
// (energies/elasticity/elasticity_effect.h), contact and friction
// (contact/contact_effects.h). Immutable; a program that adds effects copies
// it (MakeDefaultEffects) and passes its own registry to the simulation and
// the scene loader.
#pragma once

#include "energies/effect_registry.h"

namespace ipstep {

const EffectRegistry& DefaultEffects();
EffectRegistry MakeDefaultEffects();

}  // namespace ipstep
