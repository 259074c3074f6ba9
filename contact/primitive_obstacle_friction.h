// Friction of a 3D mesh primitive against an obstacle (the pairs of
// contact/pairs/face_obstacle_pairs.h and box_edge_pairs.h): IPC's lagged
// smoothed friction (contact/friction.h, 3D form) of the primitive's closest
// point, a fixed (lagged) combination of its n nodes (n = 3: a face's
// barycentric weights w; n = 2: an edge's (1 - s, s)), relative to the
// obstacle, which translates with velocity v_o (at the lag's time; zero once
// it stopped):
//   v_rel = sum_k alpha_k v_k - v_o,   v_t = T^T v_rel   (T: 3 x 2, lagged),
//   r = psi(|v_t|) v_t / |v_t|  (FrictionResidual),  loss rho(s) = mu lambda s,
// so 1/2 rho(|r|^2) = mu lambda f0(|v_t|), and with v_k = v_base + slope
// (x_k - x_base) the Jacobian of block k is alpha_k slope dr/dv_t T^T.
// As for a node against an obstacle (alpha = (1), ObstacleFriction in
// contact/contact_terms.h), the lagged normal force lambda = kappa w (-B'(d))
// and T are taken where the pair's barrier is, and the obstacle's velocity
// is subtracted so that a moving obstacle drags the cloth.
#pragma once

#include <array>
#include <vector>

#include <ceres/cost_function.h>
#include <Eigen/Core>

#include "contact/pair_set.h"
#include "core/incremental_potential.h"
#include "core/step_context.h"

namespace ipstep {

struct PrimitiveObstacleFrictionLag {
  int num_nodes = 3;  // 3: face, 2: edge
  std::array<int, 3> nodes{};
  std::array<double, 3> alpha{};
  Eigen::Matrix<double, 3, 2> tangents;
  Eigen::Vector3d obstacle_velocity = Eigen::Vector3d::Zero();  // at the lag's time
  double normal_force = 0.0;                                    // lambda [N]
  const Obstacle* obstacle = nullptr;  // its friction coefficient (FrictionSettings)
};

// The lag at obstacle time t of a primitive whose closest point is `point`,
// with unit normal n (from the obstacle's feature towards the point): the
// tangent basis of n (TangentBasis, as for nodes against obstacles), the
// obstacle's velocity at the point (its material point there moves within
// |omega| d_hat of the one the primitive touches) and the normal force; the
// caller sets num_nodes, nodes and alpha.
PrimitiveObstacleFrictionLag LagPrimitiveObstacleFriction(const Obstacle& obstacle, double t,
                                                          const Eigen::Vector3d& n,
                                                          const Eigen::Vector3d& point,
                                                          double normal_force);

class PrimitiveObstacleFriction : public ceres::CostFunction {
 public:
  PrimitiveObstacleFriction(const StepContext* context, const PrimitiveObstacleFrictionLag& lag,
                            double eps_v);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;

  // The relative tangential velocity v_t at positions x (one block per node).
  Eigen::Vector2d TangentialVelocity(double const* const* x) const;

 private:
  const StepContext* context_;
  PrimitiveObstacleFrictionLag lag_;
  double eps_v_;
};

// One term per lag whose obstacle's coefficient mu (FrictionSettings::
// ForObstacle) is > 0 (kind kDissipation, impulsive, owner `owner`,
// FrictionLoss mu lambda); returns the number of terms.
int AddPrimitiveObstacleFrictionTerms(const std::vector<PrimitiveObstacleFrictionLag>& lags,
                                      const StepContext* step, const TermOwner& owner,
                                      const FrictionSettings& friction,
                                      IncrementalPotential* potential);

}  // namespace ipstep
