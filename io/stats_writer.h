// CSV outputs of a run: one row per step (--stats) and one row per optimiser
// iteration (--iterations_log). Both are io/output_file.h files: a path that
// cannot be written throws OutputError (kOpen) when the writer is made, a
// failed write OutputError (kWrite).
#pragma once

#include <string>
#include <vector>

#include "io/output_file.h"
#include "sim/simulation.h"
#include "solver/step_solver.h"

namespace ipstep {

class StatsWriter {
 public:
  // Throws OutputError "output: <output>: cannot write '<path>': <reason>" if
  // the file cannot be written (`output`: the caller's name for it, e.g.
  // "stats"). `diagnostic_names`: extra columns (Simulation::DiagnosticNames()).
  StatsWriter(const std::string& path, const std::string& output,
              const std::vector<std::string>& diagnostic_names = {});
  // Writes the step's row and flushes it (a stopped run keeps its complete
  // rows); throws OutputError (kWrite) if it cannot be written.
  void Write(const StepReport& report);
  // Flushes and closes; throws like Write.
  void Close() { file_.Close(); }

 private:
  OutputFile file_;
};

class IterationLogWriter {
 public:
  // As StatsWriter (e.g. `output` "iterations_log").
  IterationLogWriter(const std::string& path, const std::string& output);
  void set_step(int step) { step_ = step; }
  // Buffers the row and never throws (it is called from inside the solver);
  // a failed write is reported by the next Flush() or Close().
  void Write(const IterationRecord& record);
  // Writes the buffered rows out (e.g. after each step); throws OutputError
  // (kWrite) if a row could not be written.
  void Flush() { file_.Flush(); }
  void Close() { file_.Close(); }

 private:
  OutputFile file_;
  int step_ = 0;
};

}  // namespace ipstep
