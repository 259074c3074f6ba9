// Building a simulation (sim/simulation.h): its options checked, the state
// from the scene, the incremental potential from the integrator's inertia and
// the scene's effects (built in EffectBuildOrder, energies/effect_order.h, and
// kept as Effect objects), and the step solver. Stepping is in simulation.cc.
#include "sim/simulation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "energies/effect_order.h"
#include "energies/effect_registry.h"
#include "energies/gravity_effect.h"
#include "energies/inertia.h"
#include "energies/term_builder.h"
#include "sim/default_effects.h"
#include "sim/simulation_option_table.h"
#include "sim/stiff_mode_filter.h"  // complete for the constructor's cleanup

namespace ipstep {

Simulation::Simulation(const Scene& scene, const SimulationOptions& options)
    : scene_(scene), options_(options) {
  CheckSimulationOptionRanges(options);
  time_step_ = options.time_step > 0.0 ? options.time_step : scene.time_step;
  steps_ = options.steps >= 0 ? options.steps : scene.steps;
  if (!(time_step_ >= limits::kMinTimeStep && time_step_ <= limits::kMaxTimeStep)) {
    throw InputError("options", "SimulationOptions.time_step",
                     "must be in " +
                         limits::RangeText(limits::kMinTimeStep, limits::kMaxTimeStep, "s") +
                         ", got " + limits::FormatLimit(time_step_));
  }
  if (options.t_end != 0.0) {
    if (options.steps >= 0) {
      throw InputError("options", "SimulationOptions.t_end",
                       "give the steps or the end time, not both");
    }
    const double steps = std::round(options.t_end / time_step_);
    if (!(steps >= 1.0) || std::abs(steps * time_step_ - options.t_end) > 1e-9 * options.t_end) {
      const double fit = options.t_end / std::max(1.0, std::ceil(options.t_end / time_step_));
      throw InputError("options", "SimulationOptions.t_end",
                       limits::FormatLimit(options.t_end) +
                           " s is not a whole number of steps of " +
                           limits::FormatLimit(time_step_) + " s (" +
                           limits::FormatLimit(options.t_end / time_step_) +
                           "); a step that fits: " + limits::FormatLimit(fit) + " s");
    }
    steps_ = static_cast<int>(std::min(steps, static_cast<double>(limits::kMaxSteps) + 1.0));
  }
  if (!(options.accept_residual >= 0.0 && std::isfinite(options.accept_residual))) {
    throw InputError(
        "options", "SimulationOptions.accept_residual",
        "must be a finite number >= 0 [m/s], got " + limits::FormatLimit(options.accept_residual));
  }
  if (steps_ > limits::kMaxSteps) {
    throw InputError(
        "options", "SimulationOptions.steps",
        "must be in [0, " + std::to_string(limits::kMaxSteps) + "], got " + std::to_string(steps_));
  }
  integrator_ = MakeIntegrator(options.integrator);
  BuildState();
  BuildPotential();
  if (const GravityEffect* gravity = FindEffect<GravityEffect>()) {
    gravity_ = gravity->acceleration();
  }
  if (const VariationalIntegrator* variational = integrator_.variational.get()) {
    solver_ = MakeStepSolver(potential_.get(), &state_, options.optimizer);
    if (!variational->InitializeState(potential_.get(), gravity_, &state_)) {
      throw InputError(scene_.source, "positions",
                       "the energies cannot be evaluated at the initial state");
    }
  } else {
    ValidateOptimizerOptions(options.optimizer);
  }
}

void Simulation::BuildState() {
  const int dim = scene_.dimension;
  const int n = scene_.num_nodes();
  state_.dimension = dim;
  state_.x = Eigen::Map<const Eigen::VectorXd>(scene_.positions.data(), dim * n);
  state_.v = Eigen::Map<const Eigen::VectorXd>(scene_.velocities.data(), dim * n);
  state_.a = Eigen::VectorXd::Zero(dim * n);
  state_.mass = Eigen::Map<const Eigen::VectorXd>(scene_.masses.data(), n);
  state_.x0 = state_.x;
  state_.motion.assign(n, PrescribedMotion());
  state_.kind.assign(n, NodeKind::kFree);
  for (int i : scene_.pinned) state_.kind[i] = NodeKind::kPinned;
  for (const MovingNode& m : scene_.moving) {
    state_.kind[m.node] = NodeKind::kMoving;
    state_.motion[m.node] = MotionOf(m, dim);
  }
  state_.PrescribedVelocities(0.0, &state_.v);
  gravity_ = Eigen::VectorXd::Zero(dim);  // the gravity effect's, once built
}

void Simulation::BuildPotential() {
  potential_ = std::make_unique<IncrementalPotential>(state_.dimension, state_.num_nodes());
  integrator().SetWeights(time_step_, &potential_->context());
  TermBuilder builder(scene_, state_, integrator().has_inertia(), potential_.get(), &effects_);
  // Inertia terms where the weights weigh them: not for quasi-static (no
  // inertia) nor for an explicit integrator (forces only).
  if (potential_->context().inertia_weight > 0.0) {
    builder.set_family("inertia");
    for (int i = 0; i < state_.num_nodes(); ++i) {
      if (!state_.is_free(i)) continue;
      builder.AddAutoDiff<InertiaResidual, kOneResidualPerCoordinate, 1>(
          TermKind::kInertia, {i}, builder.context(), i, state_.mass[i]);
    }
  }
  const EffectRegistry& registry = options_.effects ? *options_.effects : DefaultEffects();
  for (const auto& [effect, values] : options_.effect_overrides) {
    if (!scene_.HasEffect(effect)) {
      throw InputError("options", "effect_overrides." + effect,
                       "scene " + scene_.source + " does not list the effect '" + effect + "'");
    }
    if (!values.is_object()) {
      throw InputError("options", "effect_overrides." + effect, "must be an object of parameters");
    }
  }
  for (const std::string& effect : scene_.effects) {
    if (!registry.Has(effect)) {
      throw InputError(scene_.source, "effects", "effect '" + effect + "' is not registered");
    }
  }
  effect_summaries_.assign(scene_.effects.size(), "");
  for (const size_t index : EffectBuildOrder(registry, scene_.effects, scene_.source)) {
    const std::string& effect = scene_.effects[index];
    auto it = scene_.effect_parameters.find(effect);
    nlohmann::json parameters =
        it == scene_.effect_parameters.end() ? nlohmann::json() : it->second;
    auto override_it = options_.effect_overrides.find(effect);
    if (override_it != options_.effect_overrides.end() && parameters.is_object()) {
      for (const auto& item : override_it->second.items()) parameters[item.key()] = item.value();
    }
    builder.set_family(effect);
    std::unique_ptr<Effect> built_effect = registry.Get(effect).factory(builder, parameters);
    if (built_effect == nullptr) {
      throw std::logic_error("the factory of effect '" + effect + "' returned no effect");
    }
    effect_summaries_[index] = built_effect->Summary();
    effects_.Add(effect, std::move(built_effect));
  }
}

}  // namespace ipstep
