#include "contact/contact_overrides.h"

#include <utility>

namespace ipstep {

namespace {
ContactOverridesProvider& Provider() {
  static auto* provider = new ContactOverridesProvider();
  return *provider;
}
}  // namespace

void SetContactOverridesProvider(ContactOverridesProvider provider) {
  Provider() = std::move(provider);
}

ContactOverrides CurrentContactOverrides() {
  const ContactOverridesProvider& provider = Provider();
  return provider ? provider() : ContactOverrides{};
}

}  // namespace ipstep
