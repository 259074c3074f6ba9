#include "apps/contact_flags.h"

#include <cmath>
#include <string>

#include "apps/command_line.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "problems/scene.h"

DEFINE_double(contact_kappa, 0.0,
              "Fixed barrier stiffness kappa for scenes with contact, in (0, 1e20]; default: the "
              "scene's (adaptive when the scene gives none)");
DEFINE_double(contact_dhat, 0.0,
              "Barrier activation distance d_hat [m] for scenes with contact, in [1e-9, 1e6]; "
              "default: the scene's");
DEFINE_double(friction_mu, 0.0,
              "Friction coefficient for scenes with friction, in [0, 100]; default: the scene's");
DEFINE_int32(friction_iterations, 0,
             "Friction lag iterations per step for scenes with friction, in [1, 100]; default: "
             "the scene's (1 when the scene gives none)");

namespace ipstep {
// Each flag is used only when given; an explicit 0 is out of range, not "unset".
void AddContactFlagOverrides(std::map<std::string, nlohmann::json>* overrides) {
  if (!FlagIsDefault("contact_kappa")) {
    (*overrides)["contact"]["kappa"] =
        CheckFlagRange("contact_kappa", FLAGS_contact_kappa, 0.0, limits::kMaxKappa, "",
                       "the scene's kappa", /*min_open=*/true);
  }
  if (!FlagIsDefault("contact_dhat")) {
    (*overrides)["contact"]["dhat"] =
        CheckFlagRange("contact_dhat", FLAGS_contact_dhat, limits::kMinDhat, limits::kMaxDhat, "m",
                       "the scene's dhat");
  }
  if (!FlagIsDefault("friction_mu")) {
    (*overrides)["friction"]["mu"] = CheckFlagRange("friction_mu", FLAGS_friction_mu, 0.0,
                                                    limits::kMaxFrictionMu, "", "the scene's mu");
  }
  if (!FlagIsDefault("friction_iterations")) {
    (*overrides)["friction"]["iterations"] =
        CheckFlagRange("friction_iterations", FLAGS_friction_iterations, 1,
                       limits::kMaxFrictionIterations, "the scene's iterations");
  }
}

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
