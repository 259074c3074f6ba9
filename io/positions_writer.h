// Node positions as CSV (node,x,y[,z]). Frames for ParaView: io/frame_writer.h.
#pragma once

#include <string>

#include "core/state.h"

namespace ipstep {

// Throws InputError naming `flag` if the file cannot be written.
void WritePositionsCsv(const State& state, const std::string& path, const std::string& flag);

}  // namespace ipstep
