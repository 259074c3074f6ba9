#include "contact/obstacles/read_obstacle.h"

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/plane_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"
#include "core/input_error.h"
#include "core/input_limits.h"

namespace ipstep {

namespace {

// Keys every shape takes besides its own (read after them: the order in which
// errors are found).
const std::vector<std::string> kCommonKeys = {"type",  "velocity",        "angular_velocity",
                                              "until", "rotation_center", "mu"};

std::vector<std::string> KeysOf(std::vector<std::string> own) {
  own.insert(own.end(), kCommonKeys.begin(), kCommonKeys.end());
  return own;
}

Eigen::Vector3d ReadVelocity(const JsonNode& p, int dimension) {
  if (!p.Has("velocity")) return Eigen::Vector3d::Zero();
  return p.Get("velocity").Vector3(dimension, limits::kMaxSpeed, "m/s");
}

// The motion law of moving nodes (core/prescribed_motion.h): a velocity, an
// angular velocity about "rotation_center" (a sphere's "center" is its own),
// or both; "until" stops it.
ObstaclePtr Finish(const JsonNode& p, std::shared_ptr<Obstacle> obstacle) {
  const int dimension = obstacle->dimension();
  if (auto omega = p.Find("angular_velocity")) {
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    if (dimension == 2) {
      w[2] = omega->InRange(-limits::kMaxAngularVelocity, limits::kMaxAngularVelocity, "rad/s");
    } else {
      w = omega->Vector3(3, limits::kMaxAngularVelocity, "rad/s");
    }
    obstacle->set_rotation(  // "rotation_center" is required with it
        w, p.Get("rotation_center").Vector3(dimension, limits::kMaxCoordinate, "m"));
  } else if (p.Has("rotation_center")) {
    p.Get("rotation_center").Fail("a rotation centre without \"angular_velocity\" has no effect");
  }
  if (auto until = p.Find("until")) {
    const double stop = until->InRange(0.0, limits::kMaxDuration, "s", /*min_open=*/true);
    if (!obstacle->is_moving()) {
      until->Fail("an obstacle without \"velocity\" or \"angular_velocity\" does not move");
    }
    obstacle->set_until(stop);
  }
  if (auto mu = p.Find("mu")) {
    obstacle->set_friction_mu(mu->InRange(0.0, limits::kMaxFrictionMu, ""));
  }
  return obstacle;
}

ObstaclePtr ReadPlane(const JsonNode& p, int dimension) {
  p.ExpectObject(KeysOf({"point", "normal"}));
  const Eigen::Vector3d point = p.Get("point").Vector3(dimension, limits::kMaxCoordinate, "m");
  const Eigen::Vector3d normal =
      p.Get("normal").Vector3(dimension, std::numeric_limits<double>::max(), "");
  // stableNorm: |normal|^2 must not overflow (normal [1e300, 1e300]) or underflow.
  const double length = normal.stableNorm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    p.Get("normal").Fail("must not be the zero vector");
  }
  return Finish(p, std::make_shared<PlaneObstacle>(dimension, point, normal / length,
                                                   ReadVelocity(p, dimension), p.path()));
}

ObstaclePtr ReadSphere(const JsonNode& p, int dimension) {
  p.ExpectObject(KeysOf({"center", "radius"}));
  const Eigen::Vector3d center = p.Get("center").Vector3(dimension, limits::kMaxCoordinate, "m");
  const double radius = p.Get("radius").InRange(limits::kMinLength, limits::kMaxCoordinate, "m");
  return Finish(p, std::make_shared<SphereObstacle>(dimension, center, radius,
                                                    ReadVelocity(p, dimension), p.path()));
}

ObstaclePtr ReadBox(const JsonNode& p, int dimension) {
  p.ExpectObject(KeysOf({"min", "max"}));
  const Eigen::Vector3d lower = p.Get("min").Vector3(dimension, limits::kMaxCoordinate, "m");
  const Eigen::Vector3d upper = p.Get("max").Vector3(dimension, limits::kMaxCoordinate, "m");
  for (int k = 0; k < dimension; ++k) {
    if (!(upper[k] > lower[k]))
      p.Get("max").Fail("must be greater than \"min\" in every component");
  }
  return Finish(p, std::make_shared<BoxObstacle>(dimension, lower, upper,
                                                 ReadVelocity(p, dimension), p.path()));
}

}  // namespace

ObstaclePtr ReadObstacle(const JsonNode& p, int dimension) {
  if (!p.Has("type")) p.Get("type");  // throws "required key is missing"
  const std::string type = p.Get("type").String();
  if (type == "plane") return ReadPlane(p, dimension);
  if (type == "sphere" || type == "circle") return ReadSphere(p, dimension);
  if (type == "box") return ReadBox(p, dimension);
  p.Get("type").Fail("unknown obstacle type \"" + ClipInput(type) +
                     "\" (known: plane, sphere, circle, box)");
}

}  // namespace ipstep
