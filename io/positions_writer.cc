#include "io/positions_writer.h"

#include <iomanip>

#include "core/input_error.h"

namespace ipstep {

PositionsFile::PositionsFile(const std::string& path, const std::string& output)
    : path_(path), output_(output), out_(path) {
  if (!out_) throw InputError("output", output_, "cannot write '" + path_ + "'");
}

void PositionsFile::Write(const State& s) {
  out_ << std::setprecision(17) << (s.dimension == 2 ? "node,x,y\n" : "node,x,y,z\n");
  for (int i = 0; i < s.num_nodes(); ++i) {
    out_ << i;
    for (int k = 0; k < s.dimension; ++k) out_ << ',' << s.x[s.dimension * i + k];
    out_ << '\n';
  }
  out_.flush();
  if (!out_) throw InputError("output", output_, "cannot write '" + path_ + "'");
}

void WritePositionsCsv(const State& state, const std::string& path, const std::string& output) {
  PositionsFile(path, output).Write(state);
}

}  // namespace ipstep
