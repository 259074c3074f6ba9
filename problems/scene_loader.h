// Reading scenes from JSON with strict validation. Every problem with the
// input (unreadable file, malformed JSON, unknown key, wrong type, non-finite or
// out-of-range number, bad node index, data without its effect) throws one
// ipstep::InputError whose message names the file and the key.
// The format is documented key by key in docs/scenes.md.
#pragma once

#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "problems/scene.h"

namespace ipstep {

struct SceneLoadOptions {
  // Names of user-registered effects accepted in "effects" in addition to the
  // built-in ones; each may have a top-level object of parameters under its name.
  std::set<std::string> extra_effects;
  // When > 0, overrides the size of a "grid" generator: nx = ny = grid_size.
  int grid_size = 0;
};

// Parses `text` as a scene; `source` names it in error messages.
Scene ParseScene(const std::string& text, const std::string& source,
                 const SceneLoadOptions& options = {});
Scene ParseScene(const nlohmann::json& json, const std::string& source,
                 const SceneLoadOptions& options = {});

// Reads a scene file.
Scene LoadSceneFile(const std::string& path, const SceneLoadOptions& options = {});

// Built-in scenes (compiled into the library from problems/*.json).
std::set<std::string> BuiltinSceneNames();
bool IsBuiltinScene(const std::string& name);
// The JSON text of a built-in scene; throws InputError for an unknown name.
std::string BuiltinSceneText(const std::string& name);

// `name_or_path` is either a built-in scene name ("oscillator") or a path to a
// JSON file.
Scene LoadScene(const std::string& name_or_path, const SceneLoadOptions& options = {});

}  // namespace ipstep
