// The built gravity effect (energies/builtin_effects.cc): the scene's uniform
// acceleration g (Scene::gravity). With inertia the step itself carries it
// (the variational integrators' predictor, symplectic Euler's explicit
// update), so the simulation asks this effect for g (Simulation::gravity());
// quasi-static, its linear potential terms carry it. A scene without the
// effect has no gravity, whatever Scene::gravity holds.
#pragma once

#include <string>
#include <utility>

#include <Eigen/Core>

#include "energies/effect.h"

namespace ipstep {

class GravityEffect final : public Effect {
 public:
  GravityEffect(Eigen::VectorXd acceleration, std::string summary)
      : acceleration_(std::move(acceleration)), summary_(std::move(summary)) {}
  // g [m/s^2], one entry per dimension.
  const Eigen::VectorXd& acceleration() const { return acceleration_; }
  std::string Summary() const override { return summary_; }

 private:
  Eigen::VectorXd acceleration_;
  std::string summary_;
};

}  // namespace ipstep
