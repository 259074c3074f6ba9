// Registration of the effects the scene loader reads natively: gravity,
// springs, damping.
#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include "core/input_error.h"
#include "energies/effect_registry.h"
#include "energies/elasticity/elasticity_effect.h"
#include "energies/gravity_effect.h"
#include "energies/gravity_potential.h"
#include "energies/hookean_spring.h"
#include "energies/quartic_spring.h"
#include "energies/rayleigh_mass_damping.h"
#include "energies/rayleigh_stiffness_damping.h"
#include "energies/squared_strain_spring.h"

namespace ipstep {
namespace {

// Offset H of the quasi-static gravity potential: ten scene sizes (at least 10 m).
double GravityOffset(const State& state) {
  const int dim = state.dimension;
  double extent = 1.0;
  for (int k = 0; k < dim; ++k) {
    double lo = 0.0, hi = 0.0;
    for (int i = 0; i < state.num_nodes(); ++i) {
      const double c = state.x[dim * i + k];
      lo = i == 0 ? c : std::min(lo, c);
      hi = i == 0 ? c : std::max(hi, c);
    }
    extent = std::max(extent, hi - lo);
  }
  return 10.0 * extent;
}

std::unique_ptr<Effect> BuildGravity(TermBuilder& builder, const nlohmann::json&) {
  const Scene& scene = builder.scene();
  const State& state = builder.state();
  if (static_cast<int>(scene.gravity.size()) != state.dimension) {
    throw InputError(scene.source, "gravity",
                     "must have " + std::to_string(state.dimension) +
                         " components (the scene's dimension), has " +
                         std::to_string(scene.gravity.size()));
  }
  const Eigen::VectorXd g =
      Eigen::Map<const Eigen::VectorXd>(scene.gravity.data(), state.dimension);
  // With inertia the acceleration goes into the step itself: the variational
  // integrators' predictor, or symplectic Euler's explicit update.
  if (builder.has_inertia()) {
    return std::make_unique<GravityEffect>(
        g, "gravity: a uniform acceleration in the predictor or explicit update (no terms)");
  }
  const double offset = GravityOffset(state);
  int count = 0;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (!state.is_free(i)) continue;
    builder.AddAutoDiff<GravityPotential, 1, 1>(TermKind::kPotential, {i}, builder.context(), i,
                                                state.mass[i], scene.gravity.data(), offset);
    ++count;
  }
  return std::make_unique<GravityEffect>(
      g, "gravity: " + std::to_string(count) + " linear potential terms (quasi-static)");
}

std::string BuildSprings(TermBuilder& builder, const nlohmann::json&) {
  int counts[3] = {0, 0, 0};
  for (const Spring& s : builder.scene().springs) {
    const std::array<int, 2> nodes = {s.i, s.j};
    switch (s.model) {
      case SpringModel::kHookean:
        builder.AddAutoDiff<HookeanSpring, 1, 2>(TermKind::kPotential, nodes, s.stiffness,
                                                 s.rest_length);
        break;
      case SpringModel::kSquaredStrain:
        builder.AddAutoDiff<SquaredStrainSpring, 1, 2>(TermKind::kPotential, nodes, s.stiffness,
                                                       s.rest_length);
        break;
      case SpringModel::kQuartic:
        builder.AddAutoDiff<QuarticSpring, 1, 2>(TermKind::kPotential, nodes, s.stiffness,
                                                 s.rest_length);
        break;
    }
    ++counts[static_cast<int>(s.model)];
  }
  std::ostringstream out;
  out << "springs: " << counts[0] << " hookean, " << counts[1] << " squared_strain, " << counts[2]
      << " quartic";
  return out.str();
}

// Linearised stiffness at the rest length, used by stiffness-proportional damping.
double RestStiffness(const Spring& s) {
  switch (s.model) {
    case SpringModel::kHookean:
      return s.stiffness;
    case SpringModel::kSquaredStrain:
      return 4.0 * s.stiffness;
    case SpringModel::kQuartic:
      return 0.0;
  }
  return 0.0;
}

std::string BuildDamping(TermBuilder& builder, const nlohmann::json&) {
  const Scene& scene = builder.scene();
  const State& state = builder.state();
  const Damping& damping = scene.damping;
  int mass_terms = 0, spring_terms = 0;
  if (damping.mass_proportional > 0.0) {
    for (int i = 0; i < state.num_nodes(); ++i) {
      if (!state.is_free(i)) continue;
      builder.AddAutoDiff<RayleighMassDamping, kOneResidualPerCoordinate, 1>(
          TermKind::kDissipation, {i}, builder.context(), i,
          damping.mass_proportional * state.mass[i]);
      ++mass_terms;
    }
  }
  if (damping.stiffness_proportional > 0.0) {
    if (!scene.HasEffect("springs")) {
      throw InputError(scene.source, "damping.stiffness_proportional",
                       "needs the 'springs' effect (it damps spring length rates)");
    }
    for (const Spring& s : scene.springs) {
      const double k = RestStiffness(s);
      if (k <= 0.0) continue;
      builder.AddAutoDiff<RayleighStiffnessDamping, 1, 2>(TermKind::kDissipation, {s.i, s.j},
                                                          builder.context(), s.i, s.j,
                                                          damping.stiffness_proportional * k);
      ++spring_terms;
    }
  }
  return "damping: " + std::to_string(mass_terms) + " mass-proportional, " +
         std::to_string(spring_terms) + " stiffness-proportional terms";
}

}  // namespace

void RegisterBuiltinEffects(EffectRegistry* registry) {
  registry->Register("gravity",
                     "uniform gravity (an acceleration in the step; quasi-static: terms)",
                     BuildGravity);
  registry->Register("springs", "spring networks: hookean, squared_strain, quartic", BuildSprings);
  registry->Register("damping", "Rayleigh dissipation, mass- and stiffness-proportional",
                     BuildDamping);
}

}  // namespace ipstep
