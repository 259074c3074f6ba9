#include "python/bindings.h"
#include "sim/default_effects.h"

namespace ipstep::python {

EffectRegistry& Effects() {
  static EffectRegistry registry = MakeDefaultEffects();
  return registry;
}

}  // namespace ipstep::python
