// A mesh as VTK's XML unstructured grid (.vtu, ASCII): points, cells of any VTK
// type (vertices, lines, triangles, polygons, quads) and named point and cell
// data. ParaView and meshio read it; tools/animate.py draws it.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace ipstep {

// VTK cell type ids (vtkCellType.h).
enum class VtkCell : std::uint8_t {
  kVertex = 1,
  kLine = 3,
  kTriangle = 5,
  kPolygon = 7,
  kQuad = 9,
};

struct VtkMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> cells;  // point indices per cell
  std::vector<VtkCell> types;           // per cell
  // Point data: 3-component vectors (e.g. "velocity"), one per point.
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> point_vectors;
  // Cell data: integers (e.g. "obstacle": which obstacle a cell belongs to).
  std::vector<std::pair<std::string, std::vector<int>>> cell_integers;

  void AddCell(VtkCell type, std::vector<int> points);
};

// Writes `mesh` to `path`. Throws OutputError (io/output_file.h) naming
// `output` if the file cannot be opened (kOpen) or written (kWrite).
void WriteVtu(const VtkMesh& mesh, const std::string& path, const std::string& output);

}  // namespace ipstep
