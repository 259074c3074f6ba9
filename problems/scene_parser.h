// The scene reader behind problems/scene_loader.h (not an interface of its
// own): SceneParser builds a Scene from a parsed JSON document, checking
// everything on the way. Its steps live by concept: the top level (header,
// effects and their data) in scene_parser.cc, the node sources (the
// generators particle, chain and grid, explicit nodes, the solid) in
// generators.cc, the contact surface in surface.cc, springs in springs.cc,
// node references, pins, moving nodes and velocities in node_sets.cc.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/json_node.h"
#include "problems/scene.h"
#include "problems/scene_loader.h"

namespace ipstep {
namespace internal {

inline std::string Join(const std::vector<std::string>& items,
                        const std::string& separator = ", ") {
  std::string joined;
  for (const std::string& item : items) {
    if (!joined.empty()) joined += separator;
    joined += item;
  }
  return joined;
}

inline double ReadInRange(const JsonNode& node, double min, double max, const std::string& unit,
                          bool min_open = false) {
  return node.InRange(min, max, unit, min_open);
}

inline int ReadIntInRange(const JsonNode& node, int64_t min, int64_t max) {
  return node.IntegerInRange(min, max);
}

// Builds a Scene from a parsed JSON document, checking everything on the way.
class SceneParser {
 public:
  SceneParser(const std::string& source, const SceneLoadOptions& options)
      : source_(source), options_(options) {}

  Scene Parse(const nlohmann::json& document);

 private:
  // What made the nodes; node names ("top_left", "last", ...) depend on it.
  enum class Layout { kExplicit, kParticle, kChain, kGrid, kSolid };

  // A generated family of springs: {"model": ..., "stiffness": ...}.
  struct SpringFamily {
    std::string path;
    SpringModel model;
    double stiffness;
  };

  int dim() const { return scene_.dimension; }
  int num_nodes() const { return scene_.num_nodes(); }

  // ---- Top level, effects and their data (scene_parser.cc) ----------------
  void CheckExtraEffectNames(const JsonNode& root) const;
  void ReadHeader(const JsonNode& root);
  void ReadEffects(const JsonNode& root);
  void RequireEffect(const JsonNode& data, const std::string& effect) const;
  void ReadGravity(const JsonNode& root);
  void ReadDamping(const JsonNode& root);
  void ReadEffectParameters(const JsonNode& root);

  // ---- Nodes (generators.cc) ----------------------------------------------
  void ReadNodes(const JsonNode& root);
  int AddNode(const std::vector<double>& position, double mass);
  void SetOwnVelocity(int index, const JsonNode& velocity);
  void ReadSolidNodes(const JsonNode& solid);
  void ReadParticle(const JsonNode& particle);
  void ReadExplicitNodes(const JsonNode& nodes);
  std::vector<double> ReadMasses(const JsonNode& object, const std::vector<std::string>& keys,
                                 double measure, int64_t count);
  void ReadChain(const JsonNode& chain);
  void ReadGrid(const JsonNode& grid);
  void DeclareGridSurface(bool connected);

  // ---- Surface (surface.cc) -----------------------------------------------
  void ReadSurface(const JsonNode& root);

  // ---- Springs (springs.cc) -----------------------------------------------
  SpringFamily ReadSpringFamily(const JsonNode& node);
  double Distance(int i, int j) const;
  void AddGeneratedSpring(const SpringFamily& family, int i, int j);
  void ReadSprings(const JsonNode& root);
  void ReadSpring(const JsonNode& entry);

  // ---- Node references, initial and boundary conditions (node_sets.cc) ----
  std::vector<int> ReadNodeReference(const JsonNode& reference) const;
  int ReadSingleNode(const JsonNode& reference) const;
  std::vector<int> NamedNodes(const JsonNode& reference, const std::string& name) const;
  void ReadInitialVelocity(const JsonNode& root);
  void ReadPinned(const JsonNode& root);
  void ReadMoving(const JsonNode& root);
  MovingNode ReadMotion(const JsonNode& entry) const;
  void FinishVelocities();

  const std::string& source_;
  const SceneLoadOptions& options_;
  Scene scene_;
  Layout layout_ = Layout::kExplicit;
  int nx_ = 0;                                       // grid columns
  int ny_ = 0;                                       // grid rows
  std::map<std::string, std::string> effect_paths_;  // effect -> "effects[k]"
  std::vector<std::string> velocity_paths_;          // per node: key of its own velocity
  std::map<int, std::string> pinned_by_;             // node -> "pinned[k]"
  std::map<int, std::string> moving_by_;             // node -> "moving[k]"
};

}  // namespace internal
}  // namespace ipstep
