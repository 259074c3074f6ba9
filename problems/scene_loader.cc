#include "problems/scene_loader.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/input_error.h"
#include "core/input_file.h"
#include "core/input_limits.h"
#include "core/json_node.h"
#include "mesh/mesh_boundary.h"
#include "problems/solid_loader.h"  // "solid": elastic solids

namespace ipstep {
namespace internal {
// Built-in scene name -> JSON text. Defined in builtin_scenes.cc, which
// problems/CMakeLists.txt generates from problems/*.json.
const std::map<std::string, std::string>& BuiltinSceneTexts();
}  // namespace internal

namespace {

using nlohmann::json;

// Upper bound on the number of nodes, so that a typo such as "nx": 200000
// gives an error instead of exhausting memory.
constexpr int64_t kMaxNodes = limits::kMaxNodes;

// Upper bound on the size of a scene file (a 1000 x 1000 grid written out as
// explicit nodes and springs takes about 100 MB).
constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{256} << 20;

constexpr char kOneNodeSource[] =
    "give exactly one of \"nodes\", \"particle\", \"chain\", \"grid\", \"solid\"";

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

std::string Join(const std::vector<std::string>& items, const std::string& separator = ", ") {
  std::string joined;
  for (const std::string& item : items) {
    if (!joined.empty()) joined += separator;
    joined += item;
  }
  return joined;
}

double ReadPositive(const JsonNode& node) { return node.Positive(); }

double ReadInRange(const JsonNode& node, double min, double max, const std::string& unit,
                   bool min_open = false) {
  return node.InRange(min, max, unit, min_open);
}

double ReadStiffness(const JsonNode& node) {
  return ReadInRange(node, 0.0, limits::kMaxStiffness, "", /*min_open=*/true);
}

double ReadMass(const JsonNode& node) {
  return ReadInRange(node, limits::kMinMass, limits::kMaxMass, "kg");
}

int ReadIntInRange(const JsonNode& node, int64_t min, int64_t max) {
  return node.IntegerInRange(min, max);
}

SpringModel ReadSpringModel(const JsonNode& node) {
  const std::string name = node.String();
  for (SpringModel model :
       {SpringModel::kHookean, SpringModel::kSquaredStrain, SpringModel::kQuartic}) {
    if (name == SpringModelName(model)) return model;
  }
  node.Fail("unknown spring model " + Quoted(name) + " (known: hookean, squared_strain, quartic)");
}

// Removes nlohmann's "[json.exception.parse_error.101] " prefix and cuts the
// input it quotes ("last read: '...'", "number overflow parsing '...'").
std::string WithoutExceptionId(const std::string& message) {
  std::string text = message;
  if (!text.empty() && text.front() == '[') {
    const size_t end = text.find("] ");
    if (end != std::string::npos) text = text.substr(end + 2);
  }
  for (const char* marker : {"last read: '", "parsing '"}) {
    const size_t start = text.find(marker);
    const size_t end = text.rfind('\'');
    if (start == std::string::npos) continue;
    const size_t from = start + std::strlen(marker);
    if (end == std::string::npos || end < from) continue;
    text = text.substr(0, from) + ClipInput(text.substr(from, end - from)) + text.substr(end);
  }
  return ClipInput(text, 4 * kMaxEchoedInput);
}

// Follows the key path while nlohmann parses, so that parse errors can say
// where they happened, and rejects duplicate keys in an object (nlohmann would
// silently keep the last one).
class KeyPathTracker {
 public:
  explicit KeyPathTracker(const std::string& source) : source_(source) {}

  // The nlohmann parser callback.
  bool OnEvent(json::parse_event_t event, const json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        frames_.push_back(Frame{false, {}, 0, {}});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back(Frame{true, {}, 0, {}});
        break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) {
          throw InputError(source_, CurrentPath(), "duplicate key in the same object");
        }
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        [[fallthrough]];
      case json::parse_event_t::value:
        if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
        break;
    }
    return true;
  }

  // Key path of the value being read, e.g. "springs[2].stiffness".
  std::string CurrentPath() const {
    std::string path;
    for (const Frame& frame : frames_) {
      if (frame.is_array) {
        path += "[" + std::to_string(frame.index) + "]";
      } else {
        path += (path.empty() ? "" : ".") + frame.key;
      }
    }
    return path;
  }

