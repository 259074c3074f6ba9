// A ParaView time series (.pvd): the files of each frame with the simulated
// time as their `timestep`, so ParaView's time slider shows seconds. Each part
// (e.g. 0 the body, 1 the obstacles) is a block of its own.
#pragma once

#include <string>
#include <vector>

namespace ipstep {

class PvdSeries {
 public:
  // `path`: the .pvd file; the data files are named relative to its directory.
  PvdSeries(std::string path, std::string flag);
  // Adds `file` (relative to the .pvd's directory) as part `part` at `time` [s]
  // and rewrites the .pvd, so that it is complete after every frame (also when
  // a run stops). Throws InputError naming the flag if it cannot be written.
  void Add(double time, int part, const std::string& file);

 private:
  struct Entry {
    double time;
    int part;
    std::string file;
  };
  std::string path_;
  std::string flag_;
  std::vector<Entry> entries_;
};

}  // namespace ipstep
