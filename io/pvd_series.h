// A ParaView time series (.pvd): the files of each frame with the simulated
// time as their `timestep`, so ParaView's time slider shows seconds. Each part
// (e.g. 0 the body, 1 the obstacles) is a block of its own, with a name.
#pragma once

#include <ios>
#include <string>

#include "io/output_file.h"

namespace ipstep {

class PvdSeries {
 public:
  // Creates the .pvd at `path` (an empty collection); the data files are named
  // relative to its directory. Throws OutputError naming `output` if it cannot
  // be opened (kOpen) or written (kWrite).
  PvdSeries(const std::string& path, const std::string& output);
  // Adds `file` (relative to the .pvd's directory) as part `part` at `time`
  // [s], printed in the shortest form that reads back as the same double
  // (0.98, not 0.980000000000001). The .pvd is complete after every call (also when a run stops
  // there): the entry is written over the closing tags, which follow it again. Throws OutputError
  // (kWrite) if the file cannot be written.
  // `name` names the part's block (ParaView's PVD reader shows it).
  void Add(double time, int part, const std::string& name, const std::string& file);

 private:
  void WriteClosingTags();

  OutputFile file_;
  std::streampos end_of_entries_;
};

}  // namespace ipstep
