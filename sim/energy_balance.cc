#include "sim/energy_balance.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ipstep {

bool MeasureEnergy(const IncrementalPotential& potential, const State& state,
                   const Eigen::VectorXd& gravity, bool has_inertia, double impulsive_factor,
                   bool prescribed_motion, EnergyPoint* point) {
  if (!ComputeEnergies(potential, state, gravity, has_inertia, impulsive_factor, &point->energy,
                       prescribed_motion ? &point->gradient : nullptr)) {
    return false;
  }
  const int dim = state.dimension;
  double gravity_potential = 0.0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    gravity_potential -= state.mass[i] * gravity.dot(state.x.segment(dim * i, dim));
  }
  point->potential_without_gravity = point->energy.potential - gravity_potential;
  point->x = state.x;
  return std::isfinite(point->energy.total()) && std::isfinite(point->potential_without_gravity);
}

EnergyBalance BalanceOf(const EnergyPoint& start, const EnergyPoint& end, const State& state,
                        const Eigen::VectorXd& gravity, double filter_work,
                        double tolerance_per_h) {
  EnergyBalance b;
  b.start = start.energy.total();
  b.end = end.energy.total();
  b.work = filter_work;
  const int dim = state.dimension;
  if (start.gradient.size() == state.num_dofs() && end.gradient.size() == state.num_dofs()) {
    for (int i = 0; i < state.num_nodes(); ++i) {
      if (state.is_free(i)) continue;
      const auto segment = [&](const Eigen::VectorXd& v) { return v.segment(dim * i, dim); };
      b.work +=
          0.5 *
          (segment(start.gradient) + segment(end.gradient)).dot(segment(end.x) - segment(start.x));
    }
  }
  double gravity_work = 0.0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (!state.is_free(i)) continue;
    // An expression over the two positions, not a copy: no allocation per node.
    const auto dx = end.x.segment(dim * i, dim) - start.x.segment(dim * i, dim);
    b.floor += state.mass[i] * tolerance_per_h * dx.norm();
    if (gravity.size() == dim) gravity_work += state.mass[i] * gravity.dot(dx);
  }
  b.scale = start.energy.kinetic + std::abs(start.potential_without_gravity) + std::abs(b.work) +
            std::abs(gravity_work);
  return b;
}

RunEnergyBalance RunEnergyBalance::After(const EnergyBalance& step) const {
  RunEnergyBalance run;
  run.growth = growth + step.growth();
  run.scale = std::max(scale, step.scale - std::max(0.0, growth));
  run.floor = floor + step.floor;
  return run;
}

std::string RunEnergyBalance::Describe() const {
  char text[160];
  std::snprintf(text, sizeof(text),
                "energy growth over the run: %+.3g J (%.3g %% of the energy in motion, %.3g J)",
                growth, scale > 0.0 ? 100.0 * growth / scale : INFINITY, scale);
  return text;
}

std::string EnergyBalance::Describe() const {
  char text[160];
  std::snprintf(text, sizeof(text),
                "energy growth: %+.3g J (%.3g %% of the energy in motion, %.3g J)", growth(),
                scale > 0.0 ? 100.0 * growth() / scale : INFINITY, scale);
  return text;
}

}  // namespace ipstep
