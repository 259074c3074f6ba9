// Reading back the CSV files the programs write (--stats, --iterations_log,
// ipstep_bench's sweeps, ipstep_tune's shards): one line split into its
// fields; and one field written so that it reads back.
#pragma once

#include <string>
#include <vector>

namespace ipstep {

// The fields of a CSV line (quoted fields may hold commas and doubled quotes).
std::vector<std::string> CsvFields(const std::string& line);

// `text` as a CSV field: as it is, or quoted (quotes doubled) when it holds a
// comma, a quote or a newline; a newline becomes a space (one row per line).
std::string CsvField(const std::string& text);

}  // namespace ipstep
