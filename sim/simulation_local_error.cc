// Simulation::LocalError: the local error estimate of the step just taken,
// raw or with the stiff modes filtered out (sim/stiff_mode_filter.h).
#include "sim/simulation.h"
#include "sim/stiff_mode_filter.h"

#include <string>

#include <glog/logging.h>

namespace ipstep {

Simulation::~Simulation() = default;

double Simulation::LocalError(const State& before, double h, bool filter_stiff_modes) {
  const Integrator& integrator = integrator_.common();
  Eigen::VectorXd error;
  integrator.LocalErrorVector(before, state_, h, &error);
  // An explicit step has no matrix (and its stiff modes are unstable, not
  // damped); quasi-static steps have no inertia and no error to control.
  if (filter_stiff_modes && integrator_.variational && integrator.has_inertia()) {
    const double raw = Integrator::LargestFreeNodeNorm(state_, error);
    // With the step solver's own factorisation of the step matrix when it
    // kept one (projected_newton), else assembled and factorised here. A
    // failed filter (a term not evaluable, a failed factorisation) keeps the
    // raw estimate: the conservative one.
    Eigen::VectorXd weighted = error, filtered_error;
    for (int i = 0; i < state_.num_nodes(); ++i) {
      weighted.segment(state_.dimension * i, state_.dimension) *= state_.mass[i];
    }
    const bool reused = solver_ && solver_->SolveWithLastStepMatrix(weighted, &filtered_error);
    if (!reused && !stiff_mode_filter_) {
      stiff_mode_filter_ =
          std::make_unique<StiffModeFilter>(potential_.get(), &state_, options_.optimizer);
    }
    // (Only the free DOFs are read below: the solves leave the others 0.)
    const bool filtered = reused || stiff_mode_filter_->Solve(state_.x, weighted, &filtered_error);
    if (filtered) error = filtered_error;
    VLOG(2) << "local error: raw " << raw << ", filtered "
            << (filtered ? std::to_string(Integrator::LargestFreeNodeNorm(state_, error))
                         : std::string("failed"))
            << (reused ? " (the solver's factorisation)" : "");
  }
  return Integrator::LargestFreeNodeNorm(state_, error);
}

}  // namespace ipstep
