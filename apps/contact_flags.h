// Flags overriding contact parameters of a scene's "contact" and "friction"
// effects (docs/contact.md): they become SimulationOptions::effect_overrides
// (sim/simulation.h), the parameters "contact.kappa", "contact.dhat",
// "friction.mu", "friction.iterations".
#pragma once

#include <map>
#include <string>

#include <gflags/gflags.h>
#include <nlohmann/json.hpp>

DECLARE_double(contact_kappa);
DECLARE_double(contact_dhat);
DECLARE_double(friction_mu);
DECLARE_int32(friction_iterations);

namespace ipstep {

struct Scene;

// Adds the given contact flags (range-checked, InputError naming the flag) to
// the effect overrides.
void AddContactFlagOverrides(std::map<std::string, nlohmann::json>* overrides);

// Throws InputError naming the flag when a contact flag is given for a scene
// without the effect it overrides.
void CheckContactFlagsApply(const Scene& scene);

}  // namespace ipstep
