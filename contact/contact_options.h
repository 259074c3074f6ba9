// Options of the contact state (contact/contact_state.h): ContactOptions when it
// is made, FrictionOptions for its EnableFriction.
#pragma once

#include <vector>

#include "contact/obstacle.h"

namespace ipstep {

struct ContactOptions {
  double d_hat = 1e-3;  // barrier activation distance [m]
  double kappa = 0.0;   // barrier stiffness: > 0 fixed; 0 adaptive (contact/adaptive_kappa.h)
  bool self_contact = false;
  // Self-contact pairs' barrier stiffness (> 0; needs a fixed kappa) and
  // friction coefficient (>= 0, with the friction effect); the defaults
  // (0 and < 0) take kappa and the friction effect's mu.
  double self_contact_kappa = 0.0;
  double self_contact_mu = -1.0;
  // Each obstacle's own friction coefficient: Obstacle::friction_mu.
  ObstacleList obstacles;
};

struct FrictionOptions {
  double mu = 0.0;
  double epsilon_v = 1e-3;  // [m/s]
  int iterations = 1;       // lags per step (1: lagged at the step start only)
};

}  // namespace ipstep
