// The integrator of IntegratorOptions, and which kind it is. MadeIntegrator
// holds exactly one of a VariationalIntegrator and an ExplicitIntegrator: the
// caller (Simulation) takes its step path from which one is set, once, so no
// integrator carries a trait saying what it is and none needs a cast.
#pragma once

#include <memory>

#include "integrators/explicit_integrator.h"
#include "integrators/integrator.h"
#include "integrators/integrator_options.h"
#include "integrators/variational_integrator.h"

namespace ipstep {

struct MadeIntegrator {
  std::unique_ptr<VariationalIntegrator> variational;       // set for a variational scheme,
  std::unique_ptr<ExplicitIntegrator> explicit_integrator;  // or this one for an explicit one
  // The part both kinds have (name, weights, energy accounting, error control).
  const Integrator& common() const;
};

// Throws InputError naming the option (IntegratorOptions.name, .newmark_beta,
// .newmark_gamma).
MadeIntegrator MakeIntegrator(const IntegratorOptions& options);
const char* IntegratorNames();  // "backward_euler, newmark, quasi_static, symplectic_euler"

}  // namespace ipstep