 private:
  struct Frame {
    bool is_array;
    std::string key;  // current key (objects)
    size_t index;     // current element (arrays)
    std::set<std::string> keys;
  };

  const std::string& source_;
  std::vector<Frame> frames_;
};

// Reads a scene file: a regular file (not a directory, device or pipe such as
// /dev/zero, which never ends) of at most kMaxSceneFileBytes.
std::string ReadTextFile(const std::string& path) {
  namespace fs = std::filesystem;
  const std::string problem = InputFileProblem(path);
  if (!problem.empty()) throw InputError(path + ": cannot read scene file: " + problem);
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  const std::string too_large = path + ": cannot read scene file: larger than the limit of " +
                                std::to_string(kMaxSceneFileBytes >> 20) + " MiB";
  if (fs::exists(status) && fs::file_size(path, error) > kMaxSceneFileBytes && !error) {
    throw InputError(too_large);
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    throw InputError(path + ": cannot open scene file: " + std::strerror(errno));
  }
  // Read with the limit as well: the file may grow, or report no size (procfs).
  std::string text;
  std::vector<char> buffer(1 << 16);
  while (file.read(buffer.data(), static_cast<std::streamsize>(buffer.size())) ||
         file.gcount() > 0) {
    text.append(buffer.data(), static_cast<size_t>(file.gcount()));
    if (text.size() > kMaxSceneFileBytes) throw InputError(too_large);
  }
  if (file.bad()) throw InputError(path + ": cannot read scene file: " + std::strerror(errno));
  return text;
}

std::string BuiltinSource(const std::string& name) { return "problems/" + name + ".json"; }

std::string BuiltinNameList() {
  const std::set<std::string> names = BuiltinSceneNames();
  return Join(std::vector<std::string>(names.begin(), names.end()));
}

// Builds a Scene from a parsed JSON document, checking everything on the way.
class SceneParser {
 public:
  SceneParser(const std::string& source, const SceneLoadOptions& options)
      : source_(source), options_(options) {}

