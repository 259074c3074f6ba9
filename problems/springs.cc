// A scene's springs (problems/scene_parser.h): the families a generator
// makes ({"model", "stiffness"}) and the explicit "springs" entries.
#include "problems/scene_parser.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/input_limits.h"

namespace ipstep {
namespace internal {
namespace {

double ReadStiffness(const JsonNode& node) {
  return ReadInRange(node, 0.0, limits::kMaxStiffness, "", /*min_open=*/true);
}

SpringModel ReadSpringModel(const JsonNode& node) {
  const std::string name = node.String();
  for (SpringModel model :
       {SpringModel::kHookean, SpringModel::kSquaredStrain, SpringModel::kQuartic}) {
    if (name == SpringModelName(model)) return model;
  }
  node.Fail("unknown spring model " + Quoted(name) + " (known: hookean, squared_strain, quartic)");
}

}  // namespace

SceneParser::SpringFamily SceneParser::ReadSpringFamily(const JsonNode& node) {
  RequireEffect(node, "springs");
  node.ExpectObject({"model", "stiffness"});
  return SpringFamily{node.path(), ReadSpringModel(node.Get("model")),
                      ReadStiffness(node.Get("stiffness"))};
}

double SceneParser::Distance(int i, int j) const {
  double squared = 0.0;
  for (int k = 0; k < dim(); ++k) {
    const double d = scene_.positions[dim() * j + k] - scene_.positions[dim() * i + k];
    squared += d * d;
  }
  return std::sqrt(squared);
}

void SceneParser::AddGeneratedSpring(const SpringFamily& family, int i, int j) {
  const double length = Distance(i, j);
  if (!(length >= limits::kMinLength && length <= limits::kMaxLength)) {
    throw InputError(source_, family.path,
                     "the spring between nodes " + std::to_string(i) + " and " + std::to_string(j) +
                         " would have rest length " + FormatNumber(length) + " m; it must be in " +
                         limits::RangeText(limits::kMinLength, limits::kMaxLength, "m"));
  }
  scene_.springs.push_back(Spring{i, j, family.model, family.stiffness, length});
}

void SceneParser::ReadSprings(const JsonNode& root) {
  if (auto springs = root.Find("springs")) {
    RequireEffect(*springs, "springs");
    for (const JsonNode& entry : springs->Elements()) ReadSpring(entry);
  }
  if (scene_.HasEffect("springs") && scene_.springs.empty()) {
    root.FailAt(effect_paths_.at("springs"), "lists \"springs\" but the scene defines no springs");
  }
}

void SceneParser::ReadSpring(const JsonNode& entry) {
  entry.ExpectObject({"nodes", "model", "stiffness", "rest_length"});
  const JsonNode nodes = entry.Get("nodes");
  const std::vector<JsonNode> ends = nodes.Elements();
  if (ends.size() != 2) nodes.Fail("must list exactly 2 nodes, got " + Describe(nodes.value()));
  Spring spring;
  spring.i = ReadSingleNode(ends[0]);
  spring.j = ReadSingleNode(ends[1]);
  if (spring.i == spring.j) {
    nodes.Fail("must name two different nodes, got node " + std::to_string(spring.i) + " twice");
  }
  spring.model = ReadSpringModel(entry.Get("model"));
  spring.stiffness = ReadStiffness(entry.Get("stiffness"));
  if (auto rest_length = entry.Find("rest_length")) {
    spring.rest_length = ReadInRange(*rest_length, limits::kMinLength, limits::kMaxLength, "m");
  } else {
    spring.rest_length = Distance(spring.i, spring.j);
    if (!(spring.rest_length > 0)) {
      entry.FailAt(entry.ChildPath("rest_length"),
                   "is required: nodes " + std::to_string(spring.i) + " and " +
                       std::to_string(spring.j) + " start at the same position");
    }
    if (!std::isfinite(spring.rest_length)) {
      entry.FailAt(entry.ChildPath("rest_length"), "is required: the initial length is not finite");
    }
    if (!(spring.rest_length >= limits::kMinLength && spring.rest_length <= limits::kMaxLength)) {
      entry.FailAt(entry.ChildPath("rest_length"),
                   "the initial distance of nodes " + std::to_string(spring.i) + " and " +
                       std::to_string(spring.j) + " is " + FormatNumber(spring.rest_length) +
                       " m; a rest length must be in " +
                       limits::RangeText(limits::kMinLength, limits::kMaxLength, "m"));
    }
  }
  scene_.springs.push_back(spring);
}

}  // namespace internal
}  // namespace ipstep
