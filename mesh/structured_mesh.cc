#include "mesh/structured_mesh.h"

#include <algorithm>
#include <string>
#include <utility>

#include "mesh/mesh_boundary.h"

namespace ipstep {
namespace {

// Adds the nodes with coordinate `axis` at its minimum or maximum grid index.
void AddSideSets(SimplexMesh* mesh, const int* cells) {
  const char* names[3][2] = {{"x_min", "x_max"}, {"y_min", "y_max"}, {"z_min", "z_max"}};
  const int dim = mesh->dimension;
  for (int i = 0; i < mesh->num_nodes(); ++i) {
    int index = i;
    for (int axis = 0; axis < dim; ++axis) {
      const int c = index % (cells[axis] + 1);
      index /= cells[axis] + 1;
      if (c == 0) mesh->node_sets[names[axis][0]].push_back(i);
      if (c == cells[axis]) mesh->node_sets[names[axis][1]].push_back(i);
    }
  }
}

}  // namespace

SimplexMesh StructuredRectangle(const std::array<double, 2>& origin,
                                const std::array<double, 2>& size,
                                const std::array<int, 2>& cells) {
  SimplexMesh mesh;
  mesh.dimension = 2;
  const int nx = cells[0], ny = cells[1];
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.positions.push_back(origin[0] + size[0] * i / nx);
      mesh.positions.push_back(origin[1] + size[1] * j / ny);
    }
  }
  const auto id = [nx](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if ((i + j) % 2 == 0) {  // diagonal a-c
        mesh.elements.push_back({a, b, c, -1});
        mesh.elements.push_back({a, c, d, -1});
      } else {  // diagonal b-d
        mesh.elements.push_back({a, b, d, -1});
        mesh.elements.push_back({b, c, d, -1});
      }
    }
  }
  AddSideSets(&mesh, cells.data());
  AddStandardNodeSets(&mesh);
  return mesh;
}

SimplexMesh StructuredBox(const std::array<double, 3>& origin, const std::array<double, 3>& size,
                          const std::array<int, 3>& cells) {
  SimplexMesh mesh;
  mesh.dimension = 3;
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  for (int k = 0; k <= nz; ++k) {
    for (int j = 0; j <= ny; ++j) {
      for (int i = 0; i <= nx; ++i) {
        mesh.positions.push_back(origin[0] + size[0] * i / nx);
        mesh.positions.push_back(origin[1] + size[1] * j / ny);
        mesh.positions.push_back(origin[2] + size[2] * k / nz);
      }
    }
  }
  const auto id = [nx, ny](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  // Kuhn: one tetrahedron per order of the axes, walking from corner (0,0,0)
  // to (1,1,1) one axis at a time.
  std::array<int, 3> order = {0, 1, 2};
  std::vector<std::array<int, 3>> orders;
  do {
    orders.push_back(order);
  } while (std::next_permutation(order.begin(), order.end()));
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (const std::array<int, 3>& axes : orders) {
          std::array<int, 3> corner = {i, j, k};
          std::array<int, 4> tet;
          tet[0] = id(i, j, k);
          for (int step = 0; step < 3; ++step) {
            ++corner[axes[step]];
            tet[step + 1] = id(corner[0], corner[1], corner[2]);
          }
          mesh.elements.push_back(tet);
        }
      }
    }
  }
  OrientPositively(&mesh);  // odd permutations of the axes give negative tetrahedra
  AddSideSets(&mesh, cells.data());
  AddStandardNodeSets(&mesh);
  return mesh;
}

}  // namespace ipstep