  Scene Parse(const json& document) {
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

 private:
  // What made the nodes; node names ("top_left", "last", ...) depend on it.
  enum class Layout { kExplicit, kParticle, kChain, kGrid, kSolid };

  int dim() const { return scene_.dimension; }
  int num_nodes() const { return scene_.num_nodes(); }

  void CheckExtraEffectNames(const JsonNode& root) const {
    for (const std::string& effect : options_.extra_effects) {
      if (effect.empty() || Contains(TopLevelKeys(), effect)) {
        root.FailAt("effects", "registered effect name " + Quoted(effect) +
                                   " is empty or clashes with a scene key");
      }
    }
  }

  void ReadHeader(const JsonNode& root) {
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

  void ReadEffects(const JsonNode& root) {
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
  void RequireEffect(const JsonNode& data, const std::string& effect) const {
    if (!scene_.HasEffect(effect)) {
      data.Fail("is given but " + Quoted(effect) + " is not listed in \"effects\"");
    }
  }

  // ---- Nodes -------------------------------------------------------------

  void ReadNodes(const JsonNode& root) {
    std::string source_key;
    for (const char* key : {"nodes", "particle", "chain", "grid", "solid"}) {
      if (!root.Has(key)) continue;
      if (!source_key.empty()) {
        root.FailAt(key, "conflicts with " + Quoted(source_key) + ": " + kOneNodeSource);
      }
      source_key = key;
    }
    if (source_key.empty()) {
      root.FailAt("nodes", std::string("no nodes: ") + kOneNodeSource);
    }
    if (options_.grid_size > 0 && source_key != "grid") {
      throw InputError("options", "SceneLoadOptions.grid_size",
                       "scene " + source_ + " has no \"grid\" whose size could be overridden");
    }
    const JsonNode generator = root.Get(source_key);
    if (source_key == "nodes") {
      ReadExplicitNodes(generator);
    } else if (source_key == "particle") {
      ReadParticle(generator);
    } else if (source_key == "chain") {
      ReadChain(generator);
    } else if (source_key == "solid") {
      ReadSolidNodes(generator);
    } else {
      ReadGrid(generator);
    }
    for (int i = 0; i < num_nodes(); ++i) {
      for (int k = 0; k < dim(); ++k) {
        if (!(std::abs(scene_.positions[dim() * i + k]) <= limits::kMaxCoordinate)) {
          generator.Fail("the position of node " + std::to_string(i) + " is outside " +
                         limits::RangeText(-limits::kMaxCoordinate, limits::kMaxCoordinate, "m") +
                         " (sizes or coordinates too large)");
        }
      }
    }
  }

  int AddNode(const std::vector<double>& position, double mass) {
    scene_.positions.insert(scene_.positions.end(), position.begin(), position.end());
    scene_.velocities.insert(scene_.velocities.end(), dim(), 0.0);
    scene_.masses.push_back(mass);
    velocity_paths_.emplace_back();
    return num_nodes() - 1;
  }

  // Gives node `index` its own initial velocity, read from `velocity`.
  void SetOwnVelocity(int index, const JsonNode& velocity) {
    const std::vector<double> v = velocity.Velocity(dim());
    std::copy(v.begin(), v.end(), scene_.velocities.begin() + dim() * index);
    velocity_paths_[index] = velocity.path();
  }

  // "solid": an elastic solid's mesh and material (problems/solid_loader.h).
  void ReadSolidNodes(const JsonNode& solid) {
    layout_ = Layout::kSolid;
    RequireEffect(solid, "elasticity");
    auto data = std::make_shared<Solid>(ReadSolid(solid.value(), dim(), source_, solid.path()));
    const std::vector<double>& masses = data->masses;  // lumped or uniform, range-checked
    for (int i = 0; i < data->mesh.num_nodes(); ++i) {
      const double* x = data->mesh.positions.data() + dim() * i;
      AddNode(std::vector<double>(x, x + dim()), masses[i]);
    }
    // The contact surface is the mesh's boundary: edges (2D) or triangles (3D).
    scene_.surface.declared = true;
    for (const std::array<int, 3>& facet : BoundaryFacets(data->mesh)) {
      if (dim() == 2) {
        scene_.surface.edges.push_back({facet[0], facet[1]});
      } else {
        scene_.surface.triangles.push_back(facet);
      }
    }
    scene_.solid = std::move(data);
  }

  // "particle": {"position": [...], "mass": m, "velocity": [...]}.
  void ReadParticle(const JsonNode& particle) {
    layout_ = Layout::kParticle;
    particle.ExpectObject({"position", "mass", "velocity"});
    const std::vector<double> position = particle.Get("position").Position(dim());
    AddNode(position, ReadMass(particle.Get("mass")));
    if (auto velocity = particle.Find("velocity")) SetOwnVelocity(0, *velocity);
  }

  // "nodes": {"positions": [...], "velocities": [...], "masses" | "mass" | "total_mass"}.
  void ReadExplicitNodes(const JsonNode& nodes) {
    layout_ = Layout::kExplicit;
    nodes.ExpectObject({"positions", "velocities", "masses", "mass", "total_mass"});
    const JsonNode positions = nodes.Get("positions");
    if (positions.value().is_array() &&
        static_cast<int64_t>(positions.value().size()) > kMaxNodes) {
      positions.Fail("lists more than " + std::to_string(kMaxNodes) + " nodes");
    }
    const std::vector<JsonNode> entries = positions.Elements();
    if (entries.empty()) positions.Fail("must list at least one node");
    const int count = static_cast<int>(entries.size());
    const std::vector<double> masses =
        ReadMasses(nodes, {"masses", "mass", "total_mass"}, 0, count);
    for (int i = 0; i < count; ++i) AddNode(entries[i].Position(dim()), masses[i]);
    if (auto velocities = nodes.Find("velocities")) {
      const std::vector<JsonNode> list = velocities->Elements();
      if (static_cast<int>(list.size()) != count) {
        velocities->Fail("must list one velocity per position (" + std::to_string(count) +
                         "), got " + std::to_string(list.size()));
      }
      for (int i = 0; i < count; ++i) SetOwnVelocity(i, list[i]);
    }
  }

  // The mass of each of `count` nodes from exactly one of the `keys` of
  // `object`: "masses" (one per node), "mass" (of each node), "total_mass"
  // (spread evenly) or "density" (per unit of `measure`, the chain's length or
  // the grid's area, spread evenly).
  std::vector<double> ReadMasses(const JsonNode& object, const std::vector<std::string>& keys,
                                 double measure, int64_t count) {
    const std::string one_of = "give exactly one of \"" + Join(keys, "\", \"") + "\"";
    std::optional<JsonNode> given;
    std::string key;
    for (const std::string& candidate : keys) {
      auto node = object.Find(candidate);
      if (!node) continue;
      if (given) node->Fail("conflicts with " + given->path() + ": " + one_of);
      given = node;
      key = candidate;
    }
    if (!given) object.FailAt(object.ChildPath(keys.front()), "missing: " + one_of);

    if (key == "masses") {
      const std::vector<JsonNode> list = given->Elements();
      if (static_cast<int64_t>(list.size()) != count) {
        given->Fail("must list one mass per node (" + std::to_string(count) + "), got " +
                    std::to_string(list.size()));
      }
      std::vector<double> masses;
      for (const JsonNode& mass : list) masses.push_back(ReadMass(mass));
      return masses;
    }
    if (key == "mass") return std::vector<double>(count, ReadMass(*given));
    const double value = ReadPositive(*given);
    double mass = value;
    if (key == "total_mass") mass = value / static_cast<double>(count);
    if (key == "density") mass = value * measure / static_cast<double>(count);
    if (!(mass >= limits::kMinMass && mass <= limits::kMaxMass)) {
      given->Fail("gives each node a mass of " + FormatNumber(mass) + " kg, which must be in " +
                  limits::RangeText(limits::kMinMass, limits::kMaxMass, "kg"));
    }
    return std::vector<double>(count, mass);
  }

  void ReadChain(const JsonNode& chain) {
    layout_ = Layout::kChain;
    chain.ExpectObject({"count", "from", "to", "mass", "total_mass", "density", "spring"});
    const int count = ReadIntInRange(chain.Get("count"), 2, kMaxNodes);
    const std::vector<double> from = chain.Get("from").Position(dim());
    const JsonNode to_node = chain.Get("to");
    const std::vector<double> to = to_node.Position(dim());
    double length = 0.0;
    for (int k = 0; k < dim(); ++k) length += (to[k] - from[k]) * (to[k] - from[k]);
    length = std::sqrt(length);
    if (!(length > 0) || !std::isfinite(length)) {
      to_node.Fail("must differ from chain.from and lie at a finite distance from it");
    }
    const std::vector<double> masses =
        ReadMasses(chain, {"mass", "total_mass", "density"}, length, count);
    for (int i = 0; i < count; ++i) {
      const double t = static_cast<double>(i) / (count - 1);
      std::vector<double> position(dim());
      for (int k = 0; k < dim(); ++k) position[k] = from[k] + t * (to[k] - from[k]);
      AddNode(position, masses[i]);
    }
    if (auto spring = chain.Find("spring")) {
      const SpringFamily family = ReadSpringFamily(*spring);
      for (int i = 0; i + 1 < count; ++i) AddGeneratedSpring(family, i, i + 1);
      // The chain's segments are its contact surface.
      for (int i = 0; i + 1 < count; ++i) scene_.surface.edges.push_back({i, i + 1});
    } else {
      for (int i = 0; i < count; ++i) scene_.surface.points.push_back(i);
    }
    scene_.surface.declared = true;
  }

  void ReadGrid(const JsonNode& grid) {
    layout_ = Layout::kGrid;
    grid.ExpectObject({"nx", "ny", "width", "height", "origin", "plane", "mass", "total_mass",
                       "density", "structural", "shear", "bending"});
    nx_ = ReadIntInRange(grid.Get("nx"), 2, kMaxNodes);
    ny_ = ReadIntInRange(grid.Get("ny"), 2, kMaxNodes);
    if (options_.grid_size > 0) {
      if (options_.grid_size < 2) {
        throw InputError("options", "SceneLoadOptions.grid_size",
                         "must be >= 2 to resize the grid of " + source_ + ", got " +
                             std::to_string(options_.grid_size));
      }
      nx_ = ny_ = options_.grid_size;
    }
    if (static_cast<int64_t>(nx_) * ny_ > kMaxNodes) {
      const std::string what = "nx * ny = " + std::to_string(static_cast<int64_t>(nx_) * ny_) +
                               " nodes exceeds the limit of " + std::to_string(kMaxNodes);
      if (options_.grid_size > 0)
        throw InputError("options", "SceneLoadOptions.grid_size", what + " in " + source_);
      grid.Fail(what);
    }
    const double width = ReadPositive(grid.Get("width"));
    const double height = ReadPositive(grid.Get("height"));
    std::vector<double> origin(dim(), 0.0);
    if (auto node = grid.Find("origin")) origin = node->Position(dim());

    // The grid spans axis u (columns, width) and axis v (rows, height).
    int u = 0;
    int v = 1;
    if (auto plane = grid.Find("plane")) {
      if (dim() != 3) plane->Fail("is only allowed when \"dimension\" is 3");
      const std::string name = plane->String();
      if (name == "xz") {
        v = 2;
      } else if (name == "yz") {
        u = 1;
        v = 2;
      } else if (name != "xy") {
        plane->Fail("must be \"xy\", \"xz\" or \"yz\", got " + Quoted(name));
      }
    }

    const std::vector<double> masses = ReadMasses(grid, {"mass", "total_mass", "density"},
                                                  width * height, static_cast<int64_t>(nx_) * ny_);
    const auto index_of = [this](int row, int col) { return row * nx_ + col; };
    // Row 0 is the top row, at the origin; rows go down (towards -v).
    for (int row = 0; row < ny_; ++row) {
      for (int col = 0; col < nx_; ++col) {
        std::vector<double> position = origin;
        position[u] += width * col / (nx_ - 1);
        position[v] -= height * row / (ny_ - 1);
        AddNode(position, masses[index_of(row, col)]);
      }
    }

    DeclareGridSurface(grid.Has("structural"));
    if (auto structural = grid.Find("structural")) {
      const SpringFamily family = ReadSpringFamily(*structural);
      for (int row = 0; row < ny_; ++row) {
        for (int col = 0; col + 1 < nx_; ++col) {
          AddGeneratedSpring(family, index_of(row, col), index_of(row, col + 1));
        }
      }
      for (int row = 0; row + 1 < ny_; ++row) {
        for (int col = 0; col < nx_; ++col) {
          AddGeneratedSpring(family, index_of(row, col), index_of(row + 1, col));
        }
      }
    }
    if (auto shear = grid.Find("shear")) {
      const SpringFamily family = ReadSpringFamily(*shear);
      for (int row = 0; row + 1 < ny_; ++row) {
        for (int col = 0; col + 1 < nx_; ++col) {
          AddGeneratedSpring(family, index_of(row, col), index_of(row + 1, col + 1));
          AddGeneratedSpring(family, index_of(row, col + 1), index_of(row + 1, col));
        }
      }
    }
    if (auto bending = grid.Find("bending")) {
      const SpringFamily family = ReadSpringFamily(*bending);
      for (int row = 0; row < ny_; ++row) {
        for (int col = 0; col + 2 < nx_; ++col) {
          AddGeneratedSpring(family, index_of(row, col), index_of(row, col + 2));
        }
      }
      for (int row = 0; row + 2 < ny_; ++row) {
        for (int col = 0; col < nx_; ++col) {
          AddGeneratedSpring(family, index_of(row, col), index_of(row + 2, col));
        }
      }
    }
  }

  // The grid's contact surface: with structural springs, its perimeter (2D)
  // or two triangles per cell (3D, split along the (row, col) -> (row + 1,
  // col + 1) diagonal); without, every node is a point.
  void DeclareGridSurface(bool connected) {
    Surface& surface = scene_.surface;
    surface.declared = true;
    const auto id = [this](int row, int col) { return row * nx_ + col; };
    if (!connected) {
      for (int i = 0; i < num_nodes(); ++i) surface.points.push_back(i);
    } else if (dim() == 2) {
      for (int col = 0; col + 1 < nx_; ++col) {
        surface.edges.push_back({id(0, col), id(0, col + 1)});
        surface.edges.push_back({id(ny_ - 1, col), id(ny_ - 1, col + 1)});
      }
      for (int row = 0; row + 1 < ny_; ++row) {
        surface.edges.push_back({id(row, 0), id(row + 1, 0)});
        surface.edges.push_back({id(row, nx_ - 1), id(row + 1, nx_ - 1)});
      }
    } else {
      for (int row = 0; row + 1 < ny_; ++row) {
        for (int col = 0; col + 1 < nx_; ++col) {
          surface.triangles.push_back({id(row, col), id(row + 1, col), id(row + 1, col + 1)});
          surface.triangles.push_back({id(row, col), id(row + 1, col + 1), id(row, col + 1)});
        }
      }
    }
  }

  // ---- Surface -------------------------------------------------------------

  // "surface": {"edges": [[i, j], ...], "triangles": [[i, j, k], ...],
  // "points": [i, ...]} (triangles in 3D only); replaces a generator's.
  void ReadSurface(const JsonNode& root) {
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

  // ---- Springs -----------------------------------------------------------

  // A generated family of springs: {"model": ..., "stiffness": ...}.
  struct SpringFamily {
    std::string path;
    SpringModel model;
    double stiffness;
  };

  SpringFamily ReadSpringFamily(const JsonNode& node) {
    RequireEffect(node, "springs");
    node.ExpectObject({"model", "stiffness"});
    return SpringFamily{node.path(), ReadSpringModel(node.Get("model")),
                        ReadStiffness(node.Get("stiffness"))};
  }

  double Distance(int i, int j) const {
    double squared = 0.0;
    for (int k = 0; k < dim(); ++k) {
      const double d = scene_.positions[dim() * j + k] - scene_.positions[dim() * i + k];
      squared += d * d;
    }
    return std::sqrt(squared);
  }

  void AddGeneratedSpring(const SpringFamily& family, int i, int j) {
    const double length = Distance(i, j);
    if (!(length >= limits::kMinLength && length <= limits::kMaxLength)) {
      throw InputError(source_, family.path,
                       "the spring between nodes " + std::to_string(i) + " and " +
                           std::to_string(j) + " would have rest length " + FormatNumber(length) +
                           " m; it must be in " +
                           limits::RangeText(limits::kMinLength, limits::kMaxLength, "m"));
    }
    scene_.springs.push_back(Spring{i, j, family.model, family.stiffness, length});
  }

  void ReadSprings(const JsonNode& root) {
    if (auto springs = root.Find("springs")) {
      RequireEffect(*springs, "springs");
      for (const JsonNode& entry : springs->Elements()) ReadSpring(entry);
    }
    if (scene_.HasEffect("springs") && scene_.springs.empty()) {
      root.FailAt(effect_paths_.at("springs"),
                  "lists \"springs\" but the scene defines no springs");
    }
  }

  void ReadSpring(const JsonNode& entry) {
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
        entry.FailAt(entry.ChildPath("rest_length"),
                     "is required: the initial length is not finite");
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

  // ---- Node references ---------------------------------------------------

  // A node reference: an index, or a name for generated layouts. Returns the
  // nodes it names (a row name names several).
  std::vector<int> ReadNodeReference(const JsonNode& reference) const {
    const json& value = reference.value();
    if (value.is_string()) return NamedNodes(reference, value.get<std::string>());
    if (!value.is_number_integer()) {
      reference.Fail("must be a node index (integer) or a node name (string), got " +
                     Describe(value));
    }
    const int64_t index = reference.Integer();
    if (index < 0 || index >= num_nodes()) {
      reference.Fail("node index " + std::to_string(index) + " is out of range: the scene has " +
                     std::to_string(num_nodes()) + " nodes (0 to " +
                     std::to_string(num_nodes() - 1) + ")");
    }
    return {static_cast<int>(index)};
  }

  int ReadSingleNode(const JsonNode& reference) const {
    const std::vector<int> nodes = ReadNodeReference(reference);
    if (nodes.size() != 1) reference.Fail("must name a single node, not a row or column");
    return nodes.front();
  }

  std::vector<int> NamedNodes(const JsonNode& reference, const std::string& name) const {
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

  // ---- Effects -----------------------------------------------------------

  void ReadGravity(const JsonNode& root) {
    if (auto gravity = root.Find("gravity")) {
      RequireEffect(*gravity, "gravity");
      scene_.gravity = gravity->Vector(dim(), limits::kMaxAcceleration, "m/s^2");
    } else if (scene_.HasEffect("gravity")) {
      root.FailAt("gravity", "is missing but \"effects\" lists \"gravity\" (" +
                                 effect_paths_.at("gravity") + ")");
    }
  }

  void ReadDamping(const JsonNode& root) {
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

  void ReadEffectParameters(const JsonNode& root) {
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

  // ---- Initial and boundary conditions ------------------------------------

  void ReadInitialVelocity(const JsonNode& root) {
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

  void ReadPinned(const JsonNode& root) {
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

  void ReadMoving(const JsonNode& root) {
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
  MovingNode ReadMotion(const JsonNode& entry) const {
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
  void FinishVelocities() {
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

}  // namespace

Scene ParseScene(const std::string& text, const std::string& source,
                 const SceneLoadOptions& options) {
  // nlohmann stops at a NUL byte as at the end of the input, which would
  // accept a valid scene followed by anything; JSON text never contains one.
  const size_t nul = text.find('\0');
  if (nul != std::string::npos) {
    throw InputError(source + ": malformed JSON: NUL byte at offset " + std::to_string(nul) +
                     " (a JSON text cannot contain one)");
  }
  KeyPathTracker tracker(source);
  json document;
  try {
    document = json::parse(text, [&tracker](int, json::parse_event_t event, json& parsed) {
      return tracker.OnEvent(event, parsed);
    });
  } catch (const json::parse_error& error) {
    const std::string path = tracker.CurrentPath();
    throw InputError(source + ": malformed JSON" +
                     (path.empty() ? "" : " (near " + ClipInput(path) + ")") + ": " +
                     WithoutExceptionId(error.what()));
  } catch (const json::out_of_range& error) {
    // A number such as 1e400, read as the value at CurrentPath().
    throw InputError(source, tracker.CurrentPath(),
                     "number out of the range of a double: " + WithoutExceptionId(error.what()));
  } catch (const json::exception& error) {
    throw InputError(source + ": malformed JSON: " + WithoutExceptionId(error.what()));
  }
  return ParseScene(document, source, options);
}

Scene ParseScene(const nlohmann::json& document, const std::string& source,
                 const SceneLoadOptions& options) {
  try {
    return SceneParser(source, options).Parse(document);
  } catch (const nlohmann::json::exception& error) {
    // Not expected (every access is checked first); keeps the promise that bad
    // input only ever raises InputError.
    throw InputError(source + ": " + WithoutExceptionId(error.what()));
  }
}

Scene LoadSceneFile(const std::string& path, const SceneLoadOptions& options) {
  return ParseScene(ReadTextFile(path), path, options);
}

std::set<std::string> BuiltinSceneNames() {
  std::set<std::string> names;
  for (const auto& entry : internal::BuiltinSceneTexts()) names.insert(entry.first);
  return names;
}

bool IsBuiltinScene(const std::string& name) {
  return internal::BuiltinSceneTexts().count(name) != 0;
}

std::string BuiltinSceneText(const std::string& name) {
  const auto& texts = internal::BuiltinSceneTexts();
  const auto found = texts.find(name);
  if (found == texts.end()) {
    throw InputError(ClipInput(name) +
                     ": unknown built-in scene (built-in scenes: " + BuiltinNameList() + ")");
  }
  return found->second;
}

Scene LoadScene(const std::string& name_or_path, const SceneLoadOptions& options) {
  if (name_or_path.empty()) {
    throw InputError("scene: the name is empty: give a built-in scene (" + BuiltinNameList() +
                     ") or a JSON file");
  }
  if (IsBuiltinScene(name_or_path)) {
    return ParseScene(BuiltinSceneText(name_or_path), BuiltinSource(name_or_path), options);
  }
  std::error_code error;
  if (std::filesystem::exists(name_or_path, error)) return LoadSceneFile(name_or_path, options);
  throw InputError(ClipInput(name_or_path) +
                   ": no such scene file, and not a built-in scene (built-in scenes: " +
                   BuiltinNameList() + ")");
}

}  // namespace ipstep
