#include "problems/scene.h"

#include <algorithm>

namespace ipstep {

const char* SpringModelName(SpringModel model) {
  switch (model) {
    case SpringModel::kHookean:
      return "hookean";
    case SpringModel::kSquaredStrain:
      return "squared_strain";
    case SpringModel::kQuartic:
      return "quartic";
  }
  return "unknown";
}

const std::vector<std::string>& SceneNativeEffects() {
  static const auto* const effects = new std::vector<std::string>{"gravity", "springs", "damping"};
  return *effects;
}

bool Scene::HasEffect(const std::string& effect) const {
  return std::find(effects.begin(), effects.end(), effect) != effects.end();
}

}  // namespace ipstep
