// The ranges within which ipstep accepts physical inputs (scene keys, contact
// parameters) and the programs' size-like flags. Anything outside is an
// InputError (exit code 2) naming the key or flag and the range. Documented in
// docs/scenes.md ("Validation"), docs/contact.md and docs/programs.md ("Flags").
//
// Why these values: within them every energy, force, Hessian entry and step
// weight of a scene of at most 10^6 nodes stays a finite, normal double (the
// largest products are of order 10^47, the smallest weights of order 10^-42),
// so that an overflow never turns into inf/NaN energies after a "valid" load.
// They are generous: the hard-case benchmarks use stiffness 10^2..10^8 N/m,
// h = 10^-6..0.1 s, impacts at 1000 m/s and nodes of 10^-6 kg next to 1 kg.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

namespace ipstep::limits {

// ---- Scenes (problems/scene_loader.cc) ------------------------------------
// Nodes of a scene, from every node source (explicit nodes, chains, grids,
// solids' meshes): the scale every other bound here is chosen for.
constexpr long long kMaxNodes = 1000000;
// Every position component, also of generated nodes and obstacles [m]: at
// 10^6 m double coordinates still resolve 10^-10 m, below kMinLength.
constexpr double kMaxCoordinate = 1e6;
// Every side and radius of a shape meshed by Gmsh [m]: OpenCASCADE's
// geometric tolerance is 1e-7 m; it refuses rectangles and boxes of sides
// 1e-7 m, and a ball of radius 3e-8 m makes Gmsh throw inside an OpenMP
// region, which aborts the program (no catch can stop it).
constexpr double kMinGmshLength = 1e-6;
// Spring rest lengths and generated spring lengths [m]; the upper bound is above
// any distance within the coordinate range (2·10^6·√3).
constexpr double kMinLength = 1e-9;
constexpr double kMaxLength = 1e7;
// Every velocity component: initial and prescribed velocities, obstacles [m/s].
constexpr double kMaxSpeed = 1e6;
// Every component of a moving node's angular velocity [rad/s] (|ω| r stays
// within kMaxSpeed for r up to 1 m).
constexpr double kMaxAngularVelocity = 1e6;
// Durations such as a moving node's "until" [s]: kMaxSteps steps of kMaxTimeStep.
constexpr double kMaxDuration = 1e10;
// Every gravity component [m/s²] (10^5 g).
constexpr double kMaxAcceleration = 1e6;
// The mass of each node [kg] (also when derived from total_mass or density):
// ratios up to 10^24 keep m·|v|² and m/h² finite.
constexpr double kMinMass = 1e-12;
constexpr double kMaxMass = 1e12;
// Spring stiffness (N/m; N/m³ for quartic springs), > 0.
constexpr double kMaxStiffness = 1e15;
// Time step [s] (scene time_step, --dt): below 10^-12 s the step weights h²,
// h³ approach the end of the double range together with small masses; above
// 10^3 s nothing is dynamic any more.
constexpr double kMinTimeStep = 1e-12;
constexpr double kMaxTimeStep = 1e3;
// Steps of a run (scene steps, --steps, --frame_every): ipstep_compare runs
// its reference at 16 times as many steps, which must fit an int; at ~10 µs
// for the smallest scene's step, 10^7 steps already take minutes.
constexpr int kMaxSteps = 10000000;
// Rayleigh damping: mass-proportional α [1/s] (1/α is a relaxation time, not
// shorter than kMinTimeStep) and stiffness-proportional β [s] (a time, not
// longer than kMaxTimeStep).
constexpr double kMaxMassDamping = 1e12;
constexpr double kMaxStiffnessDamping = 1e3;

// ---- Contact (contact/contact_effects.cc, apps/contact_flags.cc) -----------
// Barrier activation distance d̂ [m]: gaps far above the round-off of coordinates.
constexpr double kMinDhat = 1e-9;
constexpr double kMaxDhat = 1e6;
// Fixed barrier stiffness κ (N/m² in 2D, N/m³ in 3D), > 0.
constexpr double kMaxKappa = 1e20;
// Friction coefficient μ >= 0 and mollifier width ε_v [m/s].
constexpr double kMaxFrictionMu = 100.0;
constexpr double kMinEpsilonV = 1e-12;
constexpr double kMaxEpsilonV = 1e6;
constexpr int kMaxFrictionIterations = 100;

// ---- Optimisers and programs (solver/optimizer_options.cc, apps/) ----------
// Substeps a failed step is retried as (SimulationOptions::max_substeps):
// 1024 substeps of the smallest h is still a step of 10^-9 s.
constexpr int kMaxSubsteps = 1024;
// Iterations per step (the slowest default, gradient_descent, is 50,000).
constexpr int kMaxIterations = 1000000;
// Ceres threads (each is a real thread).
constexpr int kMaxThreads = 256;
// L-BFGS correction pairs: Ceres allocates 2 × rank vectors of the free
// coordinates up front (rank 2^31 - 1 was a bad_alloc); Ceres's default is 20.
constexpr int kMaxLbfgsRank = 1000;
// Initial trust-region radius: Ceres's own limits are 1e-32 and 1e16 (raised
// to the initial radius when it is larger).
constexpr double kMinTrustRegionRadius = 1e-12;
constexpr double kMaxTrustRegionRadius = 1e20;
// Wall-time limit per step [s]; "none" is 10^9 s (32 years) internally.
constexpr double kMaxTimeLimit = 1e9;
// Nodes per side of a resized grid (--grid_size): nx·ny <= 10^6 nodes.
constexpr int kMaxGridSize = 1000;

// A limit for messages: the shortest form, exponents without '+' and leading
// zeros (1e6, 1e-12, 0.5, 100).
inline std::string FormatLimit(double value) {
  if (value == static_cast<double>(static_cast<long long>(value)) && value > -1e3 && value < 1e3) {
    return std::to_string(static_cast<long long>(value));
  }
  char buffer[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof(buffer), "%.*g", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  std::string text = buffer;
  const size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string exponent = text.substr(e + 1);
  const bool negative = !exponent.empty() && exponent[0] == '-';
  if (!exponent.empty() && (exponent[0] == '+' || exponent[0] == '-')) exponent.erase(0, 1);
  while (exponent.size() > 1 && exponent[0] == '0') exponent.erase(0, 1);
  return text.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

// "[min, max] unit" for messages; `min_open` writes "(min, max]".
inline std::string RangeText(double min, double max, const std::string& unit = "",
                             bool min_open = false) {
  return std::string(min_open ? "(" : "[") + FormatLimit(min) + ", " + FormatLimit(max) + "]" +
         (unit.empty() ? "" : " " + unit);
}

}  // namespace ipstep::limits
