// Effects are named families of energy terms ("springs", "damping", ...). A
// scene lists the effects it calls for and only those are built. A registry is
// an object the program owns: sim/default_effects.h gives the default one
// (gravity, springs, damping from energies/builtin_effects.cc, contact and
// friction from contact/contact_effects.h); a program adds its own effects to a
// copy and hands it to the simulation (SimulationOptions::effects) and the
// scene loader (SceneLoadOptions::extra_effects = registry.UserNames()).
// Effects read their parameters with core/json_node.h. A built effect is an
// Effect object (energies/effect.h) the simulation keeps.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "energies/effect.h"
#include "energies/term_builder.h"

namespace ipstep {

// Adds the effect's terms. `parameters` is the scene's top-level object under
// the effect's name (null when absent). Returns the built effect (its Summary
// is the line of the "active effects" report). Throws InputError for bad
// parameters.
using EffectFactory =
    std::function<std::unique_ptr<Effect>(TermBuilder& builder, const nlohmann::json& parameters)>;
// The same for an effect that leaves nothing but its summary line behind
// (registered as a SummaryEffect).
using SummaryEffectFactory =
    std::function<std::string(TermBuilder& builder, const nlohmann::json& parameters)>;

struct EffectInfo {
  std::string name;
  std::string description;
  EffectFactory factory;
  // Effects this one works with when the scene lists them (friction: contact):
  // they are built before it whatever the order of the scene's "effects".
  std::vector<std::string> needs;
};

class EffectRegistry {
 public:
  // Throws std::invalid_argument if the name is taken or empty.
  void Register(const std::string& name, const std::string& description, EffectFactory factory,
                std::vector<std::string> needs = {});
  void Register(const std::string& name, const std::string& description,
                SummaryEffectFactory factory);
  bool Has(const std::string& name) const;
  const EffectInfo& Get(const std::string& name) const;
  std::set<std::string> Names() const;
  // Effects whose parameters are a top-level scene object under the effect's
  // name: every effect but those the scene loader reads natively
  // (SceneNativeEffects(), problems/scene.h). Pass them as
  // SceneLoadOptions::extra_effects.
  std::set<std::string> UserNames() const;

 private:
  std::map<std::string, EffectInfo> effects_;
};

// Registers the effects the scene loader reads natively: gravity, springs,
// damping (energies/builtin_effects.cc).
void RegisterBuiltinEffects(EffectRegistry* registry);

}  // namespace ipstep
