#include "integrators/integrator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/input_error.h"
#include "integrators/backward_euler.h"
#include "integrators/newmark.h"
#include "integrators/quasi_static.h"
#include "integrators/symplectic_euler.h"

namespace ipstep {

double Integrator::LargestFreeNodeChange(const State& state, const Eigen::VectorXd& before,
                                         const Eigen::VectorXd& after) {
  const int dim = state.dimension;
  double worst = 0.0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (!state.is_free(i)) continue;
    worst = std::max(worst, (after.segment(dim * i, dim) - before.segment(dim * i, dim)).norm());
  }
  return worst;
}

double Integrator::LocalError(const State& before, const State& after, double h) const {
  return 0.5 * h * LargestFreeNodeChange(after, before.v, after.v);
}

void Integrator::Advance(const Eigen::VectorXd&, double, State*) const {
  throw std::logic_error(name() + " is not an explicit integrator");
}

namespace {

std::string FormatParameter(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.6g", value);
  return buffer;
}

}  // namespace

const char* IntegratorNames() { return "backward_euler, newmark, quasi_static, symplectic_euler"; }

std::unique_ptr<Integrator> MakeIntegrator(const IntegratorOptions& o) {
  if (o.name == "backward_euler") return std::make_unique<BackwardEuler>();
  if (o.name == "quasi_static") return std::make_unique<QuasiStatic>();
  if (o.name == "symplectic_euler") return std::make_unique<SymplecticEuler>();
  if (o.name == "newmark") {
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
    return std::make_unique<Newmark>(o.newmark_beta, o.newmark_gamma);
  }
  throw InputError("options", "IntegratorOptions.name",
                   "unknown integrator '" + o.name + "' (choose one of " + IntegratorNames() + ")");
}

}  // namespace ipstep
