#include "apps/flag_names.h"

namespace ipstep {

const std::vector<FlagName>& FlagNames() {
  static const std::vector<FlagName> names = {
      // solver/optimizer_options.cc, solver/line_search_solver.cc
      {"options: OptimizerOptions.optimizer", "optimizer"},
      {"options: OptimizerOptions.tolerance", "tolerance"},
      {"options: OptimizerOptions.max_iterations", "max_iterations"},
      {"options: OptimizerOptions.time_limit", "time_limit"},
      {"options: OptimizerOptions.num_threads", "num_threads"},
      {"options: OptimizerOptions.initial_trust_region_radius", "trust_region_radius"},
      {"options: OptimizerOptions.linear_solver", "linear_solver"},
      {"options: OptimizerOptions.sparse_library", "sparse_library"},
      {"options: OptimizerOptions.linear_solver_ordering", "linear_solver_ordering"},
      {"options: OptimizerOptions.line_search", "line_search"},
      {"options: OptimizerOptions.nonlinear_cg", "nonlinear_cg"},
      {"options: OptimizerOptions.lbfgs_rank", "lbfgs_rank"},
      {"options: OptimizerOptions.backtrack_rejected_steps", "backtrack_rejected_steps"},
      {"options: OptimizerOptions.mass_scaled_coordinates", "mass_scaled_coordinates"},
      {"options: OptimizerOptions.precise_line_search_energy", "precise_energy"},
      {"options: OptimizerOptions.hessian_projection", "hessian_projection"},
      // integrators/integrator.cc
      {"options: IntegratorOptions.name", "integrator"},
      {"options: IntegratorOptions.newmark_beta", "newmark_beta"},
      {"options: IntegratorOptions.newmark_gamma", "newmark_gamma"},
      // sim/simulation.cc
      {"options: SimulationOptions.time_step", "dt"},
      {"options: SimulationOptions.steps", "steps"},
      {"options: SimulationOptions.energy_tolerance", "energy_tolerance"},
      {"options: SimulationOptions.max_substeps", "max_substeps"},
      {"options: SimulationOptions.t_end", "t_end"},
      // sim/step_size_controller.cc, sim/run_trajectory.cc
      {"options: AdaptiveOptions.error_tolerance", "error_tolerance"},
      {"options: AdaptiveOptions.t_end", "t_end"},
      {"options: AdaptiveOptions.initial_time_step", "dt"},
      {"options: AdaptiveOptions.min_time_step", "min_dt"},
      {"options: AdaptiveOptions.max_time_step", "max_dt"},
      {"options: AdaptiveOptions.filter_stiff_modes", "filter_stiff_modes"},
      {"options: RunOptions.adaptive", "adaptive"},
      // problems/generators.cc (the grid generator)
      {"options: SceneLoadOptions.grid_size", "grid_size"},
      // io/: the names apps/ipstep_program.cc gives its outputs
      {"output: stats", "stats"},
      {"output: iterations_log", "iterations_log"},
      {"output: positions", "positions"},
      {"output: frames", "frames"},
      // apps/compare_program.cc
      {"output: compare_output", "compare_output"},
  };
  return names;
}

const std::vector<UnmappedName>& UnmappedNames() {
  static const std::vector<UnmappedName> names = {
      {"options: effect_overrides.",
       "the contact flags are range-checked and checked against the scene's effects in "
       "apps/contact_flags.cc before they become overrides, and one effect's overrides come "
       "from several flags (--contact_kappa, --contact_dhat)"},
      {"options: SimulationOptions.accept_residual",
       "set from --error_tolerance and the end time (sim/step_size_controller.h), not a flag "
       "of its own"},
      {"options: AdaptiveOptions.safety",
       "the controller's constants (sim/step_size_controller.h) are not flags"},
      {"options: AdaptiveOptions.max_growth",
       "the controller's constants (sim/step_size_controller.h) are not flags"},
      {"options: AdaptiveOptions.max_shrink",
       "the controller's constants (sim/step_size_controller.h) are not flags"},
      {"options: RunOptions.steps",
       "the programs run a Simulation's own steps (--steps, --t_end) or ipstep_bench's checked "
       "--steps"},
      {"options: RunOptions.stop_on_failure",
       "set from --on_failure (stop or continue), checked by the programs; the library's "
       "option tables (sim/simulation_option_table.h) name it for the Python module"},
      {"options: RunOptions.stop_on_divergence",
       "follows --on_failure; named by the option tables for the Python module"},
      {"options: ComparisonOptions.",
       "ipstep_compare checks its lists (--integrators, --optimizers) before, naming the flag "
       "and a near miss"},
      {"options: RunOptions.max_wall_seconds",
       "ipstep_bench range-checks --max_run_seconds before it becomes the run's limit"},
      {"options: ReferenceOptions.refinement",
       "the programs use the default refinement; the step count it gives is checked by the "
       "programs' own --steps and --t_end ranges"},
      {"options: ReferenceOptions.checkpoints",
       "the programs' references record kErrorCheckpoints (sim/error_measure.h), not a flag"},
      {"options: ReferenceSolution",
       "the programs compute the reference a measure needs themselves (ipstep_tune's "
       "--measure)"},
  };
  return names;
}

std::string FlagFor(const std::string& library_name) {
  const std::string name = library_name.substr(0, library_name.find('='));
  for (const FlagName& entry : FlagNames()) {
    if (name == entry.library_name) return entry.flag;
  }
  return "";
}

std::string WithFlagNames(const InputError& error) {
  if (error.key().empty()) return WithFlagNames(std::string(error.what()));
  const std::string name = error.where() + ": " + error.key();  // "options: X.y[=v]"
  const std::string flag = FlagFor(name);
  if (flag.empty()) return error.what();
  const size_t equals = error.key().find('=');
  const std::string value = equals == std::string::npos ? "" : error.key().substr(equals);
  return "flag: --" + flag + value + ": " + error.detail();
}

std::string WithFlagNames(const std::string& message) {
  const size_t kind_end = message.find(": ");
  if (kind_end == std::string::npos) return message;
  const size_t name_end = message.find(": ", kind_end + 2);
  if (name_end == std::string::npos) return message;
  const std::string name = message.substr(0, name_end);  // "options: X.y" or "options: X.y=v"
  const std::string flag = FlagFor(name);
  if (flag.empty()) return message;
  const size_t equals = name.find('=');
  const std::string value = equals == std::string::npos ? "" : name.substr(equals);
  return "flag: --" + flag + value + message.substr(name_end);
}

}  // namespace ipstep
