// Node positions as CSV (node,x,y[,z]). Frames for ParaView: io/frame_writer.h.
#pragma once

#include <fstream>
#include <string>

#include "core/state.h"

namespace ipstep {

// A positions file opened when a run starts and written when it ends, so that
// a path that cannot be written is reported before the run, not after it.
class PositionsFile {
 public:
  // Throws InputError "output: <output>: cannot write '<path>'" if the file
  // cannot be opened for writing (`output`: the caller's name for it, e.g.
  // "positions"). Creates (truncates) the file.
  PositionsFile(const std::string& path, const std::string& output);
  // Writes the header and one row per node; throws InputError like the
  // constructor if the stream fails (e.g. the disk is full).
  void Write(const State& state);

 private:
  std::string path_, output_;
  std::ofstream out_;
};

// PositionsFile(path, output).Write(state).
void WritePositionsCsv(const State& state, const std::string& path, const std::string& output);

}  // namespace ipstep
