// When a run has diverged: the one definition used by ipstep_compare (its
// table), ipstep_bench (the CSV's status) and bench/plot_benchmarks.py (which
// leaves diverged runs out of its plots; it repeats the bound below for CSV
// files written before the status existed).
//
// A run has diverged when a position, velocity or energy became non-finite, or
// when its total energy moved away from the initial energy by more than
// kDivergedEnergyRatio times the initial energy's magnitude:
//   |E_n - E_0| > 1e6 |E_0|   (E_0 != 0; for E_0 = 0 only the first rule).
// A stable run changes its energy by at most a few times |E_0| (dissipation,
// work of moving obstacles); an explicit integrator past its stability limit
// grows it geometrically (symplectic Euler on the cloth at dt = 1/60 s: 1e150).
#pragma once

#include <cmath>

namespace ipstep {

constexpr double kDivergedEnergyRatio = 1e6;
// The rule in words, for reports.
constexpr const char* kDivergedRule =
    "a position, velocity or energy became non-finite, or |E - E0| > 1e6 |E0|";

// True if a run whose initial total energy is `initial_energy` has diverged
// at a step with total energy `energy` and a state that is (not) `finite`.
inline bool RunDiverged(double initial_energy, double energy, bool finite_state) {
  if (!finite_state || !std::isfinite(energy) || !std::isfinite(initial_energy)) return true;
  return initial_energy != 0.0 &&
         std::abs(energy - initial_energy) > kDivergedEnergyRatio * std::abs(initial_energy);
}

}  // namespace ipstep
