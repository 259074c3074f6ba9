#include "contact/pairs/edge_obstacle_pairs.h"

#include <algorithm>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "geometry/point_edge.h"

namespace ipstep {

EdgeObstaclePairs::EdgeObstaclePairs(const PairSetContext& context) : Base(context) {
  for (const auto& e : c_.mesh->edges) {
    edge_slots_.push_back({NodeSlot(*c_.mesh, e[0]), NodeSlot(*c_.mesh, e[1])});
  }
}

double EdgeObstaclePairs::Distance(const double* x, double t, const Pair& p) const {
  return (*c_.obstacles)[p.obstacle]->EdgeDistance(p.feature, End(x, p.edge, 0), End(x, p.edge, 1),
                                                   t);
}

PairDistance<2> EdgeObstaclePairs::Measure(const double* x, double t, const Pair& p) const {
  PairDistance<2> m;
  m.nodes = c_.mesh->edges[p.edge];
  m.distance = (*c_.obstacles)[p.obstacle]->EdgeDistance(
      p.feature, End(x, p.edge, 0), End(x, p.edge, 1), t, &m.gradient[0], &m.gradient[1]);
  return m;
}

bool EdgeObstaclePairs::HasFreeNode(const Pair& pair) const {
  const std::vector<bool>& node_free = *c_.node_free;
  return node_free[edge_slots_[pair.edge][0]] || node_free[edge_slots_[pair.edge][1]];
}

template <class F>
void EdgeObstaclePairs::ForEachCandidate(const double*, const double*, double, const F& f) const {
  for (size_t e = 0; e < c_.mesh->edges.size(); ++e) {
    for (size_t o = 0; o < c_.obstacles->size(); ++o) {
      const int features = (*c_.obstacles)[o]->NumEdgeFeatures();
      for (int k = 0; k < features; ++k) f(Pair{static_cast<int>(e), static_cast<int>(o), k});
    }
  }
}

bool EdgeObstaclePairs::Admits(const CandidateRegion& region, const Pair& pair,
                               double* alpha) const {
  const std::vector<double>& reach = *region.reach;
  const auto& slots = edge_slots_[pair.edge];
  const double d = Distance(region.start, *c_.time, pair);
  if (!(d <
        c_.d_hat + std::max(reach[slots[0]], reach[slots[1]]) + (*region.travel)[pair.obstacle])) {
    return false;
  }
  PointSegmentDistance((*c_.obstacles)[pair.obstacle]->EdgeFeature(pair.feature, *c_.time),
                       End(region.start, pair.edge, 0), End(region.start, pair.edge, 1), alpha);
  return true;
}

double EdgeObstaclePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                       double t_b) const {
  double first = kNoImpact;
  for (const ObstaclePtr& obstacle_ptr : *c_.obstacles) {
    const Obstacle& obstacle = *obstacle_ptr;
    const int features = obstacle.NumEdgeFeatures();
    if (features == 0) continue;
    for (size_t e = 0; e < c_.mesh->edges.size(); ++e) {
      const int edge = static_cast<int>(e);
      const Eigen::Vector3d a0 = End(a, edge, 0), a1 = End(b, edge, 0);
      const Eigen::Vector3d b0 = End(a, edge, 1), b1 = End(b, edge, 1);
      for (int f = 0; f < features; ++f) {
        first = std::min(first, obstacle.EdgeTimeOfImpact(f, a0, a1, b0, b1, t_a, t_b, c_.margin));
        if (first == 0.0) return 0.0;
      }
    }
  }
  // A 2D path across a circle or box corner: blocked (ShrinkToClear finds how far).
  if (first > 1.0 && !Conflict(a, b, t_a).empty()) first = 1.0;
  return first;
}

double EdgeObstaclePairs::ShrinkToClear(const double* from, const double* to, double t) const {
  if (c_.dimension != 2 || !(t > 0.0)) return t;
  const int n = c_.num_coordinates;
  Eigen::VectorXd end(n);
  for (int halvings = 0; halvings < 60; ++halvings) {
    for (int k = 0; k < n; ++k) end[k] = from[k] + t * (to[k] - from[k]);
    if (Conflict(from, end.data(), *c_.time).empty()) break;
    t *= 0.5;
  }
  return t;
}

