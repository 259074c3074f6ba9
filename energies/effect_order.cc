#include "energies/effect_order.h"

#include "core/input_error.h"

namespace ipstep {

std::vector<size_t> EffectBuildOrder(const EffectRegistry& registry,
                                     const std::vector<std::string>& effects,
                                     const std::string& source) {
  std::vector<size_t> order;
  std::vector<bool> placed(effects.size(), false);
  while (order.size() < effects.size()) {
    const size_t before = order.size();
    // The first effect in scene order whose listed needs are all placed.
    for (size_t i = 0; i < effects.size() && order.size() == before; ++i) {
      if (placed[i]) continue;
      bool ready = true;
      for (const std::string& need : registry.Get(effects[i]).needs) {
        for (size_t j = 0; j < effects.size(); ++j) {
          if (effects[j] == need && !placed[j]) ready = false;
        }
      }
      if (ready) {
        placed[i] = true;
        order.push_back(i);
      }
    }
    if (order.size() == before) {
      throw InputError(source, "effects",
                       "the effects need each other in a cycle (EffectInfo::needs)");
    }
  }
  return order;
}

}  // namespace ipstep
