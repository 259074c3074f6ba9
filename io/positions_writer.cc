#include "io/positions_writer.h"

#include <fstream>
#include <iomanip>

#include "core/input_error.h"

namespace ipstep {

void WritePositionsCsv(const State& s, const std::string& path, const std::string& output) {
  std::ofstream out(path);
  if (!out) throw InputError("output", output, "cannot write '" + path + "'");
  out << std::setprecision(17) << (s.dimension == 2 ? "node,x,y\n" : "node,x,y,z\n");
  for (int i = 0; i < s.num_nodes(); ++i) {
    out << i;
    for (int k = 0; k < s.dimension; ++k) out << ',' << s.x[s.dimension * i + k];
    out << '\n';
  }
}

}  // namespace ipstep
