#include "io/comparison_csv.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/output_file.h"

namespace ipstep {
namespace {

std::string Number(double x) {
  if (!std::isfinite(x)) return "";
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", x);
  return text;
}

// Quoted when it holds a comma or a quote (quotes doubled; io/csv_fields.h).
std::string Text(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

const std::vector<std::string>& ComparisonColumns() {
  static const std::vector<std::string> columns = {"scene",
                                                   "integrator",
                                                   "optimizer",
                                                   "dt",
                                                   "steps",
                                                   "t_end",
                                                   "tolerance",
                                                   "failed_steps",
                                                   "iterations_per_step",
                                                   "ms_per_step",
                                                   "position_error",
                                                   "max_energy_drift",
                                                   "diverged_at",
                                                   "termination",
                                                   "reference",
                                                   "reference_error"};
  return columns;
}

std::string ComparisonCsvHeader() {
  std::string header;
  for (const std::string& column : ComparisonColumns()) {
    header += (header.empty() ? "" : ",") + column;
  }
  return header;
}

std::string ComparisonCsvRow(const std::string& scene, const Comparison& c,
                             const ComparisonRow& row) {
  const RunSummary& r = row.run;
  std::ostringstream out;
  out << Text(scene) << ',' << row.integrator << ',' << row.optimizer << ',' << Number(row.dt)
      << ',' << r.steps_done << ',' << Number(c.t_end) << ',' << Number(c.tolerance) << ','
      << r.failed << ',' << Number(r.iterations_per_step()) << ',' << Number(r.ms_per_step()) << ','
      << Number(r.diverged() ? std::nan("") : row.position_error) << ','
      << Number(r.diverged() ? std::nan("") : r.max_energy_drift) << ',' << r.diverged_at << ','
      << Text(RunTerminationName(r.termination)) << ',' << Text(c.reference_note) << ','
      << Number(c.reference.error);
  return out.str();
}

void WriteComparisonCsv(const std::string& path, const std::string& name, const std::string& scene,
                        const Comparison& comparison) {
  OutputFile file(path, "output: " + name);
  file.stream() << ComparisonCsvHeader() << '\n';
  for (const ComparisonRow& row : comparison.rows) {
    file.stream() << ComparisonCsvRow(scene, comparison, row) << '\n';
    file.EndRow();
  }
  file.Close();
}

}  // namespace ipstep
