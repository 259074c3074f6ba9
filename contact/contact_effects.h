// Registration of the "contact" and "friction" effects (docs/contact.md).
#pragma once

#include "energies/effect_registry.h"

namespace ipstep {

void RegisterContactEffects(EffectRegistry* registry);

}  // namespace ipstep
