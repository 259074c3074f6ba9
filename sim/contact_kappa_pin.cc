#include "sim/contact_kappa_pin.h"

#include "contact/contact_effect.h"
#include "sim/run_trajectory.h"

namespace ipstep {

double PinAdaptiveContactKappa(const Scene& scene, SimulationOptions* options) {
  if (!scene.HasEffect("contact")) return 0.0;  // (no simulation to build)
  Simulation sim(scene, *options);
  const ContactEffect* contact = sim.FindEffect<ContactEffect>();
  if (contact == nullptr || !contact->state().adaptive_kappa()) return 0.0;
  RunOptions run;
  run.stop_on_divergence = true;
  RunTrajectory(sim, run);
  const double kappa = contact->state().kappa();
  options->effect_overrides["contact"]["kappa"] = kappa;
  return kappa;
}

}  // namespace ipstep
