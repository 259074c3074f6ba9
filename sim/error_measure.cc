#include "sim/error_measure.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/input_error.h"
#include "sim/checkpoint_recorder.h"

namespace ipstep {

const char* ErrorMeasureName(ErrorMeasure measure) {
  switch (measure) {
    case ErrorMeasure::kPosition:
      return "position";
    case ErrorMeasure::kMaxPosition:
      return "max_position";
    case ErrorMeasure::kEnergy:
      return "energy";
  }
  return "?";
}

bool ParseErrorMeasure(const std::string& name, ErrorMeasure* measure) {
  for (ErrorMeasure m :
       {ErrorMeasure::kPosition, ErrorMeasure::kMaxPosition, ErrorMeasure::kEnergy}) {
    if (name == ErrorMeasureName(m)) {
      *measure = m;
      return true;
    }
  }
  return false;
}

const char* ErrorMeasureUnit(ErrorMeasure measure) {
  return measure == ErrorMeasure::kEnergy ? "energy scales" : "m";
}

bool MeasureNeedsReference(ErrorMeasure measure) { return measure != ErrorMeasure::kEnergy; }

MeasuredRun RunMeasured(Simulation& sim, RunOptions options, ErrorMeasure measure,
                        const ReferenceSolution* reference) {
  if (MeasureNeedsReference(measure) && reference == nullptr) {
    throw InputError("options", "ReferenceSolution",
                     std::string("the ") + ErrorMeasureName(measure) +
                         " measure is taken against a reference: give one");
  }
  std::optional<CheckpointRecorder> recorder;
  if (measure == ErrorMeasure::kMaxPosition) {
    if (reference->checkpoint_times.empty() ||
        reference->checkpoint_x.size() != reference->checkpoint_times.size()) {
      throw InputError("options", "ReferenceOptions.checkpoints",
                       "the max_position measure needs a reference with checkpoints (> 0)");
    }
    recorder.emplace(reference->checkpoint_times);
    recorder->Attach(sim, &options);
  }
  MeasuredRun out;
  out.run = RunTrajectory(sim, options);
  out.error = std::nan("");
  if (out.run.termination != RunTermination::kCompleted || out.run.diverged()) return out;
  const State& state = sim.state();
  switch (measure) {
    case ErrorMeasure::kPosition:
      out.error = MaxNodeDistance(state.x, reference->x, FreeNodes(state), state.dimension);
      break;
    case ErrorMeasure::kMaxPosition: {
      if (!recorder->complete()) break;  // a run that ends before the reference's end
      const std::vector<int> free_nodes = FreeNodes(state);
      double worst = 0.0;
      for (size_t j = 0; j < recorder->positions().size(); ++j) {
        const double e = MaxNodeDistance(recorder->positions()[j], reference->checkpoint_x[j],
                                         free_nodes, state.dimension);
        if (std::isnan(e)) return out;
        worst = std::max(worst, e);
      }
      out.error = worst;
      break;
    }
    case ErrorMeasure::kEnergy:
      out.error = out.run.max_energy_drift;
      break;
  }
  return out;
}

}  // namespace ipstep
