// Nodes by reference (problems/scene_parser.h): indices and names (a chain's,
// a grid's, a solid's node sets), and what is set on them: "pinned",
// "moving", "initial_velocity", and the velocities pins and motions imply.
#include "problems/scene_parser.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "problems/solid.h"

namespace ipstep {
namespace internal {
namespace {

using nlohmann::json;

}  // namespace

// A node reference: an index, or a name for generated layouts. Returns the
// nodes it names (a row name names several).
std::vector<int> SceneParser::ReadNodeReference(const JsonNode& reference) const {
  const json& value = reference.value();
  if (value.is_string()) return NamedNodes(reference, value.get<std::string>());
  if (!value.is_number_integer()) {
    reference.Fail("must be a node index (integer) or a node name (string), got " +
                   Describe(value));
  }
  const int64_t index = reference.Integer();
  if (index < 0 || index >= num_nodes()) {
    reference.Fail("node index " + std::to_string(index) + " is out of range: the scene has " +
                   std::to_string(num_nodes()) + " nodes (0 to " + std::to_string(num_nodes() - 1) +
                   ")");
  }
  return {static_cast<int>(index)};
}

int SceneParser::ReadSingleNode(const JsonNode& reference) const {
  const std::vector<int> nodes = ReadNodeReference(reference);
  if (nodes.size() != 1) reference.Fail("must name a single node, not a row or column");
  return nodes.front();
}

std::vector<int> SceneParser::NamedNodes(const JsonNode& reference, const std::string& name) const {
  std::map<std::string, std::vector<int>> names;
  if (layout_ == Layout::kChain) {
    names = {{"first", {0}}, {"last", {num_nodes() - 1}}};
  } else if (layout_ == Layout::kGrid) {
    const int last_row = (ny_ - 1) * nx_;
    names = {{"top_left", {0}},
             {"top_right", {nx_ - 1}},
             {"bottom_left", {last_row}},
             {"bottom_right", {last_row + nx_ - 1}}};
    for (int col = 0; col < nx_; ++col) {
      names["top_row"].push_back(col);
      names["bottom_row"].push_back(last_row + col);
    }
    for (int row = 0; row < ny_; ++row) {
      names["left_column"].push_back(row * nx_);
      names["right_column"].push_back(row * nx_ + nx_ - 1);
    }
  } else if (layout_ == Layout::kSolid) {
    names = scene_.solid->mesh.node_sets;
  } else {
    reference.Fail("node names such as " + Quoted(name) +
                   " need a \"chain\" or \"grid\" generator; use a node index");
  }
  const auto found = names.find(name);
  if (found == names.end()) {
    std::vector<std::string> known;
    for (const auto& entry : names) known.push_back(entry.first);
    reference.Fail("unknown node name " + Quoted(name) + " (known: " + Join(known) + ")");
  }
  return found->second;
}

void SceneParser::ReadInitialVelocity(const JsonNode& root) {
  auto velocity = root.Find("initial_velocity");
  if (!velocity) return;
  const std::vector<double> v = velocity->Velocity(dim());
  bool used = false;
  for (int i = 0; i < num_nodes(); ++i) {
    if (!velocity_paths_[i].empty()) continue;  // a node's own velocity wins
    std::copy(v.begin(), v.end(), scene_.velocities.begin() + dim() * i);
    used = true;
  }
  if (!used) velocity->Fail("has no effect: every node has a velocity of its own");
}

void SceneParser::ReadPinned(const JsonNode& root) {
  auto pinned = root.Find("pinned");
  if (!pinned) return;
  for (const JsonNode& entry : pinned->Elements()) {
    for (int node : ReadNodeReference(entry)) {
      if (pinned_by_.count(node) != 0) {
        entry.Fail("node " + std::to_string(node) + " is already pinned by " + pinned_by_[node]);
      }
      pinned_by_[node] = entry.path();
      scene_.pinned.push_back(node);
    }
  }
}

void SceneParser::ReadMoving(const JsonNode& root) {
  auto moving = root.Find("moving");
  if (!moving) return;
  for (const JsonNode& entry : moving->Elements()) {
    entry.ExpectObject({"node", "velocity", "angular_velocity", "center", "until"});
    const JsonNode reference = entry.Get("node");
    const std::vector<int> nodes = ReadNodeReference(reference);
    MovingNode motion = ReadMotion(entry);
    for (int node : nodes) {
      if (pinned_by_.count(node) != 0) {
        reference.Fail("node " + std::to_string(node) + " is pinned by " + pinned_by_[node] +
                       "; a node cannot be both pinned and moving");
      }
      if (moving_by_.count(node) != 0) {
        reference.Fail("node " + std::to_string(node) + " is already moving by " +
                       moving_by_[node]);
      }
      moving_by_[node] = entry.path();
      motion.node = node;
      scene_.moving.push_back(motion);
    }
  }
}

// A moving entry's rigid motion (problems/scene.h MovingNode): a velocity,
// an angular velocity about a centre, or both; optionally until a time.
MovingNode SceneParser::ReadMotion(const JsonNode& entry) const {
  MovingNode motion;
  if (!entry.Has("velocity") && !entry.Has("angular_velocity")) {
    entry.Fail(
        "a moving entry needs \"velocity\", \"angular_velocity\" (with \"center\") "
        "or both");
  }
  motion.velocity = std::vector<double>(dim(), 0.0);
  if (auto velocity = entry.Find("velocity")) motion.velocity = velocity->Velocity(dim());
  if (auto omega = entry.Find("angular_velocity")) {
    if (dim() == 2) {
      motion.angular_velocity = {
          omega->InRange(-limits::kMaxAngularVelocity, limits::kMaxAngularVelocity, "rad/s")};
    } else {
      motion.angular_velocity = omega->Vector(3, limits::kMaxAngularVelocity, "rad/s");
    }
    motion.center = entry.Get("center").Position(dim());
  } else if (entry.Has("center")) {
    entry.Get("center").Fail("a centre without \"angular_velocity\" has no effect");
  }
  if (auto until = entry.Find("until")) {
    motion.until = until->InRange(0.0, limits::kMaxDuration, "s", /*min_open=*/true);
  }
  return motion;
}

// Pinned nodes rest and moving nodes move at their prescribed velocity; a
// node's own nonzero "velocity" would contradict that.
void SceneParser::FinishVelocities() {
  const auto set_velocity = [this](int node, const std::vector<double>& velocity,
                                   const std::string& reason) {
    double* v = scene_.velocities.data() + dim() * node;
    if (!velocity_paths_[node].empty()) {
      for (int k = 0; k < dim(); ++k) {
        if (v[k] != velocity[k]) {
          throw InputError(source_, velocity_paths_[node],
                           "node " + std::to_string(node) + " is " + reason +
                               ", which sets its velocity; remove this velocity");
        }
      }
    }
    std::copy(velocity.begin(), velocity.end(), v);
  };
  const std::vector<double> zero(dim(), 0.0);
  for (const auto& [node, path] : pinned_by_) set_velocity(node, zero, "pinned by " + path);
  for (const MovingNode& moving : scene_.moving) {
    Eigen::Vector3d x0 = Eigen::Vector3d::Zero();
    for (int k = 0; k < dim(); ++k) x0[k] = scene_.positions[dim() * moving.node + k];
    const Eigen::Vector3d v0 = MotionOf(moving, dim()).Velocity(x0, 0.0);
    set_velocity(moving.node, std::vector<double>(v0.data(), v0.data() + dim()),
                 "moving by " + moving_by_[moving.node]);
  }
}

}  // namespace internal
}  // namespace ipstep
