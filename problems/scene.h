// A scene: the nodes, their masses and initial state, the springs, the
// boundary conditions and the list of effects (energy families) to build.
// Scenes are plain data; problems/scene_loader.h reads them from JSON.
#pragma once

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/prescribed_motion.h"

namespace ipstep {

struct Solid;  // problems/solid.h

enum class SpringModel {
  kHookean,        // k/2 (|d| - L)^2
  kSquaredStrain,  // k/2 L^2 (|d|^2/L^2 - 1)^2
  kQuartic,        // c (|d| - L)^4   (c stored in `stiffness`)
};

const char* SpringModelName(SpringModel model);

struct Spring {
  int i = 0;
  int j = 0;
  SpringModel model = SpringModel::kHookean;
  double stiffness = 0.0;    // k [N/m] (Hookean, squared strain) or c [N/m^3] (quartic)
  double rest_length = 0.0;  // L [m]; the loader fills in the initial length when omitted
};

// A node moved along a prescribed constant velocity (moving Dirichlet condition):
// x(t) = x(0) + velocity * t.
// A node moved rigidly (core/prescribed_motion.h): translated by `velocity` and
// turned by `angular_velocity` about `center` (which moves with the
// velocity), until `until`, after which it holds still.
struct MovingNode {
  int node = 0;
  std::vector<double> velocity;            // size dimension [m/s]
  std::vector<double> angular_velocity{};  // empty (none), 1 (2D, about z) or 3 (3D) [rad/s]
  std::vector<double> center{};            // size dimension with angular_velocity [m]
  double until = std::numeric_limits<double>::infinity();  // [s]
};

// The node's motion in the simulation's terms (3-vectors, 2D padded with z = 0).
PrescribedMotion MotionOf(const MovingNode& moving, int dimension);

// Rayleigh dissipation R = 1/2 v^T B v with
// B = mass_proportional * M + stiffness_proportional * K_springs (on spring length rates).
struct Damping {
  double mass_proportional = 0.0;       // alpha [1/s]
  double stiffness_proportional = 0.0;  // beta [s]
};

// The contact surface a scene declares (key "surface"; the "grid", "chain"
// and "particle" generators declare theirs). contact/collision_mesh.h builds
// the collision mesh from it.
struct Surface {
  std::vector<std::array<int, 2>> edges;      // 2D boundary edges (3D: curves)
  std::vector<std::array<int, 3>> triangles;  // 3D surface triangles
  std::vector<int> points;                    // nodes in contact on their own (particles)
  bool declared = false;
};

// Effects whose data the scene loader reads itself (top-level keys
// "gravity", "springs"/"grid"/"chain", "damping"); energies/builtin_effects.cc
// builds them. Every other effect's parameters are the top-level object under
// its name.
const std::vector<std::string>& SceneNativeEffects();

struct Scene {
  std::string name;    // scene name (file stem or built-in name)
  std::string source;  // file path it was read from, for error messages
  int dimension = 2;   // 2 or 3

  // Per node, flattened: positions[dimension * i + k].
  std::vector<double> positions;   // [m]
  std::vector<double> velocities;  // [m/s], same size as positions
  std::vector<double> masses;      // [kg], one per node, > 0

  std::vector<Spring> springs;
  Surface surface;
  // An elastic solid ("solid": mesh and material) whose nodes are the scene's
  // nodes; its energy is the "elasticity" effect. Null without one.
  std::shared_ptr<const Solid> solid;
  std::vector<int> pinned;  // node indices held fixed
  std::vector<MovingNode> moving;

  std::vector<double> gravity;  // size dimension [m/s^2]; empty when unset
  Damping damping;

  // Effects the scene calls for, in file order: "gravity", "springs", "damping",
  // or the name of a user-registered effect. Only these energies are built.
  std::vector<std::string> effects;
  // Parameters of user-registered effects: top-level object whose key is the
  // effect's name.
  std::map<std::string, nlohmann::json> effect_parameters;

  // Run defaults a scene may carry (flags override them).
  double time_step = 0.01;  // [s]
  int steps = 100;

  int num_nodes() const { return static_cast<int>(masses.size()); }
  bool HasEffect(const std::string& effect) const;
};

}  // namespace ipstep
