// The comparison of integrators x optimisers (sim/comparison.h) as CSV: one
// row per configuration, the columns of ipstep_compare's table at full
// precision, written by ipstep_compare --compare_output and by the Python
// module's ipstep.compare(..., csv=PATH), whose records carry the same names.
#pragma once

#include <string>
#include <vector>

#include "sim/comparison.h"

namespace ipstep {

// scene, integrator, optimizer, dt, steps, t_end, tolerance, failed_steps,
// iterations_per_step, ms_per_step, position_error, max_energy_drift,
// diverged_at, termination, reference, reference_error.
const std::vector<std::string>& ComparisonColumns();
std::string ComparisonCsvHeader();
// A diverged run's position_error and max_energy_drift are empty; an explicit
// integrator's optimizer is empty.
std::string ComparisonCsvRow(const std::string& scene, const Comparison& comparison,
                             const ComparisonRow& row);
// Writes the header and every row to `path`; throws OutputError naming
// "output: <name>" (io/output_file.h).
void WriteComparisonCsv(const std::string& path, const std::string& name, const std::string& scene,
                        const Comparison& comparison);

}  // namespace ipstep
