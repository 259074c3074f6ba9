#include "integrators/integrator.h"

#include <cmath>
#include <stdexcept>

#include "core/input_error.h"
#include "integrators/backward_euler.h"
#include "integrators/newmark.h"
#include "integrators/quasi_static.h"
#include "integrators/symplectic_euler.h"

namespace ipstep {

void Integrator::Advance(const Eigen::VectorXd&, double, State*) const {
  throw std::logic_error(name() + " is not an explicit integrator");
}

const char* IntegratorNames() { return "backward_euler, newmark, quasi_static, symplectic_euler"; }

std::unique_ptr<Integrator> MakeIntegrator(const IntegratorOptions& o) {
  if (o.name == "backward_euler") return std::make_unique<BackwardEuler>();
  if (o.name == "quasi_static") return std::make_unique<QuasiStatic>();
  if (o.name == "symplectic_euler") return std::make_unique<SymplecticEuler>();
  if (o.name == "newmark") {
    if (!std::isfinite(o.newmark_beta) || o.newmark_beta <= 0.0 || o.newmark_beta > 1.0) {
      throw InputError("flag", "--newmark_beta",
                       "must be in (0, 1], got " + std::to_string(o.newmark_beta) +
                           " (beta = 0 is explicit central differences, not a minimisation)");
    }
    if (!std::isfinite(o.newmark_gamma) || o.newmark_gamma <= 0.0 || o.newmark_gamma > 1.0) {
      throw InputError("flag", "--newmark_gamma",
                       "must be in (0, 1], got " + std::to_string(o.newmark_gamma));
    }
    return std::make_unique<Newmark>(o.newmark_beta, o.newmark_gamma);
  }
  throw InputError("flag", "--integrator",
                   "unknown integrator '" + o.name + "' (choose one of " + IntegratorNames() + ")");
}

}  // namespace ipstep
