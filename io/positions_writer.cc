#include "io/positions_writer.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>

#include "core/input_error.h"

namespace ipstep {

void WritePositionsCsv(const State& s, const std::string& path, const std::string& flag) {
  std::ofstream out(path);
  if (!out) throw InputError("flag", flag, "cannot write '" + path + "'");
  out << std::setprecision(17) << (s.dimension == 2 ? "node,x,y\n" : "node,x,y,z\n");
  for (int i = 0; i < s.num_nodes(); ++i) {
    out << i;
    for (int k = 0; k < s.dimension; ++k) out << ',' << s.x[s.dimension * i + k];
    out << '\n';
  }
}

VtkFrameWriter::VtkFrameWriter(const std::string& directory, const Scene& scene)
    : directory_(directory), scene_(scene) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    throw InputError("flag", "--frames", "cannot create directory '" + directory + "'");
  }
}

void VtkFrameWriter::Write(const State& s, int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "frame_%05d.vtk", frame);
  const std::string path = (std::filesystem::path(directory_) / name).string();
  std::ofstream out(path);
  if (!out) throw InputError("flag", "--frames", "cannot write '" + path + "'");
  const int n = s.num_nodes();
  const int dim = s.dimension;
  out << std::setprecision(12) << "# vtk DataFile Version 3.0\nipstep " << scene_.name
      << " t=" << s.time << "\nASCII\nDATASET POLYDATA\nPOINTS " << n << " double\n";
  for (int i = 0; i < n; ++i) {
    out << s.x[dim * i] << ' ' << s.x[dim * i + 1] << ' ' << (dim == 3 ? s.x[dim * i + 2] : 0.0)
        << '\n';
  }
  const size_t m = scene_.springs.size();
  if (m > 0) {
    out << "LINES " << m << ' ' << 3 * m << '\n';
    for (const Spring& sp : scene_.springs) out << "2 " << sp.i << ' ' << sp.j << '\n';
  } else {
    out << "VERTICES " << n << ' ' << 2 * n << '\n';
    for (int i = 0; i < n; ++i) out << "1 " << i << '\n';
  }
  out << "POINT_DATA " << n << "\nVECTORS velocity double\n";
  for (int i = 0; i < n; ++i) {
    out << s.v[dim * i] << ' ' << s.v[dim * i + 1] << ' ' << (dim == 3 ? s.v[dim * i + 2] : 0.0)
        << '\n';
  }
}

}  // namespace ipstep
