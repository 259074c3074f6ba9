#include "mesh/simplex_mesh.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace ipstep {

double SignedSimplexMeasure(int dimension, const double* const* x) {
  if (dimension == 2) {
    const double ax = x[1][0] - x[0][0], ay = x[1][1] - x[0][1];
    const double bx = x[2][0] - x[0][0], by = x[2][1] - x[0][1];
    return 0.5 * (ax * by - ay * bx);
  }
  double d[3][3];
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < 3; ++k) d[k][c] = x[c + 1][k] - x[0][k];
  }
  const double det = d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) -
                     d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
                     d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
  return det / 6.0;
}

double SignedMeasure(const SimplexMesh& mesh, int element) {
  const double* x[4];
  for (int a = 0; a < mesh.nodes_per_element(); ++a) {
    x[a] = mesh.positions.data() + mesh.dimension * mesh.elements[element][a];
  }
  return SignedSimplexMeasure(mesh.dimension, x);
}

double TotalMeasure(const SimplexMesh& mesh) {
  double total = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) total += SignedMeasure(mesh, e);
  return total;
}

std::string CheckMesh(const SimplexMesh& mesh) {
  const int dim = mesh.dimension;
  const int n = mesh.num_nodes();
  if (mesh.num_elements() == 0) return "the mesh has no elements";
  std::vector<bool> used(n, false);
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const std::string name = "element " + std::to_string(e);
    for (int a = 0; a < dim + 1; ++a) {
      const int node = mesh.elements[e][a];
      if (node < 0 || node >= n) {
        return name + " refers to node " + std::to_string(node) + ", out of range (the mesh has " +
               std::to_string(n) + " nodes)";
      }
      for (int b = 0; b < a; ++b) {
        if (mesh.elements[e][b] == node) {
          return name + " lists node " + std::to_string(node) + " twice";
        }
      }
      used[node] = true;
    }
    double longest = 0.0;
    for (int a = 0; a < dim + 1; ++a) {
      for (int b = 0; b < a; ++b) {
        double l2 = 0.0;
        for (int k = 0; k < dim; ++k) {
          const double d = mesh.positions[dim * mesh.elements[e][a] + k] -
                           mesh.positions[dim * mesh.elements[e][b] + k];
          l2 += d * d;
        }
        longest = std::max(longest, std::sqrt(l2));
      }
    }
    const double measure = SignedMeasure(mesh, e);
    if (!(std::abs(measure) > 1e-12 * std::pow(longest, dim))) {
      return name + " is degenerate (" + (dim == 2 ? "area " : "volume ") +
             std::to_string(measure) + ")";
    }
    if (measure < 0.0) {
      return name + " is inverted (negatively oriented: " +
             (dim == 2 ? std::string("list its nodes counterclockwise")
                       : std::string("swap two of its nodes")) +
             ")";
    }
  }
  // An element listed twice (its nodes in any order) would make each of its
  // facets seen twice, i.e. interior: the body would lose its surface.
  std::map<std::array<int, 4>, int> first;  // sorted nodes -> first element
  for (int e = 0; e < mesh.num_elements(); ++e) {
    std::array<int, 4> key = mesh.elements[e];
    std::sort(key.begin(), key.begin() + std::clamp(dim + 1, 1, 4));
    const auto [it, inserted] = first.emplace(key, e);
    if (!inserted) {
      return "element " + std::to_string(e) + " repeats element " + std::to_string(it->second) +
             " (the same nodes)";
    }
  }
  for (int i = 0; i < n; ++i) {
    if (!used[i]) return "node " + std::to_string(i) + " belongs to no element";
  }
  return "";
}

int OrientPositively(SimplexMesh* mesh) {
  int flipped = 0;
  for (int e = 0; e < mesh->num_elements(); ++e) {
    if (SignedMeasure(*mesh, e) < 0.0) {
      std::swap(mesh->elements[e][mesh->dimension - 1], mesh->elements[e][mesh->dimension]);
      ++flipped;
    }
  }
  return flipped;
}

std::vector<double> LumpedMasses(const SimplexMesh& mesh, double density) {
  std::vector<double> masses(mesh.num_nodes(), 0.0);
  const int corners = mesh.nodes_per_element();
  for (int e = 0; e < mesh.num_elements(); ++e) {
    const double share = density * std::abs(SignedMeasure(mesh, e)) / corners;
    for (int a = 0; a < corners; ++a) masses[mesh.elements[e][a]] += share;
  }
  return masses;
}

std::vector<double> UniformMasses(const SimplexMesh& mesh, double density) {
  double measure = 0.0;
  for (int e = 0; e < mesh.num_elements(); ++e) measure += std::abs(SignedMeasure(mesh, e));
  return std::vector<double>(mesh.num_nodes(), density * measure / mesh.num_nodes());
}

}  // namespace ipstep
