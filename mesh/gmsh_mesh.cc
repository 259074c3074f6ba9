#include "mesh/gmsh_mesh.h"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

#include <gmshc.h>  // declarations only: the library is loaded on first use

#include "core/input_file.h"
#include "mesh/mesh_boundary.h"

namespace ipstep {
namespace {

// Gmsh's C API, loaded with dlopen on first use rather than linked: libgmsh
// pulls in OpenCASCADE and ~100 shared libraries whose loading took 0.28 s at
// the start of every program (program_input_test, which starts the program 160
// times, went from 19 s to 115 s), scenes without a Gmsh mesh included. The
// function types come from gmshc.h, so a signature mismatch does not compile.
struct GmshApi {
// clang-format off
#define IPSTEP_GMSH_FUNCTIONS(X)                                                          \
  X(Free) X(Initialize) X(Finalize) X(OptionSetNumber) X(Open) X(Write) X(ModelAdd)       \
  X(ModelOccAddRectangle) X(ModelOccAddDisk) X(ModelOccAddBox) X(ModelOccAddSphere)     \
  X(ModelOccSynchronize) X(ModelAddPhysicalGroup) X(ModelSetPhysicalName)                \
  X(ModelGetBoundary) X(ModelGetBoundingBox) X(ModelMeshGenerate) X(ModelMeshGetElements) \
  X(ModelMeshGetElementProperties) X(ModelMeshGetNodes) X(ModelGetPhysicalGroups)        \
  X(ModelGetPhysicalName) X(ModelMeshGetNodesForPhysicalGroup) X(LoggerGetLastError)       \
  X(ModelMeshGetElementTypes)
// clang-format on
#define IPSTEP_GMSH_MEMBER(name) decltype(&gmsh##name) name = nullptr;
  IPSTEP_GMSH_FUNCTIONS(IPSTEP_GMSH_MEMBER)
#undef IPSTEP_GMSH_MEMBER
  std::string error;  // empty when loaded
};

const GmshApi& Api() {
  static const GmshApi api = [] {
    GmshApi a;
    void* handle = dlopen(IPSTEP_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* why = dlerror();
      a.error = std::string("cannot load Gmsh (" IPSTEP_GMSH_LIBRARY "): ") + (why ? why : "");
      return a;
    }
#define IPSTEP_GMSH_LOAD(name)                                                   \
  a.name = reinterpret_cast<decltype(&gmsh##name)>(dlsym(handle, "gmsh" #name)); \
  if (a.name == nullptr && a.error.empty()) a.error = "Gmsh lacks gmsh" #name;
    IPSTEP_GMSH_FUNCTIONS(IPSTEP_GMSH_LOAD)
#undef IPSTEP_GMSH_LOAD
    return a;  // never unloaded: Gmsh keeps static state
  }();
  if (!api.error.empty()) throw std::runtime_error(api.error);
  return api;
}

// Throws Gmsh's last error when a call set `ierr`.
void Check(int ierr, const std::string& what) {
  if (ierr == 0) return;
  std::string message = what;
  char* error = nullptr;
  int ignored = 0;
  Api().LoggerGetLastError(&error, &ignored);
  if (error != nullptr) {
    if (error[0] != '\0') message += ": " + std::string(error);
    Api().Free(error);
  }
  throw std::runtime_error(message);
}

// An array Gmsh allocated, freed with gmshFree.
template <typename T>
struct GmshArray {
  GmshArray() = default;
  GmshArray(const GmshArray&) = delete;
  GmshArray& operator=(const GmshArray&) = delete;
  ~GmshArray() {
    if (data != nullptr) Api().Free(data);
  }
  T* data = nullptr;
  size_t size = 0;
};

std::string TakeString(char* text) {
  std::string s = text != nullptr ? text : "";
  if (text != nullptr) Api().Free(text);
  return s;
}

// The one place that initialises and finalises Gmsh, under one mutex, with
// its terminal output off.
class GmshSession {
 public:
  explicit GmshSession(const std::string& what) : lock_(Mutex()), what_(what) {
    int ierr = 0;
    Api().Initialize(0, nullptr, /*readConfigFiles=*/0, &ierr);
    Check(ierr, what_);
    Api().OptionSetNumber("General.Terminal", 0, &ierr);
    Api().OptionSetNumber("General.Verbosity", 0, &ierr);
    Check(ierr, what_);
  }
  ~GmshSession() {
    int ierr = 0;
    Api().Finalize(&ierr);
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  // Checks a call's error code.
  void operator()(int ierr) const { Check(ierr, what_); }

 private:
  static std::mutex& Mutex() {
    static std::mutex mutex;
    return mutex;
  }
  std::lock_guard<std::mutex> lock_;
  std::string what_;
};

std::string ElementTypeName(int type, const GmshSession& check, int* order) {
  char* name = nullptr;
  int dim = 0, nodes = 0, primary = 0, ierr = 0;
  GmshArray<double> local;
  Api().ModelMeshGetElementProperties(type, &name, &dim, order, &nodes, &local.data, &local.size,
                                      &primary, &ierr);
  check(ierr);
  return TakeString(name);
}

// The current model's elements of `dimension` as a SimplexMesh.
SimplexMesh ExtractMesh(int dimension, const std::string& what, const GmshSession& check) {
  const GmshApi& api = Api();
  int ierr = 0;
  GmshArray<int> types;
  size_t** element_tags = nullptr;
  size_t* element_tags_n = nullptr;
  size_t element_tags_nn = 0;
  size_t** node_tags = nullptr;
  size_t* node_tags_n = nullptr;
  size_t node_tags_nn = 0;
  api.ModelMeshGetElements(&types.data, &types.size, &element_tags, &element_tags_n,
                           &element_tags_nn, &node_tags, &node_tags_n, &node_tags_nn, dimension, -1,
                           &ierr);
  check(ierr);
  // Copy the first type's node tags and free everything Gmsh allocated.
  std::vector<std::size_t> tags;
  if (node_tags_nn > 0) tags.assign(node_tags[0], node_tags[0] + node_tags_n[0]);
  for (size_t k = 0; k < element_tags_nn; ++k) api.Free(element_tags[k]);
  for (size_t k = 0; k < node_tags_nn; ++k) api.Free(node_tags[k]);
  api.Free(element_tags);
  api.Free(element_tags_n);
  api.Free(node_tags);
  api.Free(node_tags_n);

  if (dimension == 2) {
    // A 3D mesh read by a 2D scene would silently give its z = 0 triangles.
    GmshArray<int> solid_types;
    api.ModelMeshGetElementTypes(&solid_types.data, &solid_types.size, 3, -1, &ierr);
    check(ierr);
    if (solid_types.size > 0) {
      throw std::runtime_error(what + " has 3D elements: a 2D scene needs a 2D mesh (" +
                               "3-node triangles only)");
    }
  }
  const int expected = dimension == 2 ? 2 : 4;  // MSH types: 3-node triangle, 4-node tetrahedron
  const char* expected_name = dimension == 2 ? "3-node triangles" : "4-node tetrahedra";
  if (types.size == 0) {
    throw std::runtime_error(what + " has no " + std::to_string(dimension) +
                             "D elements (expected " + expected_name + ")");
  }
  std::string type_names;
  for (size_t k = 0; k < types.size; ++k) {
    int order = 0;
    type_names += (type_names.empty() ? "" : ", ") + ElementTypeName(types.data[k], check, &order);
  }
  if (types.size > 1) {
    throw std::runtime_error(what + " mixes element types (" + type_names + "): only linear " +
                             expected_name + " are supported");
  }
  if (types.data[0] != expected) {
    int order = 0;
    const std::string name = ElementTypeName(types.data[0], check, &order);
    throw std::runtime_error(what + " has " + name + " elements (order " + std::to_string(order) +
                             "): only linear " + expected_name + " are supported");
  }
  SimplexMesh mesh;
  mesh.dimension = dimension;
  std::map<std::size_t, int> index;  // Gmsh node tag -> node index
  for (std::size_t tag : tags) index.emplace(tag, 0);
  int next = 0;
  for (auto& entry : index) entry.second = next++;
  mesh.positions.assign(static_cast<size_t>(dimension) * next, 0.0);
  std::vector<bool> found(next, false);
  {
    GmshArray<std::size_t> all_tags;
    GmshArray<double> coords, parametric;
    api.ModelMeshGetNodes(&all_tags.data, &all_tags.size, &coords.data, &coords.size,
                          &parametric.data, &parametric.size, -1, -1, 0, 0, &ierr);
    check(ierr);
    for (size_t i = 0; i < all_tags.size; ++i) {
      const auto it = index.find(all_tags.data[i]);
      if (it == index.end()) continue;
      for (int k = 0; k < dimension; ++k) {
        mesh.positions[dimension * it->second + k] = coords.data[3 * i + k];
      }
      if (dimension == 2 && coords.data[3 * i + 2] != 0.0) {
        throw std::runtime_error(what + ": node " + std::to_string(all_tags.data[i]) +
                                 " is not in the z = 0 plane (a 2D mesh must be)");
      }
      found[it->second] = true;
    }
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

  GmshArray<int> groups;
  api.ModelGetPhysicalGroups(&groups.data, &groups.size, -1, &ierr);
  check(ierr);
  for (size_t g = 0; g + 1 < groups.size; g += 2) {
    const int dim = groups.data[g], tag = groups.data[g + 1];
    char* raw_name = nullptr;
    api.ModelGetPhysicalName(dim, tag, &raw_name, &ierr);
    check(ierr);
    std::string name = TakeString(raw_name);
    if (name.empty()) name = "physical_" + std::to_string(dim) + "_" + std::to_string(tag);
    GmshArray<std::size_t> group_tags;
    GmshArray<double> group_coords;
    api.ModelMeshGetNodesForPhysicalGroup(dim, tag, &group_tags.data, &group_tags.size,
                                          &group_coords.data, &group_coords.size, &ierr);
    check(ierr);
    std::vector<int>& set = mesh.node_sets[name];
    for (size_t i = 0; i < group_tags.size; ++i) {
      const auto it = index.find(group_tags.data[i]);
      if (it != index.end()) set.push_back(it->second);
    }
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  AddStandardNodeSets(&mesh);
  return mesh;
}

// Builds and meshes the shape in the current model, with its physical groups.
void MeshShape(const GmshShape& s, const GmshSession& check) {
  const GmshApi& api = Api();
  const int d = s.dimension;
  int ierr = 0;
  api.ModelAdd("ipstep", &ierr);
  check(ierr);
  int tag = 0;
  if (s.name == "rectangle") {
    tag = api.ModelOccAddRectangle(s.origin[0], s.origin[1], 0.0, s.size[0], s.size[1], -1, 0.0,
                                   &ierr);
  } else if (s.name == "disk") {
    tag = api.ModelOccAddDisk(s.origin[0], s.origin[1], 0.0, s.radius, s.radius, -1, &ierr);
  } else if (s.name == "box") {
    tag = api.ModelOccAddBox(s.origin[0], s.origin[1], s.origin[2], s.size[0], s.size[1], s.size[2],
                             -1, &ierr);
  } else if (s.name == "ball") {
    tag = api.ModelOccAddSphere(s.origin[0], s.origin[1], s.origin[2], s.radius, -1, -M_PI / 2,
                                M_PI / 2, 2 * M_PI, &ierr);
  } else {
    throw std::runtime_error("unknown shape \"" + s.name + "\"");
  }
  check(ierr);
  api.ModelOccSynchronize(&ierr);
  check(ierr);
  const auto add_group = [&](int dim, int entity, const char* name) {
    const int group = api.ModelAddPhysicalGroup(dim, &entity, 1, -1, &ierr);
    check(ierr);
    api.ModelSetPhysicalName(dim, group, name, &ierr);
    check(ierr);
  };
  add_group(d, tag, "domain");
  if (s.name == "rectangle" || s.name == "box") {
    int shape[2] = {d, tag};
    GmshArray<int> sides;
    api.ModelGetBoundary(shape, 2, &sides.data, &sides.size, 0, 0, 0, &ierr);
    check(ierr);
    const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
    // OpenCASCADE's bounding boxes are enlarged by ~1e-7: a side is the one
    // whose box is thin along an axis.
    const double tolerance = 1e-5 * std::max({s.size[0], s.size[1], d == 3 ? s.size[2] : 0.0});
    for (size_t k = 0; k + 1 < sides.size; k += 2) {
      const int side_dim = sides.data[k], side = sides.data[k + 1];
      double lo[3], hi[3];
      api.ModelGetBoundingBox(side_dim, side, &lo[0], &lo[1], &lo[2], &hi[0], &hi[1], &hi[2],
                              &ierr);
      check(ierr);
      for (int axis = 0; axis < d; ++axis) {
        if (hi[axis] - lo[axis] > tolerance) continue;  // not normal to this axis
        const bool at_min = std::abs(lo[axis] - s.origin[axis]) < 10.0 * tolerance;
        add_group(side_dim, side, names[axis][at_min ? 0 : 1]);
      }
    }
  }
  api.OptionSetNumber("Mesh.MeshSizeMax", s.element_size, &ierr);
  check(ierr);
  api.OptionSetNumber("Mesh.MeshSizeMin", 0.0, &ierr);
  check(ierr);
  api.ModelMeshGenerate(d, &ierr);
  check(ierr);
}

// Runs `work` at the Gmsh call boundary: whatever Gmsh throws (it throws
// std::string in some paths, and may throw anything else) becomes one
// std::runtime_error starting with `what`. (A throw inside one of Gmsh's
// OpenMP regions cannot be caught; the loaders keep shapes out of the sizes
// where that happens: core/input_limits.h, kMinGmshLength.)
template <typename Work>
auto AtGmshBoundary(const std::string& what, Work work) -> decltype(work()) {
  try {
    return work();
  } catch (const std::runtime_error&) {
    throw;
  } catch (const std::string& message) {
    throw std::runtime_error(what + ": " + message);
  } catch (const char* message) {
    throw std::runtime_error(what + ": " + std::string(message != nullptr ? message : ""));
  } catch (const std::exception& error) {
    throw std::runtime_error(what + ": " + error.what());
  } catch (...) {
    throw std::runtime_error(what + ": Gmsh failed (an unknown exception)");
  }
}

}  // namespace

SimplexMesh GmshGenerate(const GmshShape& shape) {
  return AtGmshBoundary("Gmsh", [&] {
    GmshSession session("Gmsh");
    MeshShape(shape, session);
    return ExtractMesh(shape.dimension, "the Gmsh " + shape.name, session);
  });
}

void GmshWriteShape(const GmshShape& shape, const std::string& path, double version) {
  AtGmshBoundary("Gmsh could not write " + path, [&] {
    GmshSession session("Gmsh could not write " + path);
    MeshShape(shape, session);
    int ierr = 0;
    Api().OptionSetNumber("Mesh.MshFileVersion", version, &ierr);
    session(ierr);
    Api().Write(path.c_str(), &ierr);
    session(ierr);
  });
}

SimplexMesh GmshRead(const std::string& path, int dimension) {
  // Not a directory, device or pipe (/dev/zero or a FIFO would never end),
  // and no NUL byte (Gmsh would read the file named by the part before it).
  const std::string problem = InputFileProblem(path);
  if (!problem.empty())
    throw std::runtime_error("cannot read mesh file " + path.substr(0, path.find('\0')) + ": " +
                             problem);
  {
    std::ifstream probe(path);
    if (!probe) throw std::runtime_error("cannot open mesh file " + path);
  }
  return AtGmshBoundary("Gmsh could not read " + path, [&] {
    GmshSession session("Gmsh could not read " + path);
    int ierr = 0;
    Api().Open(path.c_str(), &ierr);
    session(ierr);
    return ExtractMesh(dimension, path, session);
  });
}

}  // namespace ipstep
