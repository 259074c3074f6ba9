#include "integrators/make_integrator.h"

#include <cstdio>
#include <string>

#include "core/input_error.h"
#include "integrators/backward_euler.h"
#include "integrators/newmark.h"
#include "integrators/quasi_static.h"
#include "integrators/symplectic_euler.h"

namespace ipstep {

const Integrator& MadeIntegrator::common() const {
  if (variational) return *variational;
  return *explicit_integrator;
}

namespace {

std::string FormatParameter(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

}  // namespace

const char* IntegratorNames() { return "backward_euler, newmark, quasi_static, symplectic_euler"; }

MadeIntegrator MakeIntegrator(const IntegratorOptions& o) {
  MadeIntegrator made;
  if (o.name == "backward_euler") {
    made.variational = std::make_unique<BackwardEuler>();
  } else if (o.name == "quasi_static") {
    made.variational = std::make_unique<QuasiStatic>();
  } else if (o.name == "symplectic_euler") {
    made.explicit_integrator = std::make_unique<SymplecticEuler>();
  } else if (o.name == "newmark") {
    // The ranges and why: integrators/newmark.h.
    if (!(o.newmark_beta >= Newmark::kMinBeta && o.newmark_beta <= Newmark::kMaxBeta)) {
      throw InputError("options", "IntegratorOptions.newmark_beta",
                       "must be in [1e-3, 1], got " + FormatParameter(o.newmark_beta) +
                           " (beta -> 0 is the explicit central-difference scheme: the step "
                           "solves for beta h^2 times the acceleration, which round-off swamps; "
                           "use the integrator symplectic_euler for an explicit method)");
    }
    if (!(o.newmark_gamma >= Newmark::kMinGamma && o.newmark_gamma <= Newmark::kMaxGamma)) {
      throw InputError("options", "IntegratorOptions.newmark_gamma",
                       "must be in [0.5, 1], got " + FormatParameter(o.newmark_gamma) +
                           " (gamma < 1/2 amplifies every oscillation at every step size; 1/2 "
                           "is the trapezoidal rule, larger values dissipate)");
    }
    made.variational = std::make_unique<Newmark>(o.newmark_beta, o.newmark_gamma);
  } else {
    throw InputError(
        "options", "IntegratorOptions.name",
        "unknown integrator '" + o.name + "' (choose one of " + IntegratorNames() + ")");
  }
  return made;
}

}  // namespace ipstep
