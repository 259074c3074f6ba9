// MeshObstaclePairs' friction (contact/pairs/mesh_obstacle_pairs.h): each
// active face or box-edge pair within d_hat at the lag is one
// PrimitiveObstacleFriction term (contact/primitive_obstacle_friction.h).
//
// Lagged at x, obstacle time t, from the true distance (as the node-obstacle
// and self-contact kinds): the closest point's weights alpha (a face's
// barycentric weights, an edge's (1 - s, s)), the unit normal n, from the
// obstacle's feature towards the closest point, which is the sum of the
// distance's vertex gradients (grad_k = alpha_k n, sum alpha_k = 1), the
// tangent basis of n (TangentBasis, as for nodes against obstacles), and the
// normal force lambda = kappa w (-B'(d)) with the primitive's weight w (the
// barrier term's).
#include <algorithm>

#include "contact/barrier.h"
#include "contact/pairs/mesh_obstacle_pairs.h"
#include "geometry/tangent_basis.h"

namespace ipstep {

void MeshObstaclePairs::LagFriction(const double* x, double t) {
  friction_.clear();
  const double kappa = *c_.kappa;
  // point: the primitive's closest point (the obstacle's material point there
  // moves within |omega| d_hat of the one it touches).
  auto lag = [&](double d, const Eigen::Vector3d& n, double weight, const Obstacle& obstacle,
                 const Eigen::Vector3d& point) {
    PrimitiveObstacleFrictionLag f;
    f.tangents = TangentBasis(n, 3).leftCols<2>();
    f.obstacle_velocity = obstacle.VelocityAt(point, t);
    f.obstacle = &obstacle;
    f.normal_force = -kappa * weight * BarrierDerivative(d, d_hat_);
    return f;
  };
  for (const FacePair& p : face_pairs_.pairs()) {
    Eigen::Vector3d grad[3], w;
    const double d = Distance(x, t, p, grad, &w);
    if (!(d > 0.0 && d < d_hat_)) continue;
    const auto& face = surface_->faces[p.face];
    const Eigen::Vector3d point =
        w[0] * Vertex(x, face[0]) + w[1] * Vertex(x, face[1]) + w[2] * Vertex(x, face[2]);
    PrimitiveObstacleFrictionLag f =
        lag(d, grad[0] + grad[1] + grad[2], surface_->face_weights[p.face],
            *(*obstacles_)[p.obstacle], point);
    f.num_nodes = 3;
    f.nodes = {face[0], face[1], face[2]};
    f.alpha = {w[0], w[1], w[2]};
    friction_.push_back(f);
  }
  for (const BoxEdgePair& p : box_edge_pairs_.pairs()) {
    Eigen::Vector3d grad[2];
    double s = 0.0;
    const double d = Distance(x, t, p, grad, &s);
    if (!(d > 0.0 && d < d_hat_)) continue;
    const auto& edge = surface_->edges[p.edge];
    const Eigen::Vector3d point = (1.0 - s) * Vertex(x, edge[0]) + s * Vertex(x, edge[1]);
    PrimitiveObstacleFrictionLag f = lag(d, grad[0] + grad[1], surface_->edge_weights[p.edge],
                                         *(*obstacles_)[p.obstacle], point);
    f.num_nodes = 2;
    f.nodes = {edge[0], edge[1], -1};
    f.alpha = {1.0 - s, s, 0.0};
    friction_.push_back(f);
  }
}

int MeshObstaclePairs::AddFrictionTerms(const FrictionSettings& friction,
                                        IncrementalPotential* potential) const {
  return AddPrimitiveObstacleFrictionTerms(friction_, c_.step, c_.friction, friction, potential);
}

}  // namespace ipstep
