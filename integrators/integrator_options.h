// Which integrator MakeIntegrator (integrators/make_integrator.h) makes, and
// its parameters; the programs' flags are integrators/integrator_option_table.h.
#pragma once

#include <string>

namespace ipstep {

struct IntegratorOptions {
  std::string name =
      "backward_euler";  // backward_euler | newmark | quasi_static | symplectic_euler
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
};

}  // namespace ipstep
