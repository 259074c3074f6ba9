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

template <class F>
void NodeObstaclePairs::ForEachCandidate(const double*, const double*, double, const F& f) const {
  const int num_obstacles = static_cast<int>(c_.obstacles->size());
  for (int s = 0; s < static_cast<int>(c_.mesh->nodes.size()); ++s) {
    for (int o = 0; o < num_obstacles; ++o) f(Pair{s, o});
  }
}

double NodeObstaclePairs::Distance(const double* x, double t, const Pair& pair) const {
  return (*c_.obstacles)[pair.obstacle]->Distance(Point(x, pair.slot), t);
}

PairDistance<1> NodeObstaclePairs::Measure(const double* x, double t, const Pair& pair) const {
  PairDistance<1> m;
  m.nodes = {c_.mesh->nodes[pair.slot]};
  m.distance = (*c_.obstacles)[pair.obstacle]->Distance(Point(x, pair.slot), t, &m.gradient[0]);
  return m;
}

bool NodeObstaclePairs::Admits(const CandidateRegion& region, const Pair& pair, NoPairData*) const {
  return Distance(region.start, *c_.time, pair) <
         c_.d_hat + (*region.reach)[pair.slot] + (*region.travel)[pair.obstacle];
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

std::string NodeObstaclePairs::Describe(const Pair& pair) const {
  std::ostringstream out;
  out << "node " << c_.mesh->nodes[pair.slot] << " is inside or touching "
      << (*c_.obstacles)[pair.obstacle]->name();
  return out.str();
}

void NodeObstaclePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  term->nodes = {c_.mesh->nodes[pair.slot]};
  const Obstacle& obstacle = *(*c_.obstacles)[pair.obstacle];
  auto cost =
      std::make_unique<PointObstacleGap>(c_.dimension, &obstacle, c_.time, c_.d_hat, c_.margin);
  if (obstacle.distance_is_affine()) {
    term->gauss_newton_model = true;  // a plane's distance: its model is exact
    term->cost = std::move(cost);
  } else {
    SetGapCost(std::move(cost), term);
  }
}

bool NodeObstaclePairs::LagPairFriction(const double* x, double t, const Pair& pair,
                                        const PairDistance<1>& m,
                                        NodeObstacleFrictionLag* lag) const {
  const Obstacle& o = *(*c_.obstacles)[pair.obstacle];
  *lag = NodeObstacleFrictionLag{m.nodes[0], TangentBasis(m.gradient[0], c_.dimension),
                                 o.VelocityAt(Point(x, pair.slot), t),
                                 NormalForce(pair, m.distance), &o};
  return true;
}

int NodeObstaclePairs::FrictionTerms(const std::vector<NodeObstacleFrictionLag>& lags,
                                     const FrictionSettings& friction,
                                     IncrementalPotential* potential) const {
  const double eps_v = friction.epsilon_v;
  const double c = kFrictionSpeedScale * eps_v;
  const std::vector<int> sides = c_.dimension == 2 ? std::vector<int>{1, -1} : std::vector<int>{0};
  int count = 0;
  for (const NodeObstacleFrictionLag& f : lags) {
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

// After ForEachCandidate, which the base's loops call.
template class PairKind<NodeObstaclePairs, NodeObstaclePair, NoPairData, NodeObstacleFrictionLag>;

}  // namespace ipstep
