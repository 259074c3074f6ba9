// Meshes from Gmsh (its C++ API, libgmsh): simple shapes meshed with a target
// element size, and .msh files (format 2.2 or 4.x; gmsh::open reads both).
//
// Only linear simplices are accepted: 3-node triangles in 2D (in the z = 0
// plane), 4-node tetrahedra in 3D. Elements of lower dimension (boundary
// lines and triangles, points) are ignored except through the physical groups
// they carry. Errors (unreadable file, no elements of the dimension, mixed or
// unsupported element types, higher order, 3D elements in a file read as 2D,
// a path that is not a regular file or holds a NUL byte) are
// std::runtime_error with one sentence; so is anything Gmsh throws (it throws
// std::string in some paths). Elements are reoriented to positive orientation (Gmsh orients
// surface triangles by their surface's normal, which may be -z); an element
// of zero measure is rejected later (CheckMesh).
//
// Node sets: every physical group, by its name (or "physical_<dim>_<tag>"
// when unnamed), restricted to the nodes of the elements; "boundary", "all".
//
// Gmsh keeps global state: every call here initialises it, works on a fresh
// model and finalises it, under one process-wide mutex, with its terminal
// output off (General.Terminal = 0). No other code calls Gmsh. The library
// (libgmsh, through its C API) is loaded with dlopen on the first call, so
// programs that never mesh do not pay its 0.28 s load time.
#pragma once

#include <array>
#include <string>

#include "mesh/simplex_mesh.h"

namespace ipstep {

struct GmshShape {
  int dimension = 2;
  std::string name;  // "rectangle" (2D), "box" (3D): origin + size; "disk" (2D), "ball" (3D)
  std::array<double, 3> origin = {0.0, 0.0, 0.0};  // corner, or the centre of a disk/ball
  std::array<double, 3> size = {1.0, 1.0, 1.0};
  double radius = 1.0;
  double element_size = 0.1;  // target edge length
};

// Meshes the shape. Rectangles and boxes get the physical groups "x_min",
// "x_max", "y_min", "y_max" ("z_min", "z_max") on their sides; every shape a
// physical group "domain" holding all its elements.
SimplexMesh GmshGenerate(const GmshShape& shape);

// Meshes the shape as GmshGenerate does and writes it to `path` in MSH format
// `version` (2.2 or 4.1), physical groups included.
void GmshWriteShape(const GmshShape& shape, const std::string& path, double version);

// Reads a mesh file; `dimension` 2 or 3 selects triangles or tetrahedra.
SimplexMesh GmshRead(const std::string& path, int dimension);

}  // namespace ipstep
