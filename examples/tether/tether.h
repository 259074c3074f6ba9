// A tether: every free node is pulled towards a point p with the energy
// e = k/2 |x - p|^2, written as the residual r = sqrt(k) (x - p) (e = 1/2 |r|^2).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "energies/effect_registry.h"
#include "energies/term_builder.h"

namespace tether {

template <int kDim>  // 2 or 3: ipstep instantiates both
struct Tether {
  Tether(double stiffness, const std::array<double, 3>& point)
      : sqrt_k(std::sqrt(stiffness)), point(point) {}

  // One `const T*` per node the term touches (here one), then the residuals.
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int k = 0; k < kDim; ++k) residual[k] = sqrt_k * (x[k] - point[k]);
    return true;  // false where the energy is undefined (an infeasible point)
  }

  double sqrt_k;
  std::array<double, 3> point;
};

// The effect's factory: reads the scene's "tether" object, adds one term per
// free node and returns the line of the "active effects" report.
std::string BuildTether(ipstep::TermBuilder& builder, const nlohmann::json& parameters);

// Registers the effect "tether" in `registry` (once, before scenes are loaded).
void RegisterTether(ipstep::EffectRegistry& registry);

}  // namespace tether
