#include "io/vtk_unstructured_grid.h"

#include <cmath>
#include <iomanip>
#include <limits>

#include "io/output_file.h"

namespace ipstep {

void VtkMesh::AddCell(VtkCell type, std::vector<int> cell_points) {
  cells.push_back(std::move(cell_points));
  types.push_back(type);
}

namespace {

// A non-finite number would make the file unreadable: written as 0 (a diverged
// state is visible in the run's CSV and status, not in its picture).
double Finite(double value) { return std::isfinite(value) ? value : 0.0; }

void WriteVectors(std::ostream& out, const std::vector<Eigen::Vector3d>& vectors) {
  for (const Eigen::Vector3d& v : vectors) {
    out << Finite(v[0]) << ' ' << Finite(v[1]) << ' ' << Finite(v[2]) << '\n';
  }
}

}  // namespace

void WriteVtu(const VtkMesh& mesh, const std::string& path, const std::string& output) {
  OutputFile file(path, "output: " + output);
  std::ostream& out = file.stream();
  out << std::setprecision(std::numeric_limits<double>::max_digits10);
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\""
      << mesh.points.size() << "\" NumberOfCells=\"" << mesh.cells.size() << "\">\n";
  out << "<PointData>\n";
  for (const auto& [name, values] : mesh.point_vectors) {
    out << "<DataArray type=\"Float64\" Name=\"" << name
        << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    WriteVectors(out, values);
    out << "</DataArray>\n";
  }
  out << "</PointData>\n<CellData>\n";
  for (const auto& [name, values] : mesh.cell_integers) {
    out << "<DataArray type=\"Int32\" Name=\"" << name << "\" format=\"ascii\">\n";
    for (int value : values) out << value << '\n';
    out << "</DataArray>\n";
  }
  out << "</CellData>\n<Points>\n"
         "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  WriteVectors(out, mesh.points);
  out << "</DataArray>\n</Points>\n<Cells>\n"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const std::vector<int>& cell : mesh.cells) {
    for (size_t k = 0; k < cell.size(); ++k) out << (k == 0 ? "" : " ") << cell[k];
    out << '\n';
  }
  out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  long offset = 0;
  for (const std::vector<int>& cell : mesh.cells) {
    offset += static_cast<long>(cell.size());
    out << offset << '\n';
  }
  out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for (VtkCell type : mesh.types) out << static_cast<int>(type) << '\n';
  out << "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  file.Close();
}

}  // namespace ipstep
