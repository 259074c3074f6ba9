#include "problems/solid_loader.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/json_node.h"
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

// The solid's own checks on top of JsonNode, with the solid's messages (no
// "got ..." for a wrong type, numbers as %g, ranges open or closed at
// either end), which differ from JsonNode's.

double Num(const JsonNode& node) {
  if (!node.value().is_number()) node.Fail("must be a number");
  const double v = node.value().get<double>();
  if (!std::isfinite(v)) node.Fail("must be finite");
  return v;
}

// (min, max) open or [min, max] closed at each end.
double Range(const JsonNode& node, double min, double max, bool min_open, bool max_open,
             const std::string& unit = "") {
  const double v = Num(node);
  const bool ok = (min_open ? v > min : v >= min) && (max_open ? v < max : v <= max);
  if (!ok) {
    node.Fail("must be in " + std::string(min_open ? "(" : "[") + Number(min) + ", " + Number(max) +
              (max_open ? ")" : "]") + (unit.empty() ? "" : " " + unit) + ", got " + Number(v));
  }
  return v;
}

std::string Str(const JsonNode& node) {
  if (!node.value().is_string()) node.Fail("must be a string");
  return node.value().get<std::string>();
}

int Int(const JsonNode& node, int64_t min, int64_t max) {
  if (!node.value().is_number_integer()) node.Fail("must be an integer");
  const int64_t v = node.value().get<int64_t>();
  if (v < min || v > max) {
    node.Fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
              "], got " + std::to_string(v));
  }
  return static_cast<int>(v);
}

// The elements of an array (of exactly `size` entries if `size` > 0).
std::vector<JsonNode> Entries(const JsonNode& node, size_t size = 0) {
  if (!node.value().is_array() || (size > 0 && node.value().size() != size)) {
    node.Fail(size > 0 ? "must be an array of " + std::to_string(size) + " entries"
                       : "must be an array");
  }
  return node.Elements();
}

// `size` coordinates within the coordinate range.
std::vector<double> Point(const JsonNode& node, int size) {
  std::vector<double> p;
  for (const JsonNode& v : Entries(node, size)) {
    p.push_back(Range(v, -limits::kMaxCoordinate, limits::kMaxCoordinate, false, false, "m"));
  }
  return p;
}

// `size` lengths > 0.
std::vector<double> Lengths(const JsonNode& node, int size) {
  std::vector<double> p;
  for (const JsonNode& v : Entries(node, size)) {
    p.push_back(Range(v, limits::kMinLength, limits::kMaxLength, false, false, "m"));
  }
  return p;
}

// A side or radius of a Gmsh shape (OpenCASCADE's tolerance sets the floor).
double GmshLength(const JsonNode& node) {
  return Range(node, limits::kMinGmshLength, limits::kMaxLength, false, false,
               "m (Gmsh shapes: OpenCASCADE's tolerance is 1e-7 m)");
}

