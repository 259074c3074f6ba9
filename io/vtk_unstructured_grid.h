// A mesh as VTK's XML unstructured grid (.vtu): points, cells of any VTK type
// (vertices, lines, triangles, polygons, quads, tetrahedra) and named point
// and cell data. ParaView, VTK's vtkXMLUnstructuredGridReader and meshio read
// it; tools/animate.py draws it.
//
// Encodings (VtkEncoding):
//   kAscii: every DataArray as text, numbers in the shortest form that reads
//           back to the same double (std::to_chars), for diffs;
//   kRaw:   binary appended data: every DataArray has format="appended" and
//           an offset into <AppendedData encoding="raw">, which holds after
//           its '_' per array a UInt64 byte count and the little-endian bytes;
//   kZlib:  the same, each array compressed by zlib in blocks of 32 KiB
//           (compressor="vtkZLibDataCompressor"): a UInt64 header [number of
//           blocks, block size, size of a partial last block or 0, the
//           compressed size of each block], then the compressed blocks.
// Points and floating-point data are Float32 or Float64 (VtkPrecision; ASCII
// Float32 numbers in the shortest form that reads back to the same float),
// connectivity and offsets Int32, cell types UInt8.
// A non-finite number is written as 0 (a diverged state is visible in the
// run's CSV and status, not in its picture).
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
  kTetra = 10,
};

enum class VtkEncoding { kAscii, kRaw, kZlib };

enum class VtkPrecision { kFloat32, kFloat64 };

// "ascii", "raw", "zlib".
const char* VtkEncodingName(VtkEncoding encoding);
// False for an unknown name.
bool ParseVtkEncoding(const std::string& name, VtkEncoding* encoding);
// "float32", "float64".
const char* VtkPrecisionName(VtkPrecision precision);
// False for an unknown name.
bool ParseVtkPrecision(const std::string& name, VtkPrecision* precision);

struct VtkMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::vector<int>> cells;  // point indices per cell
  std::vector<VtkCell> types;           // per cell
  // Point data: 3-component vectors (e.g. "velocity"), one per point.
  std::vector<std::pair<std::string, std::vector<Eigen::Vector3d>>> point_vectors;
  // Cell data: integers (e.g. "obstacle": which obstacle a cell belongs to).
  std::vector<std::pair<std::string, std::vector<int>>> cell_integers;
  // Cell data: numbers (e.g. "J"), one per cell.
  std::vector<std::pair<std::string, std::vector<double>>> cell_scalars;

  void AddCell(VtkCell type, std::vector<int> points);
};

// Writes `mesh` to `path`. Throws OutputError (io/output_file.h) naming
// `output` if the file cannot be opened (kOpen) or written (kWrite).
void WriteVtu(const VtkMesh& mesh, const std::string& path, const std::string& output,
              VtkEncoding encoding, VtkPrecision precision = VtkPrecision::kFloat64);

}  // namespace ipstep
