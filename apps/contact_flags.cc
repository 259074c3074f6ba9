#include "apps/contact_flags.h"

#include <cmath>
#include <string>

#include "apps/command_line.h"
#include "contact/contact_overrides.h"
#include "core/input_error.h"
#include "problems/scene.h"

DEFINE_double(contact_kappa, 0.0,
              "Fixed barrier stiffness kappa for scenes with contact (> 0); 0: the scene's "
              "(adaptive when the scene gives none)");
DEFINE_double(contact_dhat, 0.0, "Barrier activation distance d_hat [m] (> 0); 0: the scene's");
DEFINE_double(friction_mu, 0.0,
              "Friction coefficient (>= 0) for scenes with friction; default: the scene's");
DEFINE_int32(friction_iterations, 0,
             "Friction lag iterations per step (>= 1); 0: the scene's (default 1)");

namespace ipstep {
namespace {

ContactOverrides OverridesFromFlags() {
  ContactOverrides o;
  if (!FlagIsDefault("contact_kappa")) {
    if (!std::isfinite(FLAGS_contact_kappa) || !(FLAGS_contact_kappa > 0.0)) {
      throw InputError("flag", "--contact_kappa", "must be a finite number > 0");
    }
    o.kappa = FLAGS_contact_kappa;
  }
  if (!FlagIsDefault("contact_dhat")) {
    if (!std::isfinite(FLAGS_contact_dhat) || !(FLAGS_contact_dhat > 0.0)) {
      throw InputError("flag", "--contact_dhat", "must be a finite number > 0");
    }
    o.d_hat = FLAGS_contact_dhat;
  }
  if (!FlagIsDefault("friction_mu")) {
    if (!std::isfinite(FLAGS_friction_mu) || !(FLAGS_friction_mu >= 0.0)) {
      throw InputError("flag", "--friction_mu", "must be a finite number >= 0");
    }
    o.mu = FLAGS_friction_mu;
  }
  if (!FlagIsDefault("friction_iterations")) {
    if (FLAGS_friction_iterations < 1 || FLAGS_friction_iterations > 100) {
      throw InputError("flag", "--friction_iterations", "must be an integer in [1, 100]");
    }
    o.friction_iterations = FLAGS_friction_iterations;
  }
  return o;
}

// Installed before main(): the flags are read when a scene's effects are built.
const bool kInstalled = [] {
  SetContactOverridesProvider(OverridesFromFlags);
  return true;
}();

}  // namespace

void CheckContactFlagsApply(const Scene& scene) {
  struct {
    const char* flag;
    const char* effect;
  } const uses[] = {{"contact_kappa", "contact"},
                    {"contact_dhat", "contact"},
                    {"friction_mu", "friction"},
                    {"friction_iterations", "friction"}};
  for (const auto& use : uses) {
    if (!FlagIsDefault(use.flag) && !scene.HasEffect(use.effect)) {
      throw InputError("flag", std::string("--") + use.flag,
                       "applies to scenes with the '" + std::string(use.effect) +
                           "' effect; scene " + scene.source + " has none");
    }
  }
}

}  // namespace ipstep
