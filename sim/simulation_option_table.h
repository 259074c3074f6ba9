// The option tables of a simulation and its run (core/option_table.h):
//  * SimulationOptionTable(): every option of the programs that goes into
//    SimulationOptions: its own fields (time_step, steps, t_end,
//    energy_tolerance, max_substeps), the contact and friction parameters the
//    programs override (contact_kappa, ...: SimulationOptions::effect_overrides),
//    and IntegratorOptions' and OptimizerOptions' tables
//    (integrators/integrator_option_table.h, solver/optimizer_option_table.h);
//  * RunOptionTable(): RunOptions' fields for a run from the library
//    (sim/run_trajectory.h);
//  * AdaptiveOptionTable(): AdaptiveOptions' fields, the error-controlled
//    steps of an adaptive run (sim/step_size_controller.h), except t_end,
//    which the programs and the Python module take from the run's end time.
// Names are unique across the three.
#pragma once

#include "core/option_table.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"

namespace ipstep {

const OptionTable<SimulationOptions>& SimulationOptionTable();
const OptionTable<RunOptions>& RunOptionTable();
const OptionTable<AdaptiveOptions>& AdaptiveOptionTable();

// The library's range check of SimulationOptions' own fields (time_step,
// steps, t_end, energy_tolerance, max_substeps) by their rows
// (CheckOptionRanges); the integrator and optimiser options are checked where
// they are made (MakeIntegrator, ValidateOptimizerOptions).
void CheckSimulationOptionRanges(const SimulationOptions& options);

// Throws InputError naming the field of the first option in `given` (names of
// SimulationOptionTable()) that does not apply to `options` (an L-BFGS option
// with optimizer=newton, a Newmark parameter with another integrator).
void CheckOptionsApply(const SimulationOptions& options, const std::vector<std::string>& given);

}  // namespace ipstep
