#include "sim/default_effects.h"

#include "contact/contact_effects.h"

namespace ipstep {

EffectRegistry MakeDefaultEffects() {
  EffectRegistry registry;
  RegisterBuiltinEffects(&registry);
  RegisterContactEffects(&registry);
  return registry;
}

const EffectRegistry& DefaultEffects() {
  static const EffectRegistry* const registry = new EffectRegistry(MakeDefaultEffects());
  return *registry;
}

}  // namespace ipstep
