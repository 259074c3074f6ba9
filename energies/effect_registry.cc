#include "energies/effect_registry.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "problems/scene.h"

namespace ipstep {

void EffectRegistry::Register(const std::string& name, const std::string& description,
                              EffectFactory factory, std::vector<std::string> needs) {
  if (name.empty()) throw std::invalid_argument("effect name must not be empty");
  if (effects_.count(name)) throw std::invalid_argument("effect '" + name + "' already registered");
  if (!factory) throw std::invalid_argument("effect '" + name + "' has no factory");
  effects_[name] = EffectInfo{name, description, std::move(factory), std::move(needs)};
}

void EffectRegistry::Register(const std::string& name, const std::string& description,
                              SummaryEffectFactory factory) {
  if (!factory) throw std::invalid_argument("effect '" + name + "' has no factory");
  Register(name, description,
           [factory = std::move(factory)](
               TermBuilder& builder, const nlohmann::json& parameters) -> std::unique_ptr<Effect> {
             return std::make_unique<SummaryEffect>(factory(builder, parameters));
           });
}

bool EffectRegistry::Has(const std::string& name) const { return effects_.count(name) > 0; }

const EffectInfo& EffectRegistry::Get(const std::string& name) const {
  auto it = effects_.find(name);
  if (it == effects_.end()) throw std::invalid_argument("unknown effect '" + name + "'");
  return it->second;
}

std::set<std::string> EffectRegistry::Names() const {
  std::set<std::string> names;
  for (const auto& [name, info] : effects_) names.insert(name);
  return names;
}

std::set<std::string> EffectRegistry::UserNames() const {
  std::set<std::string> names;
  for (const auto& [name, info] : effects_) {
    const std::vector<std::string>& native = SceneNativeEffects();
    if (std::find(native.begin(), native.end(), name) == native.end()) names.insert(name);
  }
  return names;
}

}  // namespace ipstep
