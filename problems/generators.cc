// A scene's nodes (problems/scene_parser.h): exactly one node source, the
// generators "particle", "chain" and "grid" (positions, masses, the springs
// and contact surface they generate) or explicit "nodes" or a "solid"
// (problems/solid_loader.h).
#include "problems/scene_parser.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "mesh/mesh_boundary.h"
#include "problems/solid_loader.h"  // "solid": elastic solids

namespace ipstep {
namespace internal {
namespace {

// Upper bound on the number of nodes, so that a typo such as "nx": 200000
// gives an error instead of exhausting memory.
constexpr int64_t kMaxNodes = limits::kMaxNodes;

constexpr char kOneNodeSource[] =
    "give exactly one of \"nodes\", \"particle\", \"chain\", \"grid\", \"solid\"";

double ReadPositive(const JsonNode& node) { return node.Positive(); }

double ReadMass(const JsonNode& node) {
  return ReadInRange(node, limits::kMinMass, limits::kMaxMass, "kg");
}

}  // namespace

void SceneParser::ReadNodes(const JsonNode& root) {
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

int SceneParser::AddNode(const std::vector<double>& position, double mass) {
  scene_.positions.insert(scene_.positions.end(), position.begin(), position.end());
  scene_.velocities.insert(scene_.velocities.end(), dim(), 0.0);
  scene_.masses.push_back(mass);
  velocity_paths_.emplace_back();
  return num_nodes() - 1;
}

// Gives node `index` its own initial velocity, read from `velocity`.
void SceneParser::SetOwnVelocity(int index, const JsonNode& velocity) {
  const std::vector<double> v = velocity.Velocity(dim());
  std::copy(v.begin(), v.end(), scene_.velocities.begin() + dim() * index);
  velocity_paths_[index] = velocity.path();
}

// "solid": an elastic solid's mesh and material (problems/solid_loader.h).
void SceneParser::ReadSolidNodes(const JsonNode& solid) {
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
void SceneParser::ReadParticle(const JsonNode& particle) {
  layout_ = Layout::kParticle;
  particle.ExpectObject({"position", "mass", "velocity"});
  const std::vector<double> position = particle.Get("position").Position(dim());
  AddNode(position, ReadMass(particle.Get("mass")));
  if (auto velocity = particle.Find("velocity")) SetOwnVelocity(0, *velocity);
}

// "nodes": {"positions": [...], "velocities": [...], "masses" | "mass" | "total_mass"}.
void SceneParser::ReadExplicitNodes(const JsonNode& nodes) {
  layout_ = Layout::kExplicit;
  nodes.ExpectObject({"positions", "velocities", "masses", "mass", "total_mass"});
  const JsonNode positions = nodes.Get("positions");
  if (positions.value().is_array() && static_cast<int64_t>(positions.value().size()) > kMaxNodes) {
    positions.Fail("lists more than " + std::to_string(kMaxNodes) + " nodes");
  }
  const std::vector<JsonNode> entries = positions.Elements();
  if (entries.empty()) positions.Fail("must list at least one node");
  const int count = static_cast<int>(entries.size());
  const std::vector<double> masses = ReadMasses(nodes, {"masses", "mass", "total_mass"}, 0, count);
  for (int i = 0; i < count; ++i) AddNode(entries[i].Position(dim()), masses[i]);
  if (auto velocities = nodes.Find("velocities")) {
    const std::vector<JsonNode> list = velocities->Elements();
    if (static_cast<int>(list.size()) != count) {
      velocities->Fail("must list one velocity per position (" + std::to_string(count) + "), got " +
                       std::to_string(list.size()));
    }
    for (int i = 0; i < count; ++i) SetOwnVelocity(i, list[i]);
  }
}

// The mass of each of `count` nodes from exactly one of the `keys` of
// `object`: "masses" (one per node), "mass" (of each node), "total_mass"
// (spread evenly) or "density" (per unit of `measure`, the chain's length or
// the grid's area, spread evenly).
std::vector<double> SceneParser::ReadMasses(const JsonNode& object,
                                            const std::vector<std::string>& keys, double measure,
                                            int64_t count) {
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

void SceneParser::ReadChain(const JsonNode& chain) {
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

void SceneParser::ReadGrid(const JsonNode& grid) {
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
void SceneParser::DeclareGridSurface(bool connected) {
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

}  // namespace internal
}  // namespace ipstep
