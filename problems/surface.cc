// A scene's "surface" (problems/scene_parser.h): the contact surface's edges,
// triangles and points, declared in the scene or left to the node source.
#include "problems/scene_parser.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace ipstep {
namespace internal {

// "surface": {"edges": [[i, j], ...], "triangles": [[i, j, k], ...],
// "points": [i, ...]} (triangles in 3D only); replaces a generator's.
void SceneParser::ReadSurface(const JsonNode& root) {
  auto surface = root.Find("surface");
  if (!surface) {
    if (layout_ == Layout::kParticle) {
      scene_.surface.points = {0};
      scene_.surface.declared = true;
    } else if (layout_ == Layout::kExplicit && scene_.springs.empty()) {
      // Unconnected nodes: each is a particle.
      for (int i = 0; i < num_nodes(); ++i) scene_.surface.points.push_back(i);
      scene_.surface.declared = true;
    }
    return;
  }
  RequireEffect(*surface, "contact");
  surface->ExpectObject({"edges", "triangles", "points"});
  Surface declared;
  declared.declared = true;
  const auto read_entry = [&](const JsonNode& entry, int size) {
    const std::vector<JsonNode> items = entry.Elements();
    if (static_cast<int>(items.size()) != size) {
      entry.Fail("must list " + std::to_string(size) + " node indices");
    }
    std::vector<int> nodes;
    for (const JsonNode& item : items) {
      const int64_t node = item.Integer();
      if (node < 0 || node >= num_nodes()) {
        item.Fail("node index " + std::to_string(node) + " out of range [0, " +
                  std::to_string(num_nodes()) + ")");
      }
      if (std::find(nodes.begin(), nodes.end(), node) != nodes.end()) {
        entry.Fail("repeats node " + std::to_string(node));
      }
      nodes.push_back(static_cast<int>(node));
    }
    return nodes;
  };
  // An edge or triangle listed twice (its nodes in any order) would be in
  // contact twice over; it is an error naming both entries.
  std::map<std::vector<int>, std::string> seen;  // sorted nodes -> first entry
  const auto check_repeat = [&](const JsonNode& entry, std::vector<int> nodes) {
    std::sort(nodes.begin(), nodes.end());
    const auto [it, inserted] = seen.emplace(nodes, entry.path());
    if (!inserted) entry.Fail("repeats " + it->second + " (the same nodes)");
  };
  if (auto edges = surface->Find("edges")) {
    for (const JsonNode& entry : edges->Elements()) {
      const std::vector<int> n = read_entry(entry, 2);
      check_repeat(entry, n);
      declared.edges.push_back({n[0], n[1]});
    }
  }
  if (auto triangles = surface->Find("triangles")) {
    if (dim() != 3) triangles->Fail("are only allowed when \"dimension\" is 3");
    for (const JsonNode& entry : triangles->Elements()) {
      const std::vector<int> n = read_entry(entry, 3);
      check_repeat(entry, n);
      declared.triangles.push_back({n[0], n[1], n[2]});
    }
  }
  if (auto points = surface->Find("points")) {
    for (const JsonNode& entry : points->Elements()) {
      const int64_t node = entry.Integer();
      if (node < 0 || node >= num_nodes()) {
        entry.Fail("node index " + std::to_string(node) + " out of range [0, " +
                   std::to_string(num_nodes()) + ")");
      }
      declared.points.push_back(static_cast<int>(node));
    }
  }
  if (declared.edges.empty() && declared.triangles.empty() && declared.points.empty()) {
    surface->Fail("declares no edges, triangles or points");
  }
  scene_.surface = std::move(declared);
}

}  // namespace internal
}  // namespace ipstep
