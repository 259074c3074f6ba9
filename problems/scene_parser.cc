// The top level of a scene (problems/scene_parser.h): the allowed keys, the
// header ("name", "dimension", "time_step", "steps"), "effects" and the data
// of effects ("gravity", "damping", user effects' parameters), and the order
// in which SceneParser reads the rest.
#include "problems/scene_parser.h"

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/input_limits.h"

namespace ipstep {
namespace internal {
namespace {

using nlohmann::json;

const std::vector<std::string>& BuiltinEffects() { return SceneNativeEffects(); }

const std::vector<std::string>& TopLevelKeys() {
  static const auto* const keys =
      new std::vector<std::string>{"name",   "description", "dimension", "time_step",
                                   "steps",  "effects",     "nodes",     "particle",
                                   "chain",  "grid",        "springs",   "pinned",
                                   "moving", "gravity",     "damping",   "initial_velocity",
                                   "surface"};
  return *keys;
}

bool Contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

Scene SceneParser::Parse(const json& document) {
  const JsonNode root(document, "", source_);
  CheckExtraEffectNames(root);
  std::vector<std::string> allowed = TopLevelKeys();
  allowed.push_back("solid");  // an elastic solid (problems/solid_loader.h)
  allowed.insert(allowed.end(), options_.extra_effects.begin(), options_.extra_effects.end());
  root.ExpectObject(allowed);

  scene_.source = source_;
  ReadHeader(root);
  ReadEffects(root);
  ReadNodes(root);
  ReadSprings(root);
  ReadSurface(root);
  ReadGravity(root);
  ReadDamping(root);
  ReadEffectParameters(root);
  ReadInitialVelocity(root);
  ReadPinned(root);
  ReadMoving(root);
  FinishVelocities();
  return std::move(scene_);
}

void SceneParser::CheckExtraEffectNames(const JsonNode& root) const {
  for (const std::string& effect : options_.extra_effects) {
    if (effect.empty() || Contains(TopLevelKeys(), effect)) {
      root.FailAt("effects", "registered effect name " + Quoted(effect) +
                                 " is empty or clashes with a scene key");
    }
  }
}

void SceneParser::ReadHeader(const JsonNode& root) {
  if (auto name = root.Find("name")) {
    scene_.name = name->String();
    if (scene_.name.empty()) name->Fail("must not be empty");
  } else {
    scene_.name = std::filesystem::path(source_).stem().string();
    if (scene_.name.empty()) scene_.name = "scene";
  }
  if (auto description = root.Find("description")) description->String();
  if (auto dimension = root.Find("dimension")) {
    scene_.dimension = ReadIntInRange(*dimension, 2, 3);
  }
  if (auto time_step = root.Find("time_step")) {
    scene_.time_step = ReadInRange(*time_step, limits::kMinTimeStep, limits::kMaxTimeStep, "s");
  }
  if (auto steps = root.Find("steps")) {
    scene_.steps = ReadIntInRange(*steps, 0, limits::kMaxSteps);
  }
}

void SceneParser::ReadEffects(const JsonNode& root) {
  auto effects = root.Find("effects");
  if (!effects) return;
  for (const JsonNode& entry : effects->Elements()) {
    const std::string effect = entry.String();
    if (!Contains(BuiltinEffects(), effect) && options_.extra_effects.count(effect) == 0) {
      std::vector<std::string> known = BuiltinEffects();
      known.insert(known.end(), options_.extra_effects.begin(), options_.extra_effects.end());
      entry.Fail("unknown effect " + Quoted(effect) + " (known effects: " + Join(known) + ")");
    }
    if (effect_paths_.count(effect) != 0) {
      entry.Fail("effect " + Quoted(effect) + " is already listed at " + effect_paths_[effect]);
    }
    effect_paths_[effect] = entry.path();
    scene_.effects.push_back(effect);
  }
}

// Data that only makes sense with `effect` requires it in "effects".
void SceneParser::RequireEffect(const JsonNode& data, const std::string& effect) const {
  if (!scene_.HasEffect(effect)) {
    data.Fail("is given but " + Quoted(effect) + " is not listed in \"effects\"");
  }
}

void SceneParser::ReadGravity(const JsonNode& root) {
  if (auto gravity = root.Find("gravity")) {
    RequireEffect(*gravity, "gravity");
    scene_.gravity = gravity->Vector(dim(), limits::kMaxAcceleration, "m/s^2");
  } else if (scene_.HasEffect("gravity")) {
    root.FailAt("gravity", "is missing but \"effects\" lists \"gravity\" (" +
                               effect_paths_.at("gravity") + ")");
  }
}

void SceneParser::ReadDamping(const JsonNode& root) {
  auto damping = root.Find("damping");
  if (!damping) {
    if (scene_.HasEffect("damping")) {
      root.FailAt("damping", "is missing but \"effects\" lists \"damping\" (" +
                                 effect_paths_.at("damping") + ")");
    }
    return;
  }
  RequireEffect(*damping, "damping");
  damping->ExpectObject({"mass_proportional", "stiffness_proportional"});
  if (auto alpha = damping->Find("mass_proportional")) {
    scene_.damping.mass_proportional = ReadInRange(*alpha, 0.0, limits::kMaxMassDamping, "1/s");
  }
  if (auto beta = damping->Find("stiffness_proportional")) {
    scene_.damping.stiffness_proportional =
        ReadInRange(*beta, 0.0, limits::kMaxStiffnessDamping, "s");
    if (scene_.damping.stiffness_proportional > 0 && !scene_.HasEffect("springs")) {
      beta->Fail("has no effect without the \"springs\" effect");
    }
  }
}

void SceneParser::ReadEffectParameters(const JsonNode& root) {
  for (const std::string& effect : options_.extra_effects) {
    auto parameters = root.Find(effect);
    if (!parameters) continue;
    RequireEffect(*parameters, effect);
    if (!parameters->value().is_object()) {
      parameters->Fail("must be an object holding the parameters of effect " + Quoted(effect) +
                       ", got " + Describe(parameters->value()));
    }
    scene_.effect_parameters[effect] = parameters->value();
  }
}

}  // namespace internal
}  // namespace ipstep
