// CSV outputs of a run: one row per step (--stats) and one row per optimiser
// iteration (--iterations_log).
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "sim/simulation.h"
#include "solver/step_solver.h"

namespace ipstep {

class StatsWriter {
 public:
  // Throws InputError "output: <output>: cannot write '<path>'" if the file
  // cannot be written (`output`: the caller's name for it, e.g. "stats").
  // `diagnostic_names`: extra columns (Simulation::DiagnosticNames()).
  StatsWriter(const std::string& path, const std::string& output,
              const std::vector<std::string>& diagnostic_names = {});
  void Write(const StepReport& report);

 private:
  std::ofstream out_;
};

class IterationLogWriter {
 public:
  // As StatsWriter (e.g. `output` "iterations_log").
  IterationLogWriter(const std::string& path, const std::string& output);
  void set_step(int step) { step_ = step; }
  void Write(const IterationRecord& record);

 private:
  std::ofstream out_;
  int step_ = 0;
};

}  // namespace ipstep
