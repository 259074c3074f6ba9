#include "apps/contact_flags.h"

#include <cmath>
#include <string>

#include "apps/command_line.h"
#include "apps/option_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "problems/scene.h"

// Help text, default and range of each flag: its option row (apps/option_flags.h).
DEFINE_double(contact_kappa, ipstep::FlagDefault<double>("contact_kappa"),
              ipstep::FlagHelp("contact_kappa"));
DEFINE_double(contact_dhat, ipstep::FlagDefault<double>("contact_dhat"),
              ipstep::FlagHelp("contact_dhat"));
DEFINE_double(friction_mu, ipstep::FlagDefault<double>("friction_mu"),
              ipstep::FlagHelp("friction_mu"));
DEFINE_int32(friction_iterations, ipstep::FlagDefault<int>("friction_iterations"),
             ipstep::FlagHelp("friction_iterations"));

namespace ipstep {
// Each flag is used only when given; an explicit 0 is out of range, not "unset".
void AddContactFlagOverrides(std::map<std::string, nlohmann::json>* overrides) {
  const auto given = [](const char* flag) { return !FlagIsDefault(flag); };
  if (given("contact_kappa")) {
    (*overrides)["contact"]["kappa"] = FlagInRowRange("contact_kappa", FLAGS_contact_kappa);
  }
  if (given("contact_dhat")) {
    (*overrides)["contact"]["dhat"] = FlagInRowRange("contact_dhat", FLAGS_contact_dhat);
  }
  if (given("friction_mu")) {
    (*overrides)["friction"]["mu"] = FlagInRowRange("friction_mu", FLAGS_friction_mu);
  }
  if (given("friction_iterations")) {
    (*overrides)["friction"]["iterations"] =
        FlagInRowRange("friction_iterations", FLAGS_friction_iterations);
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
