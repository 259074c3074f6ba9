#include "contact/primitive_obstacle_friction.h"

#include <memory>
#include <utility>

#include "contact/friction.h"
#include "geometry/tangent_basis.h"

namespace ipstep {

PrimitiveObstacleFrictionLag LagPrimitiveObstacleFriction(const Obstacle& obstacle, double t,
                                                          const Eigen::Vector3d& n,
                                                          const Eigen::Vector3d& point,
                                                          double normal_force) {
  PrimitiveObstacleFrictionLag lag;
  lag.tangents = TangentBasis(n, 3).leftCols<2>();
  lag.obstacle_velocity = obstacle.VelocityAt(point, t);
  lag.obstacle = &obstacle;
  lag.normal_force = normal_force;
  return lag;
}

PrimitiveObstacleFriction::PrimitiveObstacleFriction(const StepContext* context,
                                                     const PrimitiveObstacleFrictionLag& lag,
                                                     double eps_v)
    : context_(context), lag_(lag), eps_v_(eps_v) {
  set_num_residuals(2);
  for (int b = 0; b < lag_.num_nodes; ++b) mutable_parameter_block_sizes()->push_back(3);
}

Eigen::Vector2d PrimitiveObstacleFriction::TangentialVelocity(double const* const* x) const {
  Eigen::Vector3d v_rel = -lag_.obstacle_velocity;
  for (int k = 0; k < lag_.num_nodes; ++k) {
    double v[3];
    context_->Velocity(lag_.nodes[k], x[k], v);
    v_rel += lag_.alpha[k] * Eigen::Vector3d(v[0], v[1], v[2]);
  }
  return lag_.tangents.transpose() * v_rel;
}

bool PrimitiveObstacleFriction::Evaluate(double const* const* x, double* residuals,
                                         double** jacobians) const {
  const Eigen::Vector2d v_t = TangentialVelocity(x);
  double dr_dv[4];
  FrictionResidual(v_t.data(), 2, eps_v_, residuals, jacobians != nullptr ? dr_dv : nullptr);
  if (jacobians == nullptr) return true;
  // dr/dx_k = alpha_k slope dr/dv_t T^T (row-major 2 x 3).
  const Eigen::Matrix2d d = Eigen::Map<const Eigen::Matrix<double, 2, 2, Eigen::RowMajor>>(dr_dv);
  const Eigen::Matrix<double, 2, 3> base = d * lag_.tangents.transpose();
  for (int k = 0; k < lag_.num_nodes; ++k) {
    if (jacobians[k] == nullptr) continue;
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> block(jacobians[k]);
    block = (lag_.alpha[k] * context_->velocity_slope) * base;
  }
  return true;
}

int AddPrimitiveObstacleFrictionTerms(const std::vector<PrimitiveObstacleFrictionLag>& lags,
                                      const StepContext* step, const TermOwner& owner,
                                      const FrictionSettings& friction,
                                      IncrementalPotential* potential) {
  int count = 0;
  for (const PrimitiveObstacleFrictionLag& lag : lags) {
    const double mu = friction.ForObstacle(*lag.obstacle);
    if (!(mu > 0.0)) continue;
    ++count;
    Term term;
    term.kind = TermKind::kDissipation;
    term.SetOwner(owner);
    term.impulsive = true;
    term.nodes.assign(lag.nodes.begin(), lag.nodes.begin() + lag.num_nodes);
    term.frame_velocity = lag.obstacle_velocity;
    term.cost = std::make_unique<PrimitiveObstacleFriction>(step, lag, friction.epsilon_v);
    term.loss = std::make_unique<FrictionLoss>(mu * lag.normal_force);
    potential->AddTerm(std::move(term));
  }
  return count;
}

}  // namespace ipstep
