#include "problems/solid_loader.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "mesh/gmsh_mesh.h"
#include "mesh/mesh_boundary.h"
#include "mesh/structured_mesh.h"

namespace ipstep {
namespace {

using nlohmann::json;

// Largest structured or explicit mesh accepted (cells, nodes), and the
// smallest Gmsh element size relative to the shape's extent (bounds the
// element count to a few million: ~1e6 triangles in 2D, ~1e7 tetrahedra in 3D).
constexpr int64_t kMaxCells = 4000000;
constexpr double kMinRelativeElementSize2D = 1e-3;
constexpr double kMinRelativeElementSize3D = 1e-2;

std::string Number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%g", v);
  return buffer;
}

class Value {
 public:
  Value(const json& value, std::string path, const std::string& source)
      : value_(value), path_(std::move(path)), source_(source) {}

  [[noreturn]] void Fail(const std::string& what) const { throw InputError(source_, path_, what); }

  void ExpectObject(const std::vector<std::string>& allowed) const {
    if (!value_.is_object()) Fail("must be an object");
    for (const auto& item : value_.items()) {
      bool known = false;
      for (const std::string& key : allowed) known |= key == item.key();
      if (!known) {
        std::string list;
        for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
        throw InputError(source_, path_ + "." + item.key(),
                         "unknown key (allowed keys: " + list + ")");
      }
    }
  }
  bool Has(const std::string& key) const { return value_.is_object() && value_.contains(key); }
  Value Get(const std::string& key) const {
    if (!Has(key)) throw InputError(source_, path_ + "." + key, "required key is missing");
    return Value(value_.at(key), path_ + "." + key, source_);
  }
  double Num() const {
    if (!value_.is_number()) Fail("must be a number");
    const double v = value_.get<double>();
    if (!std::isfinite(v)) Fail("must be finite");
    return v;
  }
  // (min, max) open or [min, max] closed at each end.
  double Range(double min, double max, bool min_open, bool max_open,
               const std::string& unit = "") const {
    const double v = Num();
    const bool ok = (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max);
    if (!ok) {
      Fail("must be in " + std::string(min_open ? "(" : "[") + Number(min) + ", " + Number(max) +
           (max_open ? ")" : "]") + (unit.empty() ? "" : " " + unit) + ", got " + Number(v));
    }
    return v;
  }
  std::string Str() const {
    if (!value_.is_string()) Fail("must be a string");
    return value_.get<std::string>();
  }
  int Int(int64_t min, int64_t max) const {
    if (!value_.is_number_integer()) Fail("must be an integer");
    const int64_t v = value_.get<int64_t>();
    if (v < min || v > max) {
      Fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
           "], got " + std::to_string(v));
    }
    return static_cast<int>(v);
  }
  std::vector<Value> Elements(size_t size = 0) const {
    if (!value_.is_array() || (size > 0 && value_.size() != size)) {
      Fail(size > 0 ? "must be an array of " + std::to_string(size) + " entries"
                    : "must be an array");
    }
    std::vector<Value> list;
    for (size_t i = 0; i < value_.size(); ++i) {
      list.emplace_back(value_[i], path_ + "[" + std::to_string(i) + "]", source_);
    }
    return list;
  }
  // `size` coordinates within the coordinate range.
  std::vector<double> Point(int size) const {
    std::vector<double> p;
    for (const Value& v : Elements(size)) {
      p.push_back(v.Range(-limits::kMaxCoordinate, limits::kMaxCoordinate, false, false, "m"));
    }
    return p;
  }
  // `size` lengths > 0.
  std::vector<double> Lengths(int size) const {
    std::vector<double> p;
    for (const Value& v : Elements(size)) {
      p.push_back(v.Range(limits::kMinLength, limits::kMaxLength, false, false, "m"));
    }
    return p;
  }
  // A side or radius of a Gmsh shape (OpenCASCADE's tolerance sets the floor).
  double GmshLength() const {
    return Range(limits::kMinGmshLength, limits::kMaxLength, false, false,
                 "m (Gmsh shapes: OpenCASCADE's tolerance is 1e-7 m)");
  }
  const std::string& path() const { return path_; }

 private:
  const json& value_;
  std::string path_;
  const std::string& source_;
};

