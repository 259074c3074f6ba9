#include "sim/divergence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/simulation.h"

namespace ipstep {
namespace {

// Samples of the prescribed motion over the run (positions for the box,
// velocities for K_p).
constexpr int kMotionSamples = 64;

}  // namespace

const char* DivergenceRule::Description() {
  return "a position, velocity or energy became non-finite, or the energy moved more than "
         "1e6 energy scales from the initial energy, or a node left the scene's reach 1e3 times "
         "over (sim/divergence.h)";
}

DivergenceRule::DivergenceRule(const Simulation& sim, double t_end) {
  const State& s = sim.state();
  const int dim = s.dimension;
  const int n = s.num_nodes();
  start_time_ = s.time;
  initial_energies_ = sim.Energies();
  const EnergyReport& e0 = initial_energies_;
  const Eigen::VectorXd& g = sim.gravity();
  double gravity_energy = 0.0, mass = 0.0, speed = 0.0;
  for (int i = 0; i < n; ++i) {
    gravity_energy -= s.mass[i] * g.dot(s.x.segment(dim * i, dim));
    mass += s.mass[i];
    speed = std::max(speed, s.v.segment(dim * i, dim).norm());
  }
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(dim, HUGE_VAL);
  Eigen::VectorXd hi = Eigen::VectorXd::Constant(dim, -HUGE_VAL);
  auto extend = [&](const Eigen::VectorXd& x) {
    for (int i = 0; i < n; ++i) {
      lo = lo.cwiseMin(x.segment(dim * i, dim));
      hi = hi.cwiseMax(x.segment(dim * i, dim));
    }
  };
  extend(s.x);
  double prescribed_kinetic = 0.0;
  if (s.has_prescribed_motion() && t_end > 0.0) {
    Eigen::VectorXd x = s.x, v = s.v;
    for (int k = 0; k <= kMotionSamples; ++k) {
      const double t = start_time_ + t_end * k / kMotionSamples;
      s.PrescribedPositions(t, &x);
      s.PrescribedVelocities(t, &v);
      extend(x);
      double kinetic = 0.0;
      for (int i = 0; i < n; ++i) {
        if (s.is_free(i)) continue;
        const double vi = v.segment(dim * i, dim).norm();
        kinetic += 0.5 * s.mass[i] * vi * vi;
        speed = std::max(speed, vi);
      }
      prescribed_kinetic = std::max(prescribed_kinetic, kinetic);
    }
  }
  const double kinetic0 = std::isfinite(e0.kinetic) ? e0.kinetic : 0.0;
  const double stored0 =
      std::isfinite(e0.potential) ? std::abs(e0.potential - gravity_energy) : 0.0;
  stored_energy_ = kinetic0 + stored0 + prescribed_kinetic;
  gravity_ = g.norm();
  weight_ = mass * gravity_;
  if (mass > 0.0) speed = std::max(speed, std::sqrt(2.0 * stored_energy_ / mass));
  speed_ = speed;
  center_ = n > 0 ? Eigen::VectorXd(0.5 * (lo + hi)) : Eigen::VectorXd::Zero(dim);
  diagonal_ = n > 0 ? (hi - lo).norm() : 0.0;
}

double DivergenceRule::EnergyScale(double t, double work) const {
  return stored_energy_ + std::abs(work) +
         weight_ * (diagonal_ + speed_ * t + 0.5 * gravity_ * t * t);
}

double DivergenceRule::Reach(double t) const {
  return 0.5 * diagonal_ + speed_ * t + 0.5 * gravity_ * t * t;
}

double DivergenceRule::Drift(double time, double energy, double work) const {
  const double scale = EnergyScale(std::max(0.0, time - start_time_), work);
  return scale > 0.0 ? std::abs(energy - initial_energy()) / scale : 0.0;
}

std::string DivergenceRule::Check(const Simulation& sim, const StepReport& report,
                                  double work) const {
  const State& s = sim.state();
  if (!s.x.allFinite()) return "a position is not finite";
  if (!s.v.allFinite()) return "a velocity is not finite";
  const double energy = report.energies.total();
  if (!std::isfinite(energy)) return "the energy is not finite";
  const double t = std::max(0.0, s.time - start_time_);
  const double scale = EnergyScale(t, work);
  if (scale > 0.0 && std::abs(energy - initial_energy()) > kEnergyFactor * scale) {
    char text[200];
    std::snprintf(text, sizeof(text),
                  "the energy %.3g J is %.3g energy scales (%.3g J) from the initial %.3g J",
                  energy, std::abs(energy - initial_energy()) / scale, scale, initial_energy());
    return text;
  }
  const double reach = Reach(t);
  if (reach > 0.0) {
    const int dim = s.dimension;
    for (int i = 0; i < s.num_nodes(); ++i) {
      const double distance = (s.x.segment(dim * i, dim) - center_).norm();
      if (distance > kReachFactor * reach) {
        char text[200];
        std::snprintf(text, sizeof(text),
                      "node %d is %.3g m from the scene's centre, %.3g times its reach (%.3g m)", i,
                      distance, distance / reach, reach);
        return text;
      }
    }
  }
  return "";
}

}  // namespace ipstep
