// Node positions as CSV (node,x,y[,z]). Frames for ParaView: io/frame_writer.h.
#pragma once

#include <string>

#include "core/state.h"
#include "io/output_file.h"

namespace ipstep {

// A positions file opened when a run starts and written when it ends, so that
// a path that cannot be written is reported before the run, not after it.
class PositionsFile {
 public:
  // Throws OutputError "output: <output>: cannot write '<path>': <reason>" if
  // the file cannot be opened for writing (`output`: the caller's name for it,
  // e.g. "positions"). Creates (truncates) the file.
  PositionsFile(const std::string& path, const std::string& output);
  // Writes the header and one row per node and closes the file; throws
  // OutputError (kWrite) if a write fails (e.g. the disk is full).
  void Write(const State& state);

 private:
  OutputFile file_;
};

// PositionsFile(path, output).Write(state).
void WritePositionsCsv(const State& state, const std::string& path, const std::string& output);

}  // namespace ipstep
