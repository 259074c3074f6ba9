// Command-line overrides of contact parameters (--contact_kappa, --contact_dhat,
// --friction_mu, --friction_iterations). The library does not depend on gflags:
// the programs install a provider (apps/contact_flags.cc) that the "contact" and
// "friction" effects consult when they are built. Without a provider (tests,
// library users) there are no overrides.
#pragma once

#include <functional>
#include <optional>

namespace ipstep {

struct ContactOverrides {
  std::optional<double> kappa;  // fixed barrier stiffness
  std::optional<double> d_hat;
  std::optional<double> mu;
  std::optional<int> friction_iterations;
};

// The provider may throw InputError for invalid values.
using ContactOverridesProvider = std::function<ContactOverrides()>;
void SetContactOverridesProvider(ContactOverridesProvider provider);
ContactOverrides CurrentContactOverrides();

}  // namespace ipstep
