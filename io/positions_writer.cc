#include "io/positions_writer.h"

#include <iomanip>

namespace ipstep {

PositionsFile::PositionsFile(const std::string& path, const std::string& output)
    : file_(path, "output: " + output) {}

void PositionsFile::Write(const State& s) {
  std::ostream& out = file_.stream();
  out << std::setprecision(17) << (s.dimension == 2 ? "node,x,y\n" : "node,x,y,z\n");
  for (int i = 0; i < s.num_nodes(); ++i) {
    out << i;
    for (int k = 0; k < s.dimension; ++k) out << ',' << s.x[s.dimension * i + k];
    out << '\n';
  }
  file_.EndRow();
  file_.Close();
}

void WritePositionsCsv(const State& state, const std::string& path, const std::string& output) {
  PositionsFile(path, output).Write(state);
}

}  // namespace ipstep
