// The "contact" and "friction" effects: strict parsing of their scene
// parameters (every problem is an InputError naming the file and key), flag
// overrides, and construction of the contact state (contact/contact_state.h),
// its step filter (contact/contact_filter.h) and the ContactEffect that owns
// the state (contact/contact_effect.h), which friction receives.
#include "contact/contact_effects.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contact/collision_mesh.h"
#include "contact/contact_effect.h"
#include "contact/contact_filter.h"
#include "contact/contact_state.h"
#include "contact/obstacles/read_obstacle.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "core/json_node.h"

namespace ipstep {

namespace {

using nlohmann::json;

double BoundingBoxDiagonal(const Scene& scene) {
  const int dim = scene.dimension;
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  for (int i = 0; i < scene.num_nodes(); ++i) {
    for (int k = 0; k < dim; ++k) {
      const double c = scene.positions[dim * i + k];
      lo[k] = i == 0 ? c : std::min(lo[k], c);
      hi[k] = i == 0 ? c : std::max(hi[k], c);
    }
  }
  return (hi - lo).norm();
}

std::unique_ptr<Effect> BuildContact(TermBuilder& builder, const json& parameters) {
  const Scene& scene = builder.scene();
  const std::string& source = scene.source;
  const int dim = scene.dimension;
  if (parameters.is_null()) {
    throw InputError(source, "contact",
                     "the \"contact\" effect needs its parameters object (at least "
                     "\"obstacles\" or \"self_contact\")");
  }
  const JsonNode p(parameters, "contact", source);
  p.ExpectObject(
      {"dhat", "kappa", "obstacles", "self_contact", "self_contact_kappa", "self_contact_mu"});
  ContactOptions options;
  const double diagonal = BoundingBoxDiagonal(scene);
  options.d_hat = p.Has("dhat") ? p.Get("dhat").InRange(limits::kMinDhat, limits::kMaxDhat, "m")
                                : 1e-3 * std::max(diagonal, 1.0);
  if (p.Has("kappa")) {
    options.kappa = p.Get("kappa").InRange(0.0, limits::kMaxKappa, "", /*min_open=*/true,
                                           " (omit it for the adaptive stiffness)");
  }
  // Friction coefficients act through the friction effect (its epsilon_v).
  const auto needs_friction = [&](const JsonNode& key) {
    if (!scene.HasEffect("friction")) {
      key.Fail("a friction coefficient needs the \"friction\" effect in \"effects\"");
    }
  };
  if (p.Has("obstacles")) {
    for (const JsonNode& element : p.Get("obstacles").Elements()) {
      if (!element.Has("type")) element.Get("type");
      options.obstacles.push_back(ReadObstacle(element, dim));
      if (element.Has("mu")) needs_friction(element.Get("mu"));
    }
  }
  if (p.Has("self_contact")) {
    options.self_contact = p.Get("self_contact").Bool();
    if (options.self_contact && dim == 3 && scene.surface.triangles.empty()) {
      p.Get("self_contact")
          .Fail(
              "3D self-contact needs a surface of triangles (\"surface\": {\"triangles\": ...}, or "
              "a "
              "3D grid with structural springs)");
    }
  }
  if (auto kappa = p.Find("self_contact_kappa")) {
    options.self_contact_kappa = kappa->InRange(0.0, limits::kMaxKappa, "", /*min_open=*/true);
    if (!options.self_contact) kappa->Fail("has no effect without \"self_contact\": true");
    if (!(options.kappa > 0.0)) {
      kappa->Fail("needs a fixed \"kappa\" (the adaptive stiffness is one value for every pair)");
    }
  }
  if (auto mu = p.Find("self_contact_mu")) {
    options.self_contact_mu = mu->InRange(0.0, limits::kMaxFrictionMu, "");
    if (!options.self_contact) mu->Fail("has no effect without \"self_contact\": true");
    needs_friction(*mu);
  }
  if (options.obstacles.empty() && !options.self_contact) {
    throw InputError(source, "contact",
                     "nothing to collide with: give \"obstacles\" or \"self_contact\": true");
  }

  CollisionMesh surface = BuildCollisionMesh(scene);
  auto state = std::make_unique<ContactState>(builder.potential(), &builder.state(),
                                              std::move(surface), options);
  const std::string penetration =
      state->FindPenetration(builder.state().x.data(), builder.state().time);
  if (!penetration.empty()) {
    throw InputError(source, "contact", "the initial state is not free of contact: " + penetration);
  }
  auto filter = std::make_unique<ContactFilter>(state.get(), builder.state().x);
  auto effect = std::make_unique<ContactEffect>(std::move(state), filter.get());
  builder.AddStepFilter(std::move(filter));
  return effect;
}

std::unique_ptr<Effect> BuildFriction(TermBuilder& builder, const json& parameters) {
  const Scene& scene = builder.scene();
  const std::string& source = scene.source;
  ContactEffect* contact = builder.FindEffect<ContactEffect>();
  if (contact == nullptr) {
    throw InputError(source, "effects", "\"friction\" needs \"contact\" in \"effects\"");
  }
  ContactState* state = &contact->state();
  if (parameters.is_null()) {
    throw InputError(source, "friction", "the \"friction\" effect needs its parameters object");
  }
  const JsonNode p(parameters, "friction", source);
  p.ExpectObject({"mu", "epsilon_v", "iterations"});
  FrictionOptions options;
  options.mu = p.Get("mu").InRange(0.0, limits::kMaxFrictionMu, "");
  if (p.Has("epsilon_v")) {
    options.epsilon_v =
        p.Get("epsilon_v").InRange(limits::kMinEpsilonV, limits::kMaxEpsilonV, "m/s");
  }
  if (p.Has("iterations")) {
    options.iterations = p.Get("iterations").IntegerInRange(1, limits::kMaxFrictionIterations);
  }
  state->EnableFriction(options);
  std::ostringstream out;
  out << "friction: mu " << options.mu;
  for (const ObstaclePtr& o : state->obstacles()) {
    if (o->friction_mu()) out << " (" << o->name() << ": " << *o->friction_mu() << ")";
  }
  if (state->self_contact_mu() >= 0.0) out << " (self-contact: " << state->self_contact_mu() << ")";
  out << ", epsilon_v " << options.epsilon_v << " m/s, " << options.iterations
      << " lag iteration(s) per step";
  return std::make_unique<SummaryEffect>(out.str());
}

}  // namespace

void RegisterContactEffects(EffectRegistry* registry) {
  registry->Register(
      "contact", "IPC barrier contact: obstacles (plane, sphere, box) and self-contact (2D, 3D)",
      BuildContact);
  registry->Register("friction", "smoothed dry friction on contacts (needs contact)", BuildFriction,
                     {"contact"});
}

}  // namespace ipstep
