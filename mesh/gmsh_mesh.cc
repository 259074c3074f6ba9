#include "mesh/gmsh_mesh.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <gmsh.h>

#include "mesh/mesh_boundary.h"

namespace ipstep {
namespace {

// The one place that initialises and finalises Gmsh. Gmsh's API functions
// throw on errors once initialised (General.AbortOnError); they are turned
// into std::runtime_error with Gmsh's last error message.
class GmshSession {
 public:
  GmshSession() : lock_(Mutex()) {
    gmsh::initialize(0, nullptr, /*readConfigFiles=*/false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  // Runs f; any exception Gmsh throws becomes a runtime_error with `what`.
  template <class F>
  static void Run(const std::string& what, F&& f) {
    try {
      f();
    } catch (const std::runtime_error&) {
      throw;
    } catch (...) {
      std::string error;
      try {
        gmsh::logger::getLastError(error);
      } catch (...) {
      }
      throw std::runtime_error(what + (error.empty() ? "" : ": " + error));
    }
  }

 private:
  static std::mutex& Mutex() {
    static std::mutex mutex;
    return mutex;
  }
  std::lock_guard<std::mutex> lock_;
};

// The current model's elements of `dimension` as a SimplexMesh.
SimplexMesh ExtractMesh(int dimension, const std::string& what) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, dimension, -1);
  const int expected = dimension == 2 ? 2 : 4;  // MSH types: 3-node triangle, 4-node tetrahedron
  const char* expected_name = dimension == 2 ? "3-node triangles" : "4-node tetrahedra";
  if (types.empty()) {
    throw std::runtime_error(what + " has no " + std::to_string(dimension) +
                             "D elements (expected " + expected_name + ")");
  }
  std::string type_names;
  for (int type : types) {
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
    type_names += (type_names.empty() ? "" : ", ") + name;
  }
  if (types.size() > 1) {
    throw std::runtime_error(what + " mixes element types (" + type_names + "): only linear " +
                             expected_name + " are supported");
  }
  for (int type : types) {
    if (type == expected) continue;
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, local, primary);
    throw std::runtime_error(what + " has " + name + " elements (order " + std::to_string(order) +
                             ")" + ": only linear " + expected_name + " are supported");
  }
  SimplexMesh mesh;
  mesh.dimension = dimension;
  std::map<std::size_t, int> index;  // Gmsh node tag -> node index
  const std::vector<std::size_t>& tags = node_tags[0];
  for (std::size_t tag : tags) index.emplace(tag, 0);
  int next = 0;
  for (auto& entry : index) entry.second = next++;
  mesh.positions.assign(static_cast<size_t>(dimension) * next, 0.0);
  std::vector<bool> found(next, false);
  std::vector<std::size_t> all_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(all_tags, coords, parametric, -1, -1, false, false);
  for (size_t i = 0; i < all_tags.size(); ++i) {
    const auto it = index.find(all_tags[i]);
    if (it == index.end()) continue;
    for (int k = 0; k < dimension; ++k)
      mesh.positions[dimension * it->second + k] = coords[3 * i + k];
    if (dimension == 2 && coords[3 * i + 2] != 0.0) {
      throw std::runtime_error(what + ": node " + std::to_string(all_tags[i]) +
                               " is not in the z = 0 plane (a 2D mesh must be)");
    }
    found[it->second] = true;
  }
  if (std::find(found.begin(), found.end(), false) != found.end()) {
    throw std::runtime_error(what + ": an element refers to a node that is not defined");
  }
  const int corners = dimension + 1;
  for (size_t e = 0; e * corners < tags.size(); ++e) {
    std::array<int, 4> element = {-1, -1, -1, -1};
    for (int a = 0; a < corners; ++a) element[a] = index.at(tags[e * corners + a]);
    mesh.elements.push_back(element);
  }
  OrientPositively(&mesh);

  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, -1);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    std::vector<std::size_t> group_tags;
    std::vector<double> group_coords;
    gmsh::model::mesh::getNodesForPhysicalGroup(dim, tag, group_tags, group_coords);
    std::vector<int>& set = mesh.node_sets[name];
    for (std::size_t t : group_tags) {
      const auto it = index.find(t);
      if (it != index.end()) set.push_back(it->second);
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  AddStandardNodeSets(&mesh);
  return mesh;
}

// Builds and meshes the shape in the current model, with its physical groups.
void MeshShape(const GmshShape& s) {
  const int d = s.dimension;
  gmsh::model::add("ipstep");
  int tag = 0;
  if (s.name == "rectangle") {
    tag = gmsh::model::occ::addRectangle(s.origin[0], s.origin[1], 0.0, s.size[0], s.size[1]);
  } else if (s.name == "disk") {
    tag = gmsh::model::occ::addDisk(s.origin[0], s.origin[1], 0.0, s.radius, s.radius);
  } else if (s.name == "box") {
    tag = gmsh::model::occ::addBox(s.origin[0], s.origin[1], s.origin[2], s.size[0], s.size[1],
                                   s.size[2]);
  } else if (s.name == "ball") {
    tag = gmsh::model::occ::addSphere(s.origin[0], s.origin[1], s.origin[2], s.radius);
  } else {
    throw std::runtime_error("unknown shape \"" + s.name + "\"");
  }
  gmsh::model::occ::synchronize();
  const int domain = gmsh::model::addPhysicalGroup(d, {tag});
  gmsh::model::setPhysicalName(d, domain, "domain");
  if (s.name == "rectangle" || s.name == "box") {
    gmsh::vectorpair sides;
    gmsh::model::getBoundary({{d, tag}}, sides, false, false, false);
    const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
    const double tolerance = 1e-5 * std::max({s.size[0], s.size[1], d == 3 ? s.size[2] : 0.0});
    for (const auto& [side_dim, side] : sides) {
      double lo[3], hi[3];
      gmsh::model::getBoundingBox(side_dim, side, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
      for (int k = 0; k < d; ++k) {
        if (hi[k] - lo[k] > tolerance) continue;  // not normal to axis k
        const bool at_min = std::abs(lo[k] - s.origin[k]) < 10.0 * tolerance;
        const int group = gmsh::model::addPhysicalGroup(side_dim, {side});
        gmsh::model::setPhysicalName(side_dim, group, names[k][at_min ? 0 : 1]);
      }
    }
  }
  gmsh::option::setNumber("Mesh.MeshSizeMax", s.element_size);
  gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
  gmsh::model::mesh::generate(d);
}

}  // namespace

SimplexMesh GmshGenerate(const GmshShape& shape) {
  GmshSession session;
  SimplexMesh mesh;
  GmshSession::Run("Gmsh", [&] {
    MeshShape(shape);
    mesh = ExtractMesh(shape.dimension, "the Gmsh " + shape.name);
  });
  return mesh;
}

void GmshWriteShape(const GmshShape& shape, const std::string& path, double version) {
  GmshSession session;
  GmshSession::Run("Gmsh could not write " + path, [&] {
    MeshShape(shape);
    gmsh::option::setNumber("Mesh.MshFileVersion", version);
    gmsh::write(path);
  });
}

SimplexMesh GmshRead(const std::string& path, int dimension) {
  {
    std::ifstream probe(path);
    if (!probe) throw std::runtime_error("cannot open mesh file " + path);
  }
  GmshSession session;
  SimplexMesh mesh;
  GmshSession::Run("Gmsh could not read " + path, [&] {
    gmsh::open(path);
    mesh = ExtractMesh(dimension, path);
  });
  return mesh;
}

}  // namespace ipstep
