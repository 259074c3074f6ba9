// Reading back the CSV files the programs write (--stats, --iterations_log,
// ipstep_bench's sweeps): one line split into its fields.
#pragma once

#include <string>
#include <vector>

namespace ipstep {

// The fields of a CSV line (quoted fields may hold commas and doubled quotes).
std::vector<std::string> CsvFields(const std::string& line);

}  // namespace ipstep
