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
    if (!stiff_mode_filter_) {
      stiff_mode_filter_ =
          std::make_unique<StiffModeFilter>(potential_.get(), &state_, options_.optimizer);
    }
    const double raw = Integrator::LargestFreeNodeNorm(state_, error);
    // A failed filter (a term not evaluable, a failed factorisation) keeps
    // the raw estimate: the conservative one.
    const bool filtered = stiff_mode_filter_->Apply(state_.x, &error);
    VLOG(2) << "local error: raw " << raw << ", filtered "
            << (filtered ? std::to_string(Integrator::LargestFreeNodeNorm(state_, error))
                         : std::string("failed"));
  }
  return Integrator::LargestFreeNodeNorm(state_, error);
}

}  // namespace ipstep
