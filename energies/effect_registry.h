// Effects are named families of energy terms ("springs", "damping", ...). A
// scene lists the effects it calls for and only those are built. Built-in
// effects are registered in energies/builtin_effects.cc; a program or test adds
// its own with EffectRegistry::Global().Register(...) before loading scenes.
#pragma once

#include <functional>
#include <map>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "energies/term_builder.h"

namespace ipstep {

// Adds the effect's terms. `parameters` is the scene's top-level object under
// the effect's name (null when absent). Returns a one-line summary for the
// "active effects" report. Throws InputError for bad parameters.
using EffectFactory =
    std::function<std::string(TermBuilder& builder, const nlohmann::json& parameters)>;

struct EffectInfo {
  std::string name;
  std::string description;
  EffectFactory factory;
};

class EffectRegistry {
 public:
  // The process-wide registry, with the built-in effects already registered.
  static EffectRegistry& Global();

  // Throws std::invalid_argument if the name is taken or empty.
  void Register(const std::string& name, const std::string& description, EffectFactory factory);
  bool Has(const std::string& name) const;
  const EffectInfo& Get(const std::string& name) const;
  std::set<std::string> Names() const;
  // Effects whose parameters are a top-level scene object under the effect's
  // name: every effect but gravity, springs and damping, which the scene loader
  // reads natively. Pass them as SceneLoadOptions::extra_effects.
  std::set<std::string> UserNames() const;

 private:
  std::map<std::string, EffectInfo> effects_;
  std::set<std::string> loader_native_;  // gravity, springs, damping
  friend void RegisterBuiltinEffects(EffectRegistry* registry);
};

void RegisterBuiltinEffects(EffectRegistry* registry);

}  // namespace ipstep
