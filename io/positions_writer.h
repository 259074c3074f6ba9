// Node positions as CSV (node,x,y[,z]) and as legacy-VTK frames for ParaView.
#pragma once

#include <string>

#include "core/state.h"
#include "problems/scene.h"

namespace ipstep {

// Throws InputError naming `flag` if the file cannot be written.
void WritePositionsCsv(const State& state, const std::string& path, const std::string& flag);

// Writes DIR/frame_NNNNN.vtk: points (z = 0 in 2D), springs as lines, and a
// point field "velocity". Creates DIR if needed.
class VtkFrameWriter {
 public:
  VtkFrameWriter(const std::string& directory, const Scene& scene);
  void Write(const State& state, int frame);

 private:
  std::string directory_;
  const Scene& scene_;
};

}  // namespace ipstep
