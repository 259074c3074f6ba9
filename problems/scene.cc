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

PrescribedMotion MotionOf(const MovingNode& moving, int dimension) {
  PrescribedMotion motion;
  for (int k = 0; k < dimension && k < static_cast<int>(moving.velocity.size()); ++k) {
    motion.velocity[k] = moving.velocity[k];
  }
  if (moving.angular_velocity.size() == 1) {
    motion.angular_velocity[2] = moving.angular_velocity[0];  // 2D: about z
  } else {
    for (int k = 0; k < static_cast<int>(moving.angular_velocity.size()) && k < 3; ++k) {
      motion.angular_velocity[k] = moving.angular_velocity[k];
    }
  }
  for (int k = 0; k < dimension && k < static_cast<int>(moving.center.size()); ++k) {
    motion.center[k] = moving.center[k];
  }
  motion.until = moving.until;
  return motion;
}

}  // namespace ipstep
