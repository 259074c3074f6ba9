// The "contact" and "friction" effects: strict parsing of their scene
// parameters (every problem is an InputError naming the file and key), flag
// overrides, and construction of the contact filter (contact/contact_filter.h).
#include "contact/contact_effects.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "contact/collision_mesh.h"
#include "contact/contact_filter.h"
#include "contact/contact_overrides.h"
#include "core/input_error.h"
#include "core/input_limits.h"

namespace ipstep {

namespace {

using nlohmann::json;

std::string Format(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value);
  // Shortest form that reads back the same.
  for (int precision = 1; precision <= 17; ++precision) {
    char shorter[32];
    std::snprintf(shorter, sizeof(shorter), "%.*g", precision, value);
    if (std::strtod(shorter, nullptr) == value) return shorter;
  }
  return buffer;
}

// A JSON value with its key path, for messages "file: contact.dhat: ...".
class Param {
 public:
  Param(const json& value, std::string path, const std::string& source)
      : value_(value), path_(std::move(path)), source_(source) {}

  [[noreturn]] void Fail(const std::string& what) const { throw InputError(source_, path_, what); }

  void ExpectObject(const std::vector<std::string>& allowed) const {
    if (!value_.is_object()) Fail("must be an object");
    for (const auto& item : value_.items()) {
      bool known = false;
      for (const std::string& key : allowed) known |= key == item.key();
      if (!known) {
        std::string list;
        for (const std::string& key : allowed) list += (list.empty() ? "" : ", ") + key;
        throw InputError(source_, path_ + "." + item.key(),
                         "unknown key (allowed keys: " + list + ")");
      }
    }
  }
  bool Has(const std::string& key) const { return value_.is_object() && value_.contains(key); }
  Param Get(const std::string& key) const {
    if (!Has(key)) throw InputError(source_, path_ + "." + key, "required key is missing");
    return Param(value_.at(key), path_ + "." + key, source_);
  }
  double Number() const {
    if (!value_.is_number()) Fail("must be a number");
    const double v = value_.get<double>();
    if (!std::isfinite(v)) Fail("must be finite");
    return v;
  }
  // A number in [min, max] (or (min, max] with `min_open`).
  double InRange(double min, double max, const std::string& unit, bool min_open = false,
                 const std::string& note = "") const {
    const double v = Number();
    if (!(min_open ? v > min : v >= min) || !(v <= max)) {
      Fail("must be in " + limits::RangeText(min, max, unit, min_open) + note + ", got " +
           Format(v));
    }
    return v;
  }
  bool Bool() const {
    if (!value_.is_boolean()) Fail("must be true or false");
    return value_.get<bool>();
  }
  std::string String() const {
    if (!value_.is_string()) Fail("must be a string");
    return value_.get<std::string>();
  }
  int Integer(int min, int max) const {
    if (!value_.is_number_integer()) Fail("must be an integer");
    const auto v = value_.get<int64_t>();
    if (v < min || v > max) {
      Fail("must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
           "], got " + std::to_string(v));
    }
    return static_cast<int>(v);
  }
  // `dimension` numbers, each in [-bound, bound].
  Eigen::Vector3d Vector(int dimension, double bound, const std::string& unit) const {
    if (!value_.is_array() || static_cast<int>(value_.size()) != dimension) {
      Fail("must be an array of " + std::to_string(dimension) + " numbers (the scene's dimension)");
    }
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < dimension; ++k) {
      v[k] = Param(value_[k], path_ + "[" + std::to_string(k) + "]", source_)
                 .InRange(-bound, bound, unit);
    }
    return v;
  }
  Eigen::Vector3d Position(int dimension) const {
    return Vector(dimension, limits::kMaxCoordinate, "m");
  }
  std::vector<Param> Elements() const {
    if (!value_.is_array()) Fail("must be an array");
    std::vector<Param> list;
    for (size_t i = 0; i < value_.size(); ++i) {
      list.emplace_back(value_[i], path_ + "[" + std::to_string(i) + "]", source_);
    }
    return list;
  }
  const std::string& path() const { return path_; }

 private:
  const json& value_;
  std::string path_;
  const std::string& source_;
};

Obstacle ReadObstacle(const Param& p, int dimension) {
  if (!p.Has("type")) p.Get("type");  // throws "required key is missing"
  const std::string type = p.Get("type").String();
  Obstacle o;
  o.dimension = dimension;
  o.name = p.path();
  if (type == "plane") {
    p.ExpectObject({"type", "point", "normal", "velocity"});
    o.type = ObstacleType::kPlane;
    o.point = p.Get("point").Position(dimension);
    const Eigen::Vector3d normal =
        p.Get("normal").Vector(dimension, std::numeric_limits<double>::max(), "");
    // stableNorm: |normal|^2 must not overflow (normal [1e300, 1e300]) or underflow.
    const double length = normal.stableNorm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      p.Get("normal").Fail("must not be the zero vector");
    }
    o.normal = normal / length;
  } else if (type == "sphere" || type == "circle") {
    p.ExpectObject({"type", "center", "radius", "velocity"});
    o.type = ObstacleType::kSphere;
    o.point = p.Get("center").Position(dimension);
    o.radius = p.Get("radius").InRange(limits::kMinLength, limits::kMaxCoordinate, "m");
  } else if (type == "box") {
    p.ExpectObject({"type", "min", "max", "velocity"});
    o.type = ObstacleType::kBox;
    o.lower = p.Get("min").Position(dimension);
    o.upper = p.Get("max").Position(dimension);
    for (int k = 0; k < dimension; ++k) {
      if (!(o.upper[k] > o.lower[k])) {
        p.Get("max").Fail("must be greater than \"min\" in every component");
      }
    }
  } else {
    p.Get("type").Fail("unknown obstacle type \"" + ClipInput(type) +
                       "\" (known: plane, sphere, circle, box)");
  }
  if (p.Has("velocity")) o.velocity = p.Get("velocity").Vector(dimension, limits::kMaxSpeed, "m/s");
  return o;
}

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

