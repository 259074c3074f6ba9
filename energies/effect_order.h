// The order a scene's effects are built in: the scene's, except that an
// effect comes after those it needs (EffectInfo::needs, energies/
// effect_registry.h) that the scene lists, so that friction finds contact
// whatever the order of "effects".
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "energies/effect_registry.h"

namespace ipstep {

// Indices into `effects` (each registered in `registry`), in build order.
// Throws InputError naming `source`'s "effects" when they need each other in
// a cycle.
std::vector<size_t> EffectBuildOrder(const EffectRegistry& registry,
                                     const std::vector<std::string>& effects,
                                     const std::string& source);

}  // namespace ipstep
