#include "sim/default_effects.h"

#include "contact/contact_effects.h"
#include "energies/elasticity/elasticity_effect.h"

namespace ipstep {

EffectRegistry MakeDefaultEffects() {
  EffectRegistry registry;
  RegisterBuiltinEffects(&registry);
  registry.Register("elasticity", "elastic solids: FEM triangles/tetrahedra of the \"solid\"",
                    BuildElasticity);
  RegisterContactEffects(&registry);
  return registry;
}

const EffectRegistry& DefaultEffects() {
  static const EffectRegistry* const registry = new EffectRegistry(MakeDefaultEffects());
  return *registry;
}

}  // namespace ipstep