SimplexMesh ReadStructured(const JsonNode& mesh, int dim, std::string* description) {
  const std::string shape = Str(mesh.Get("shape"));
  const std::string expected = dim == 2 ? "rectangle" : "box";
  if (shape != expected) {
    mesh.Get("shape").Fail("must be \"" + expected + "\" in " + std::to_string(dim) + "D (got \"" +
                           ClipInput(shape) + "\")");
  }
  mesh.ExpectObject({"shape", "size", "cells", "origin"});
  const std::vector<double> size = Lengths(mesh.Get("size"), dim);
  std::vector<int> cells;
  int64_t count = 1;
  for (const JsonNode& v : Entries(mesh.Get("cells"), dim)) {
    cells.push_back(Int(v, 1, 100000));
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
  if (mesh.Has("origin")) origin = Point(mesh.Get("origin"), dim);
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

SimplexMesh ReadGmshShape(const JsonNode& mesh, int dim, std::string* description) {
  GmshShape shape;
  shape.dimension = dim;
  shape.name = Str(mesh.Get("gmsh"));
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
    for (const JsonNode& v : Entries(mesh.Get("size"), dim)) size.push_back(GmshLength(v));
    std::vector<double> origin(dim, 0.0);
    if (mesh.Has("origin")) origin = Point(mesh.Get("origin"), dim);
    for (int k = 0; k < dim; ++k) {
      shape.origin[k] = origin[k];
      shape.size[k] = size[k];
      extent = std::max(extent, size[k]);
    }
  } else {
    mesh.ExpectObject({"gmsh", "center", "radius", "element_size"});
    std::vector<double> center(dim, 0.0);
    if (mesh.Has("center")) center = Point(mesh.Get("center"), dim);
    for (int k = 0; k < dim; ++k) shape.origin[k] = center[k];
    shape.radius = GmshLength(mesh.Get("radius"));
    extent = 2.0 * shape.radius;
  }
  const double min_relative = dim == 2 ? kMinRelativeElementSize2D : kMinRelativeElementSize3D;
  shape.element_size =
      Range(mesh.Get("element_size"), min_relative * extent, extent, false, false,
            "m (between " + Number(min_relative) + " times the shape's extent and the extent)");
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

SimplexMesh ReadMeshFile(const JsonNode& mesh, int dim, const std::string& source,
                         std::string* description) {
  mesh.ExpectObject({"file"});
  const std::string file = Str(mesh.Get("file"));
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

SimplexMesh ReadExplicit(const JsonNode& mesh, int dim, std::string* description) {
  mesh.ExpectObject({"nodes", "elements"});
  SimplexMesh result;
  result.dimension = dim;
  const std::vector<JsonNode> nodes = Entries(mesh.Get("nodes"));
  if (static_cast<int64_t>(nodes.size()) > limits::kMaxNodes) {
    mesh.Get("nodes").Fail("lists " + std::to_string(nodes.size()) +
                           " nodes, more than the limit of " + std::to_string(limits::kMaxNodes));
  }
  for (const JsonNode& node : nodes) {
    for (double c : Point(node, dim)) result.positions.push_back(c);
  }
  const int n = static_cast<int>(nodes.size());
  for (const JsonNode& element : Entries(mesh.Get("elements"))) {
    std::array<int, 4> e = {-1, -1, -1, -1};
    int a = 0;
    for (const JsonNode& index : Entries(element, dim + 1)) e[a++] = Int(index, 0, n - 1);
    result.elements.push_back(e);
  }
  AddStandardNodeSets(&result);
  *description = "explicit mesh";
  return result;
}

}  // namespace

Solid ReadSolid(const json& value, int dimension, const std::string& source,
                const std::string& path) {
  const JsonNode solid(value, path, source);
  if (!value.is_object()) solid.Fail("must be an object");
  solid.ExpectObject(
      {"mesh", "model", "youngs_modulus", "poisson_ratio", "density", "plane", "masses"});
  Solid result;
  ElasticMaterial& material = result.material;
  if (solid.Has("model")) {
    const std::string name = Str(solid.Get("model"));
    if (!ParseElasticModel(name, &material.model)) {
      solid.Get("model").Fail("unknown model \"" + ClipInput(name) +
                              "\" (known: neo_hookean, stvk, fixed_corotated, linear)");
    }
  }
  material.youngs_modulus = Range(solid.Get("youngs_modulus"), 0.0, 1e15, true, false, "Pa");
  material.poisson_ratio = Range(solid.Get("poisson_ratio"), -1.0, 0.5, true, true);
  if (material.model == ElasticModel::kFixedCorotated && material.poisson_ratio < 0.0) {
    solid.Get("poisson_ratio")
        .Fail(
            "must be >= 0 for fixed_corotated (its volume term lambda/2 (J - 1)^2 needs "
            "lambda >= 0)");
  }
  material.density = Range(solid.Get("density"), 0.0, 1e12, true, false);
  if (solid.Has("plane")) {
    if (dimension != 2) solid.Get("plane").Fail("is only allowed in 2D");
    const std::string plane = Str(solid.Get("plane"));
    if (plane != "strain" && plane != "stress") {
      solid.Get("plane").Fail("must be \"strain\" or \"stress\" (got \"" + ClipInput(plane) +
                              "\")");
    }
    material.plane_stress = plane == "stress";
  }

  const JsonNode mesh = solid.Get("mesh");
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
    const std::string name = Str(solid.Get("masses"));
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
