// Node positions as CSV (node,x,y[,z]). Frames for ParaView: io/frame_writer.h.
#pragma once

#include <string>

#include "core/state.h"

namespace ipstep {

// Throws InputError "output: <output>: cannot write '<path>'" if the file cannot
// be written (`output`: the caller's name for it, e.g. "positions").
void WritePositionsCsv(const State& state, const std::string& path, const std::string& output);

}  // namespace ipstep
