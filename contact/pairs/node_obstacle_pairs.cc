#include "contact/pairs/node_obstacle_pairs.h"

#include <algorithm>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/friction.h"
#include "geometry/tangent_basis.h"

namespace ipstep {

Eigen::Vector3d NodeObstaclePairs::Point(const double* x, int slot) const {
  return ToPoint(x + c_.dimension * c_.mesh->nodes[slot], c_.dimension);
}

bool NodeObstaclePairs::Extend(const CandidateRegion& region) {
  bool added = false;
  const ObstacleList& obstacles = *c_.obstacles;
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    if (!(*c_.node_free)[s]) continue;
    const Eigen::Vector3d p = Point(region.start, static_cast<int>(s));
    for (size_t o = 0; o < obstacles.size(); ++o) {
      const double d = obstacles[o]->Distance(p, *c_.time);
      if (d < c_.d_hat + (*region.reach)[s] + (*region.travel)[o]) {
        added |= pairs_.Insert(Pair{static_cast<int>(s), static_cast<int>(o)});
      }
    }
  }
  return added;
}

bool NodeObstaclePairs::Missing(const double* x) const {
  const ObstacleList& obstacles = *c_.obstacles;
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    if (!(*c_.node_free)[s]) continue;
    for (size_t o = 0; o < obstacles.size(); ++o) {
      if (obstacles[o]->Distance(Point(x, static_cast<int>(s)), *c_.time) < c_.d_hat &&
          !pairs_.Contains(Pair{static_cast<int>(s), static_cast<int>(o)})) {
        return true;
      }
    }
  }
  return false;
}

double NodeObstaclePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                       double t_b) const {
  double first = kNoImpact;
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    const Eigen::Vector3d pa = Point(a, static_cast<int>(s)), pb = Point(b, static_cast<int>(s));
    for (const ObstaclePtr& o_ptr : *c_.obstacles) {
      const Obstacle& o = *o_ptr;
      first = std::min(first, o.TimeOfImpact(pa, pb, t_a, t_b, c_.margin));
    }
  }
  return first;
}

std::string NodeObstaclePairs::FindPenetration(const double* x, double t) const {
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    for (const ObstaclePtr& o_ptr : *c_.obstacles) {
      const Obstacle& o = *o_ptr;
      const double d = o.Distance(Point(x, static_cast<int>(s)), t);
      if (!(d > c_.margin)) {
        std::ostringstream out;
        out << "node " << c_.mesh->nodes[s] << " is inside or touching " << o.name()
            << " (distance " << d << ")";
        return out.str();
      }
    }
  }
  return "";
}

void NodeObstaclePairs::Near(const double* x, double t, double reach, double* min_distance,
                             int* count) const {
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    for (const ObstaclePtr& o_ptr : *c_.obstacles) {
      const Obstacle& o = *o_ptr;
      const double d = o.Distance(Point(x, static_cast<int>(s)), t);
      if (d < reach) {
        *min_distance = std::min(*min_distance, d);
        ++*count;
      }
    }
  }
}

void NodeObstaclePairs::AddBarrierGradient(const double* x, double t, double scale,
                                           Eigen::VectorXd* g) const {
  const int dim = c_.dimension;
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    for (const ObstaclePtr& o_ptr : *c_.obstacles) {
      const Obstacle& o = *o_ptr;
      Eigen::Vector3d grad;
      const double d = o.Distance(Point(x, static_cast<int>(s)), t, &grad);
      if (!(d > 0.0 && d < c_.d_hat)) continue;
      const double w = scale * c_.mesh->weights[s] * BarrierDerivative(d, c_.d_hat);
      for (int k = 0; k < dim; ++k) (*g)[dim * c_.mesh->nodes[s] + k] += w * grad[k];
    }
  }
}

void NodeObstaclePairs::AddBarrierTerms(IncrementalPotential* potential) const {
  for (const Pair& pair : pairs_.pairs()) {
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(c_.barrier);
    term.impulsive = true;
    term.nodes = {c_.mesh->nodes[pair.slot]};
    const Obstacle& obstacle = *(*c_.obstacles)[pair.obstacle];
    auto cost =
        std::make_unique<PointObstacleGap>(c_.dimension, &obstacle, c_.time, c_.d_hat, c_.margin);
    if (obstacle.distance_is_affine()) {
      term.gauss_newton_model = true;  // a plane's distance: its model is exact
    } else {
      term.curvature = GapCurvature(cost.get());
    }
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(c_.d_hat, c_.mesh->weights[pair.slot], c_.kappa);
    potential->AddTerm(std::move(term));
  }
}

void NodeObstaclePairs::LagFriction(const double* x, double t) {
  lagged_.clear();
  for (const Pair& pair : pairs_.pairs()) {
    const Obstacle& o = *(*c_.obstacles)[pair.obstacle];
    Eigen::Vector3d n;
    const Eigen::Vector3d point = Point(x, pair.slot);
    const double d = o.Distance(point, t, &n);
    if (!(d > 0.0 && d < c_.d_hat)) continue;
    const double lambda = -*c_.kappa * c_.mesh->weights[pair.slot] * BarrierDerivative(d, c_.d_hat);
    lagged_.push_back(LaggedFriction{c_.mesh->nodes[pair.slot], TangentBasis(n, c_.dimension),
                                     o.VelocityAt(point, t), lambda, &o});
  }
}

int NodeObstaclePairs::AddFrictionTerms(const FrictionSettings& friction,
                                        IncrementalPotential* potential) const {
  // 3D: one term per contact (side 0); 2D: the exact split, one term per side.
  const double eps_v = friction.epsilon_v;
  const double c = kFrictionSpeedScale * eps_v;
  const std::vector<int> sides = c_.dimension == 2 ? std::vector<int>{1, -1} : std::vector<int>{0};
  int count = 0;
  for (const LaggedFriction& f : lagged_) {
    const double mu = friction.ForObstacle(*f.obstacle);
    if (!(mu > 0.0)) continue;
    ++count;
    for (int side : sides) {
      Term term;
      term.kind = TermKind::kDissipation;
      term.SetOwner(c_.friction);
      term.impulsive = true;
      term.nodes = {f.node};
      term.frame_velocity = f.obstacle_velocity;
      term.cost = std::make_unique<ObstacleFriction>(c_.step, f.node, f.tangents,
                                                     f.obstacle_velocity, eps_v, side, c);
      const double scale = mu * f.normal_force;
      if (side == 0) {
        term.loss = std::make_unique<FrictionLoss>(scale);
      } else {
        term.loss = std::make_unique<OneSidedFrictionLoss>(scale, c, eps_v);
      }
      potential->AddTerm(std::move(term));
    }
  }
  return count;
}

}  // namespace ipstep