std::string BuildContact(TermBuilder& builder, const json& parameters) {
  const Scene& scene = builder.scene();
  const std::string& source = scene.source;
  const int dim = scene.dimension;
  if (parameters.is_null()) {
    throw InputError(source, "contact",
                     "the \"contact\" effect needs its parameters object (at least "
                     "\"obstacles\" or \"self_contact\")");
  }
  const Param p(parameters, "contact", source);
  p.ExpectObject({"dhat", "kappa", "obstacles", "self_contact"});
  ContactOptions options;
  const double diagonal = BoundingBoxDiagonal(scene);
  options.d_hat = p.Has("dhat") ? p.Get("dhat").InRange(limits::kMinDhat, limits::kMaxDhat, "m")
                                : 1e-3 * std::max(diagonal, 1.0);
  if (p.Has("kappa")) {
    options.kappa = p.Get("kappa").InRange(0.0, limits::kMaxKappa, "", /*min_open=*/true,
                                           " (omit it for the adaptive stiffness)");
  }
  if (p.Has("obstacles")) {
    for (const Param& element : p.Get("obstacles").Elements()) {
      if (!element.Has("type")) element.Get("type");
      options.obstacles.push_back(ReadObstacle(element, dim));
    }
  }
  if (p.Has("self_contact")) {
    options.self_contact = p.Get("self_contact").Bool();
    if (options.self_contact && dim != 2) {
      p.Get("self_contact").Fail("self-contact is implemented in 2D only");
    }
  }
  if (options.obstacles.empty() && !options.self_contact) {
    throw InputError(source, "contact",
                     "nothing to collide with: give \"obstacles\" or \"self_contact\": true");
  }
  const ContactOverrides overrides = CurrentContactOverrides();
  if (overrides.d_hat) options.d_hat = *overrides.d_hat;
  if (overrides.kappa) options.kappa = *overrides.kappa;

  CollisionMesh surface = BuildCollisionMesh(scene);
  auto filter = std::make_unique<ContactFilter>(builder.potential(), &builder.state(),
                                                std::move(surface), options);
  const std::string penetration =
      filter->FindPenetration(builder.state().x.data(), builder.state().time);
  if (!penetration.empty()) {
    throw InputError(source, "contact", "the initial state is not free of contact: " + penetration);
  }
  const std::string summary = filter->Summary();
  builder.AddStepFilter(std::move(filter));
  return summary;
}

std::string BuildFriction(TermBuilder& builder, const json& parameters) {
  const Scene& scene = builder.scene();
  const std::string& source = scene.source;
  ContactFilter* filter = nullptr;
  for (const auto& step_filter : builder.potential()->step_filters()) {
    if (auto* m = dynamic_cast<ContactFilter*>(step_filter.get())) filter = m;
  }
  if (filter == nullptr) {
    throw InputError(source, "effects", "\"friction\" needs \"contact\" listed before it");
  }
  if (parameters.is_null()) {
    throw InputError(source, "friction", "the \"friction\" effect needs its parameters object");
  }
  const Param p(parameters, "friction", source);
  p.ExpectObject({"mu", "epsilon_v", "iterations"});
  FrictionOptions options;
  options.mu = p.Get("mu").InRange(0.0, limits::kMaxFrictionMu, "");
  if (p.Has("epsilon_v")) {
    options.epsilon_v =
        p.Get("epsilon_v").InRange(limits::kMinEpsilonV, limits::kMaxEpsilonV, "m/s");
  }
  if (p.Has("iterations")) {
    options.iterations = p.Get("iterations").Integer(1, limits::kMaxFrictionIterations);
  }
  const ContactOverrides overrides = CurrentContactOverrides();
  if (overrides.mu) options.mu = *overrides.mu;
  if (overrides.friction_iterations) options.iterations = *overrides.friction_iterations;
  filter->EnableFriction(options);
  std::ostringstream out;
  out << "friction: mu " << options.mu << ", epsilon_v " << options.epsilon_v << " m/s, "
      << options.iterations << " lag iteration(s) per step";
  return out.str();
}

}  // namespace

void RegisterContactEffects(EffectRegistry* registry) {
  registry->Register("contact",
                     "IPC barrier contact: obstacles (plane, sphere, box) and 2D self-contact",
                     BuildContact);
  registry->Register("friction", "smoothed dry friction on contacts (needs contact)",
                     BuildFriction);
}

}  // namespace ipstep
