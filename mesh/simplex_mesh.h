// A mesh of linear simplices: triangles in 2D, tetrahedra in 3D, with named
// node sets (the sides of a structured mesh, Gmsh physical groups). The rest
// configuration of an elastic solid (energies/elasticity/).
//
// Orientation: an element (n0, n1, ..., nd) is positively oriented when
// det[x1 - x0, ..., xd - x0] > 0 (counterclockwise triangles; tetrahedra whose
// first three nodes turn counterclockwise seen from outside, i.e. with the
// fourth node on the side their normal points to). Every mesh an elastic
// solid uses is positively oriented with nonzero volume (CheckMesh).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace ipstep {

struct SimplexMesh {
  int dimension = 2;                                  // 2: triangles, 3: tetrahedra
  std::vector<double> positions;                      // dimension per node, flattened
  std::vector<std::array<int, 4>> elements;           // the first dimension + 1 entries are used
  std::map<std::string, std::vector<int>> node_sets;  // ascending node indices

  int num_nodes() const { return static_cast<int>(positions.size()) / dimension; }
  int num_elements() const { return static_cast<int>(elements.size()); }
  int nodes_per_element() const { return dimension + 1; }
};

// Signed measure of element e: its area (2D) or volume (3D), positive for a
// positively oriented element.
double SignedMeasure(const SimplexMesh& mesh, int element);
// Signed measure of a simplex given by its node positions (dimension each).
double SignedSimplexMeasure(int dimension, const double* const* x);

// Total measure (area or volume) of the mesh.
double TotalMeasure(const SimplexMesh& mesh);

// Empty when the mesh is valid; otherwise one sentence naming the first
// problem: a node index out of range, a repeated node in an element, an
// inverted (negatively oriented) or degenerate element (|measure| below 1e-12
// times the element's longest edge to the power dimension), a node used by no
// element.
std::string CheckMesh(const SimplexMesh& mesh);

// Reorders each negatively oriented element (swaps its last two nodes), for
// sources whose orientation is a convention, not a state (Gmsh surfaces whose
// normal points to -z). Returns how many elements were flipped.
int OrientPositively(SimplexMesh* mesh);

// Lumped masses: each element gives density * measure / (dimension + 1) to
// each of its nodes.
std::vector<double> LumpedMasses(const SimplexMesh& mesh, double density);

// Uniform masses: every node gets density * TotalMeasure / num_nodes (the
// same total as LumpedMasses).
std::vector<double> UniformMasses(const SimplexMesh& mesh, double density);

}  // namespace ipstep
