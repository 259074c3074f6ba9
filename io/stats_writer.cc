#include "io/stats_writer.h"

#include <cmath>
#include <iomanip>

namespace ipstep {

StatsWriter::StatsWriter(const std::string& path, const std::string& output,
                         const std::vector<std::string>& diagnostic_names)
    : file_(path, "output: " + output) {
  std::ostream& out = file_.stream();
  out << std::setprecision(17)
      << "step,time,iterations,evaluations,converged,status,wall_seconds,kinetic_energy,"
         "potential_energy,total_energy,residual,substeps,energy_growth,time_step,"
         "error_estimate,rejected";
  for (const std::string& name : diagnostic_names) out << ',' << name;
  out << '\n';
  file_.Flush();
}

void StatsWriter::Write(const StepReport& r) {
  std::ostream& out = file_.stream();
  out << r.step << ',' << r.time << ',' << r.iterations << ',' << r.evaluations << ','
      << (r.converged ? 1 : 0) << ",\"" << r.status << "\"," << r.wall_seconds << ','
      << r.energies.kinetic << ',' << r.energies.potential << ',' << r.energies.total() << ','
      << r.residual << ',' << r.substeps << ',' << r.energy_growth << ',' << r.time_step << ',';
  if (std::isfinite(r.error_estimate)) out << r.error_estimate;
  out << ',' << r.rejected;
  for (double value : r.diagnostics) {
    out << ',';
    if (std::isfinite(value)) out << value;
  }
  out << '\n';
  file_.Flush();
}

IterationLogWriter::IterationLogWriter(const std::string& path, const std::string& output)
    : file_(path, "output: " + output) {
  file_.stream() << std::setprecision(17)
                 << "step,iteration,energy,gradient_norm,step_size,seconds,residual\n";
  file_.Flush();
}

void IterationLogWriter::Write(const IterationRecord& r) {
  file_.stream() << step_ << ',' << r.iteration << ',' << r.energy << ',' << r.gradient_norm << ','
                 << r.step_size << ',' << r.seconds << ',' << r.residual << '\n';
  file_.EndRow();
}

}  // namespace ipstep
