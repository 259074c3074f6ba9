// Structured simplex meshes generated without Gmsh: rectangles split into
// triangles and boxes split into tetrahedra, every element positively
// oriented (mesh/simplex_mesh.h).
//
// Node sets: "x_min", "x_max", "y_min", "y_max" (and "z_min", "z_max" in 3D),
// the nodes on each side; "boundary" and "all" (added by AddStandardNodeSets).
#pragma once

#include <array>

#include "mesh/simplex_mesh.h"

namespace ipstep {

// [origin, origin + size] split into cells[0] x cells[1] rectangles, each
// split into two triangles along a diagonal that alternates from cell to cell
// (a "criss-cross" pattern: no preferred direction over two cells).
// Nodes are numbered row by row from origin: node = j * (cells[0] + 1) + i.
SimplexMesh StructuredRectangle(const std::array<double, 2>& origin,
                                const std::array<double, 2>& size, const std::array<int, 2>& cells);

// [origin, origin + size] split into cells[0] x cells[1] x cells[2] cubes, each
// split into six tetrahedra around its main diagonal (Kuhn's subdivision: the
// faces of neighbouring cubes are split alike, so the mesh is conforming).
// node = (k * (cells[1] + 1) + j) * (cells[0] + 1) + i.
SimplexMesh StructuredBox(const std::array<double, 3>& origin, const std::array<double, 3>& size,
                          const std::array<int, 3>& cells);

}  // namespace ipstep
