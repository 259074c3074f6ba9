// The error measures of a run, each defined once (what ipstep_tune's
// --measure names; library users take them the same way):
//   position      the largest distance of a free node from the reference at
//                 the end time [m] (MaxNodeDistance, sim/reference.h);
//   max_position  the largest such distance over the run [m]: at the
//                 reference's checkpoints t_j = T j / K (ReferenceOptions::
//                 checkpoints, kErrorCheckpoints for the programs; the last
//                 is T, so it is never below position), the run's positions
//                 there interpolated in its steps (sim/checkpoint_recorder.h:
//                 cubic Hermite, fixed and adaptive steps alike);
//   energy        the largest energy drift over the run, max_n |E_n - E_0| /
//                 E_s(t_n), in energy scales (RunSummary::max_energy_drift,
//                 sim/divergence.h); no reference.
// A run that did not complete (a stop, a timeout) or diverged has no error
// (NaN); one with failed steps has one (the caller decides what it is worth).
//
//   ReferenceOptions with_checkpoints;
//   with_checkpoints.checkpoints = kErrorCheckpoints;
//   const ReferenceSolution reference = ComputeReference(scene, base, with_checkpoints, h, T);
//   Simulation sim(scene, options);
//   const MeasuredRun run = RunMeasured(sim, RunOptions{}, ErrorMeasure::kMaxPosition, &reference);
#pragma once

#include <string>

#include "sim/reference.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep {

enum class ErrorMeasure { kPosition, kMaxPosition, kEnergy };

// "position", "max_position", "energy".
const char* ErrorMeasureName(ErrorMeasure measure);
// The measure of that name; false (and `measure` unchanged) for any other.
bool ParseErrorMeasure(const std::string& name, ErrorMeasure* measure);
// Its unit: "m" or "energy scales".
const char* ErrorMeasureUnit(ErrorMeasure measure);
// Whether it is taken against a reference (position, max_position).
bool MeasureNeedsReference(ErrorMeasure measure);

// The checkpoints the programs' references record (ReferenceOptions::checkpoints).
constexpr int kErrorCheckpoints = 20;

struct MeasuredRun {
  RunSummary run;
  double error = 0.0;  // NaN: none (see above)
};

// Runs `sim` with `options` (sim/run_trajectory.h; its callbacks are kept and
// called first) and takes `measure` against `reference` (null for energy).
// Throws InputError ("options: ReferenceOptions.checkpoints") for
// max_position against a reference without checkpoints, and what
// RunTrajectory throws.
MeasuredRun RunMeasured(Simulation& sim, RunOptions options, ErrorMeasure measure,
                        const ReferenceSolution* reference);

}  // namespace ipstep