SimplexMesh ReadStructured(const Value& mesh, int dim, std::string* description) {
  const std::string shape = mesh.Get("shape").Str();
  const std::string expected = dim == 2 ? "rectangle" : "box";
  if (shape != expected) {
    mesh.Get("shape").Fail("must be \"" + expected + "\" in " + std::to_string(dim) + "D (got \"" +
                           ClipInput(shape) + "\")");
  }
  mesh.ExpectObject({"shape", "size", "cells", "origin"});
  const std::vector<double> size = mesh.Get("size").Lengths(dim);
  std::vector<int> cells;
  int64_t count = 1;
  for (const Value& v : mesh.Get("cells").Elements(dim)) {
    cells.push_back(v.Int(1, 100000));
    count *= cells.back();
  }
  if (count > kMaxCells) {
    mesh.Get("cells").Fail("gives " + std::to_string(count) + " cells, more than " +
                           std::to_string(kMaxCells));
  }
  int64_t nodes = 1;
  for (int c : cells) nodes *= c + 1;
  if (nodes > limits::kMaxNodes) {
    mesh.Get("cells").Fail("gives " + std::to_string(nodes) + " nodes, more than the limit of " +
                           std::to_string(limits::kMaxNodes));
  }
  std::vector<double> origin(dim, 0.0);
  if (mesh.Has("origin")) origin = mesh.Get("origin").Point(dim);
  std::string cells_text = std::to_string(cells[0]);
  for (int k = 1; k < dim; ++k) cells_text += "x" + std::to_string(cells[k]);
  if (dim == 2) {
    *description = "structured rectangle, " + cells_text + " cells";
    return StructuredRectangle({origin[0], origin[1]}, {size[0], size[1]}, {cells[0], cells[1]});
  }
  *description = "structured box, " + cells_text + " cells, 6 tetrahedra each";
  return StructuredBox({origin[0], origin[1], origin[2]}, {size[0], size[1], size[2]},
                       {cells[0], cells[1], cells[2]});
}

SimplexMesh ReadGmshShape(const Value& mesh, int dim, std::string* description) {
  GmshShape shape;
  shape.dimension = dim;
  shape.name = mesh.Get("gmsh").Str();
  const bool box_like = shape.name == "rectangle" || shape.name == "box";
  const bool round = shape.name == "disk" || shape.name == "ball";
  const std::string box_name = dim == 2 ? "rectangle" : "box";
  const std::string round_name = dim == 2 ? "disk" : "ball";
  if (!(box_like || round) || (shape.name != box_name && shape.name != round_name)) {
    mesh.Get("gmsh").Fail("unknown shape \"" + ClipInput(shape.name) + "\" in " +
                          std::to_string(dim) + "D (known: " + box_name + ", " + round_name + ")");
  }
  double extent = 0.0;
  if (box_like) {
    mesh.ExpectObject({"gmsh", "size", "origin", "element_size"});
    std::vector<double> size;
    for (const Value& v : mesh.Get("size").Elements(dim)) size.push_back(v.GmshLength());
    std::vector<double> origin(dim, 0.0);
    if (mesh.Has("origin")) origin = mesh.Get("origin").Point(dim);
    for (int k = 0; k < dim; ++k) {
      shape.origin[k] = origin[k];
      shape.size[k] = size[k];
      extent = std::max(extent, size[k]);
    }
  } else {
    mesh.ExpectObject({"gmsh", "center", "radius", "element_size"});
    std::vector<double> center(dim, 0.0);
    if (mesh.Has("center")) center = mesh.Get("center").Point(dim);
    for (int k = 0; k < dim; ++k) shape.origin[k] = center[k];
    shape.radius = mesh.Get("radius").GmshLength();
    extent = 2.0 * shape.radius;
  }
  const double min_relative = dim == 2 ? kMinRelativeElementSize2D : kMinRelativeElementSize3D;
  shape.element_size = mesh.Get("element_size")
                           .Range(min_relative * extent, extent, false, false,
                                  "m (between " + Number(min_relative) +
                                      " times the shape's extent and the extent)");
  SimplexMesh result;
  try {
    result = GmshGenerate(shape);
  } catch (const std::runtime_error& e) {
    mesh.Fail(std::string("Gmsh could not mesh it: ") + e.what());
  }
  if (result.num_nodes() > limits::kMaxNodes) {
    mesh.Get("element_size")
        .Fail("gives " + std::to_string(result.num_nodes()) + " nodes, more than the limit of " +
              std::to_string(limits::kMaxNodes));
  }
  *description = "Gmsh " + shape.name + ", element size " + Number(shape.element_size);
  return result;
}

SimplexMesh ReadMeshFile(const Value& mesh, int dim, const std::string& source,
                         std::string* description) {
  mesh.ExpectObject({"file"});
  const std::string file = mesh.Get("file").Str();
  std::filesystem::path path(file);
  if (file.find('\0') != std::string::npos) {
    mesh.Get("file").Fail("the path contains a NUL byte (at offset " +
                          std::to_string(file.find('\0')) + ")");
  }
  if (path.is_relative()) path = std::filesystem::path(source).parent_path() / path;
  SimplexMesh result;
  try {
    result = GmshRead(path.string(), dim);
  } catch (const std::runtime_error& e) {
    mesh.Get("file").Fail(e.what());
  }
  if (result.num_nodes() > limits::kMaxNodes) {
    mesh.Get("file").Fail(ClipInput(file) + " has " + std::to_string(result.num_nodes()) +
                          " nodes, more than the limit of " + std::to_string(limits::kMaxNodes));
  }
  const std::string problem = CheckMesh(result);
  if (!problem.empty()) mesh.Get("file").Fail(ClipInput(file) + ": " + problem);
  *description = "mesh file " + ClipInput(file);
  return result;
}

