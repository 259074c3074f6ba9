// Flags overriding contact parameters of a scene's "contact" and "friction"
// effects (docs/contact.md). apps/contact_flags.cc installs them as the contact
// overrides provider (contact/contact_overrides.h) of every program that links
// ipstep_flags.
#pragma once

#include <gflags/gflags.h>

DECLARE_double(contact_kappa);
DECLARE_double(contact_dhat);
DECLARE_double(friction_mu);
DECLARE_int32(friction_iterations);

namespace ipstep {

struct Scene;

// Throws InputError naming the flag when a contact flag is given for a scene
// without the effect it overrides.
void CheckContactFlagsApply(const Scene& scene);

}  // namespace ipstep
