#include "io/stats_writer.h"

#include <cmath>
#include <iomanip>

#include "core/input_error.h"

namespace ipstep {
namespace {

std::ofstream OpenForWriting(const std::string& path, const std::string& output) {
  std::ofstream out(path);
  if (!out) throw InputError("output", output, "cannot write '" + path + "'");
  out << std::setprecision(17);
  return out;
}

}  // namespace

StatsWriter::StatsWriter(const std::string& path, const std::string& output,
                         const std::vector<std::string>& diagnostic_names)
    : out_(OpenForWriting(path, output)) {
  out_ << "step,time,iterations,evaluations,converged,status,wall_seconds,kinetic_energy,"
          "potential_energy,total_energy,residual,substeps,energy_growth,time_step,"
          "error_estimate,rejected";
  for (const std::string& name : diagnostic_names) out_ << ',' << name;
  out_ << '\n';
}

void StatsWriter::Write(const StepReport& r) {
  out_ << r.step << ',' << r.time << ',' << r.iterations << ',' << r.evaluations << ','
       << (r.converged ? 1 : 0) << ",\"" << r.status << "\"," << r.wall_seconds << ','
       << r.energies.kinetic << ',' << r.energies.potential << ',' << r.energies.total() << ','
       << r.residual << ',' << r.substeps << ',' << r.energy_growth << ',' << r.time_step << ',';
  if (std::isfinite(r.error_estimate)) out_ << r.error_estimate;
  out_ << ',' << r.rejected;
  for (double value : r.diagnostics) {
    out_ << ',';
    if (std::isfinite(value)) out_ << value;
  }
  out_ << '\n';
}

IterationLogWriter::IterationLogWriter(const std::string& path, const std::string& output)
    : out_(OpenForWriting(path, output)) {
  out_ << "step,iteration,energy,gradient_norm,step_size,seconds,residual\n";
}

void IterationLogWriter::Write(const IterationRecord& r) {
  out_ << step_ << ',' << r.iteration << ',' << r.energy << ',' << r.gradient_norm << ','
       << r.step_size << ',' << r.seconds << ',' << r.residual << '\n';
}

}  // namespace ipstep