SimplexMesh ReadExplicit(const Value& mesh, int dim, std::string* description) {
  mesh.ExpectObject({"nodes", "elements"});
  SimplexMesh result;
  result.dimension = dim;
  const std::vector<Value> nodes = mesh.Get("nodes").Elements();
  if (static_cast<int64_t>(nodes.size()) > limits::kMaxNodes) {
    mesh.Get("nodes").Fail("lists " + std::to_string(nodes.size()) +
                           " nodes, more than the limit of " + std::to_string(limits::kMaxNodes));
  }
  for (const Value& node : nodes) {
    for (double c : node.Point(dim)) result.positions.push_back(c);
  }
  const int n = static_cast<int>(nodes.size());
  for (const Value& element : mesh.Get("elements").Elements()) {
    std::array<int, 4> e = {-1, -1, -1, -1};
    int a = 0;
    for (const Value& index : element.Elements(dim + 1)) e[a++] = index.Int(0, n - 1);
    result.elements.push_back(e);
  }
  AddStandardNodeSets(&result);
  *description = "explicit mesh";
  return result;
}

}  // namespace

Solid ReadSolid(const json& value, int dimension, const std::string& source,
                const std::string& path) {
  const Value solid(value, path, source);
  solid.ExpectObject(
      {"mesh", "model", "youngs_modulus", "poisson_ratio", "density", "plane", "masses"});
  Solid result;
  ElasticMaterial& material = result.material;
  if (solid.Has("model")) {
    const std::string name = solid.Get("model").Str();
    if (!ParseElasticModel(name, &material.model)) {
      solid.Get("model").Fail("unknown model \"" + ClipInput(name) +
                              "\" (known: neo_hookean, stvk, fixed_corotated, linear)");
    }
  }
  material.youngs_modulus = solid.Get("youngs_modulus").Range(0.0, 1e15, true, false, "Pa");
  material.poisson_ratio = solid.Get("poisson_ratio").Range(-1.0, 0.5, true, true);
  if (material.model == ElasticModel::kFixedCorotated && material.poisson_ratio < 0.0) {
    solid.Get("poisson_ratio")
        .Fail(
            "must be >= 0 for fixed_corotated (its volume term lambda/2 (J - 1)^2 needs "
            "lambda >= 0)");
  }
  material.density = solid.Get("density").Range(0.0, 1e12, true, false);
  if (solid.Has("plane")) {
    if (dimension != 2) solid.Get("plane").Fail("is only allowed in 2D");
    const std::string plane = solid.Get("plane").Str();
    if (plane != "strain" && plane != "stress") {
      solid.Get("plane").Fail("must be \"strain\" or \"stress\" (got \"" + ClipInput(plane) +
                              "\")");
    }
    material.plane_stress = plane == "stress";
  }

  const Value mesh = solid.Get("mesh");
  if (!mesh.Has("shape") && !mesh.Has("gmsh") && !mesh.Has("file") && !mesh.Has("nodes")) {
    mesh.Fail(
        "must be an object with one of \"shape\" (structured), \"gmsh\", \"file\", "
        "\"nodes\" (explicit)");
  }
  if (mesh.Has("shape")) {
    result.mesh = ReadStructured(mesh, dimension, &result.description);
  } else if (mesh.Has("gmsh")) {
    result.mesh = ReadGmshShape(mesh, dimension, &result.description);
  } else if (mesh.Has("file")) {
    result.mesh = ReadMeshFile(mesh, dimension, source, &result.description);
  } else {
    result.mesh = ReadExplicit(mesh, dimension, &result.description);
  }
  const std::string problem = CheckMesh(result.mesh);
  if (!problem.empty()) mesh.Fail(problem);

  if (solid.Has("masses")) {
    const std::string name = solid.Get("masses").Str();
    if (!ParseMassDistribution(name, &material.masses)) {
      solid.Get("masses").Fail("must be \"lumped\" or \"uniform\" (got \"" + ClipInput(name) +
                               "\")");
    }
  }
  result.masses = material.masses == MassDistribution::kUniform
                      ? UniformMasses(result.mesh, material.density)
                      : LumpedMasses(result.mesh, material.density);
  // The limits every node source keeps (core/input_limits.h).
  for (size_t i = 0; i < result.masses.size(); ++i) {
    const double m = result.masses[i];
    if (!(m >= limits::kMinMass && m <= limits::kMaxMass)) {
      solid.Get("density").Fail("gives node " + std::to_string(i) + " a mass of " + Number(m) +
                                " kg (" + MassDistributionName(material.masses) +
                                " masses), which must be in " +
                                limits::RangeText(limits::kMinMass, limits::kMaxMass, "kg"));
    }
  }
  return result;
}

}  // namespace ipstep