std::string EdgeObstaclePairs::Conflict(const double* a, const double* x, double t) const {
  if (c_.dimension != 2) return "";
  for (const ObstaclePtr& obstacle_ptr : *c_.obstacles) {
    const Obstacle& obstacle = *obstacle_ptr;
    // Features that can cross an edge's interior first (a circle's centre,
    // a box's corners; a plane has none and no edge can cross it first), in
    // world coordinates.
    const int num_features = obstacle.NumEdgeFeatures();
    if (num_features == 0) continue;
    std::vector<Eigen::Vector2d> features;
    for (int k = 0; k < num_features; ++k) {
      features.push_back(obstacle.EdgeFeature(k, t).head<2>());
    }
    auto node = [](const double* y, int i) { return Eigen::Vector2d(y[2 * i], y[2 * i + 1]); };
    for (const auto& e : c_.mesh->edges) {
      const Eigen::Vector3d p = ToPoint(x + 2 * e[0], 2), q = ToPoint(x + 2 * e[1], 2);
      // The segment p -> q read as a point path: it meets the grown obstacle.
      if (obstacle.TimeOfImpact(p, q, t, t, c_.margin) <= 1.0) {
        std::ostringstream out;
        out << "boundary edge (" << e[0] << ", " << e[1] << ") meets " << obstacle.name();
        return out.str();
      }
      if (a == x) continue;
      for (const Eigen::Vector2d& f : features) {
        if (PointEdgeTimeOfImpact(f, f, node(a, e[0]), node(x, e[0]), node(a, e[1]),
                                  node(x, e[1])) <= 1.0) {
          std::ostringstream out;
          out << "boundary edge (" << e[0] << ", " << e[1] << ") sweeps across " << obstacle.name();
          return out.str();
        }
      }
    }
  }
  return "";
}

std::string EdgeObstaclePairs::FindPenetration(const double* x, double t) const {
  const std::string conflict = Conflict(x, x, t);
  return conflict.empty() ? Base::FindPenetration(x, t) : conflict;
}

std::string EdgeObstaclePairs::Describe(const Pair& pair) const {
  const auto& e = c_.mesh->edges[pair.edge];
  std::ostringstream out;
  out << "edge (" << e[0] << ", " << e[1] << ") is inside or touching "
      << (*c_.obstacles)[pair.obstacle]->name();
  return out.str();
}

void EdgeObstaclePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& e = c_.mesh->edges[pair.edge];
  term->nodes = {e[0], e[1]};
  const Obstacle& obstacle = *(*c_.obstacles)[pair.obstacle];
  SetGapCost(std::make_unique<EdgeObstacleGap>(
                 c_.dimension, &obstacle, pair.feature, c_.time, c_.d_hat, c_.margin,
                 obstacle.FeatureRadius() > 0.0 ? &pairs_.data()[k] : nullptr),
             term);
}

double EdgeObstaclePairs::Lag(const double* x) {
  double excess = 0.0;
  std::vector<double>& alpha = pairs_.data();
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const Pair& p = pairs_[k];
    const Obstacle& o = *(*c_.obstacles)[p.obstacle];
    const Eigen::Vector3d a = End(x, p.edge, 0), b = End(x, p.edge, 1);
    double closest = 0.0;
    PointSegmentDistance(o.EdgeFeature(p.feature, *c_.time), a, b, &closest);
    const double d = o.EdgeDistance(p.feature, a, b, *c_.time);
    if (d > 0.0 && d < c_.d_hat) {
      const double lagged = o.EdgePointDistance(p.feature, a, b, alpha[k], *c_.time);
      excess = std::max(excess, (lagged - d) / d);
    }
    alpha[k] = closest;
  }
  return excess;
}

// After ForEachCandidate, which the base's loops call.
template class PairKind<EdgeObstaclePairs, EdgeObstaclePair, double>;

}  // namespace ipstep
