#include "contact/pairs/box_edge_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "contact/contact_terms.h"
#include "contact/pairs/feature_ball.h"
#include "geometry/point_triangle.h"

namespace ipstep {

BoxEdgePairs::BoxEdgePairs(const PairSetContext& context) : Base(context) {
  for (const ObstaclePtr& o : *c_.obstacles) {
    active_ |= o->NumBoxEdges() > 0 && !c_.mesh->edges.empty();
  }
  for (const auto& e : c_.mesh->edges) {
    edge_slots_.push_back({NodeSlot(*c_.mesh, e[0]), NodeSlot(*c_.mesh, e[1])});
  }
}

double BoxEdgePairs::Distance(const double* x, double t, const Pair& p) const {
  const auto& e = c_.mesh->edges[p.edge];
  return (*c_.obstacles)[p.obstacle]->BoxEdgeDistance(p.box_edge, Vertex(x, e[0]), Vertex(x, e[1]),
                                                      t);
}

BoxEdgePairs::Measured BoxEdgePairs::Measure(const double* x, double t, const Pair& p) const {
  const auto& e = c_.mesh->edges[p.edge];
  Measured m;
  m.nodes = e;
  m.distance = (*c_.obstacles)[p.obstacle]->BoxEdgeDistance(
      p.box_edge, Vertex(x, e[0]), Vertex(x, e[1]), t, &m.gradient[0], &m.gradient[1], &m.s);
  return m;
}

bool BoxEdgePairs::HasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *c_.node_free;
  const auto& s = edge_slots_[pair.edge];
  return free[s[0]] || free[s[1]];
}

template <class Cutoff, class F>
void BoxEdgePairs::ForEachNear(const double* x, double t, const Cutoff& cutoff,
                               const std::vector<double>* travel, const F& f) const {
  if (!active_) return;
  const ObstacleList& obstacles = *c_.obstacles;
  const int num_obstacles = static_cast<int>(obstacles.size());
  // A box edge at distance D from the edge's midpoint m is at least D - rho
  // from the edge: it can be below the cutoff only if D < cutoff + rho. The
  // box's signed distance of m is a lower bound of every box edge's D.
  for (int i = 0; i < static_cast<int>(c_.mesh->edges.size()); ++i) {
    const auto& edge = c_.mesh->edges[i];
    const Eigen::Vector3d a = Vertex(x, edge[0]), b = Vertex(x, edge[1]);
    const Eigen::Vector3d m = 0.5 * (a + b);
    const double rho = 0.5 * (b - a).norm();
    const double edge_cutoff = cutoff(i);
    for (int o = 0; o < num_obstacles; ++o) {
      const Obstacle& obstacle = *obstacles[o];
      const int box_edges = obstacle.NumBoxEdges();
      if (box_edges == 0) continue;
      const double limit = edge_cutoff + (travel ? (*travel)[o] : 0.0) + rho;
      if (!(obstacle.Distance(m, t) < limit)) continue;
      for (int k = 0; k < box_edges; ++k) {
        Eigen::Vector3d p, q;
        obstacle.BoxEdge(k, t, &p, &q);
        if (PointSegmentDistance(m, p, q) < limit) f(Pair{i, o, k});
      }
    }
  }
}

template <class F>
void BoxEdgePairs::ForEachCandidateAt(const double* x, double t, double grow, const F& f) const {
  ForEachNear(
      x, t, [grow](int) { return grow; }, nullptr, f);
}

template <class F>
void BoxEdgePairs::ForEachCandidateIn(const CandidateRegion& region, const F& f) const {
  ForEachNear(
      region.start, *c_.time, [&](int edge) { return ExtendCutoff(region, edge); }, region.travel,
      f);
}

double BoxEdgePairs::ExtendCutoff(const CandidateRegion& region, int edge) const {
  const std::vector<double>& reach = *region.reach;
  const auto& s = edge_slots_[edge];
  return c_.d_hat + std::max(reach[s[0]], reach[s[1]]);
}

bool BoxEdgePairs::Admits(const CandidateRegion& region, const Pair& pair, NoPairData*) const {
  const double cutoff = ExtendCutoff(region, pair.edge) + (*region.travel)[pair.obstacle];
  return Distance(region.start, *c_.time, pair) < cutoff;
}

double BoxEdgePairs::TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const {
  if (!active_) return kNoImpact;
  double first = kNoImpact;
  for (const ObstaclePtr& obstacle_ptr : *c_.obstacles) {
    const Obstacle& obstacle = *obstacle_ptr;
    const int box_edges = obstacle.NumBoxEdges();
    if (box_edges == 0) continue;
    for (const auto& edge : c_.mesh->edges) {
      const Eigen::Vector3d v0[2] = {Vertex(a, edge[0]), Vertex(a, edge[1])};
      const Eigen::Vector3d v1[2] = {Vertex(b, edge[0]), Vertex(b, edge[1])};
      const Eigen::Vector3d y0[2] = {obstacle.ToRest(v0[0], t_a), obstacle.ToRest(v0[1], t_a)};
      const Eigen::Vector3d y1[2] = {obstacle.ToRest(v1[0], t_b), obstacle.ToRest(v1[1], t_b)};
      const Eigen::Vector3d m = obstacle.ToRest(0.5 * (v0[0] + v0[1]), t_a);
      // (The second start vertex is as far from m as the first.)
      const double rho =
          obstacle.rotates()
              ? PathBallRadius(obstacle, v0, v1, y0, y1, 2, m, t_a, t_b)
              : std::sqrt(std::max({(y0[0] - m).squaredNorm(), (y1[0] - m).squaredNorm(),
                                    (y1[1] - m).squaredNorm()}));
      if (FeatureClearsBall(obstacle.Distance(m, 0.0), rho, c_.margin)) continue;
      for (int k = 0; k < box_edges; ++k) {
        Eigen::Vector3d p, q;
        obstacle.BoxEdge(k, 0.0, &p, &q);
        if (FeatureClearsBall(PointSegmentDistance(m, p, q), rho, c_.margin)) continue;
        first = std::min(first, obstacle.BoxEdgeTimeOfImpact(k, v0[0], v1[0], v0[1], v1[1], t_a,
                                                             t_b, c_.margin));
        if (first == 0.0) return 0.0;
      }
    }
  }
  return first;
}

std::string BoxEdgePairs::Describe(const Pair& pair) const {
  const auto& e = c_.mesh->edges[pair.edge];
  std::ostringstream out;
  out << "edge (" << e[0] << ", " << e[1] << ") touches an edge of "
      << (*c_.obstacles)[pair.obstacle]->name();
  return out.str();
}

std::string BoxEdgePairs::FindCrossing(const double* x, double t) const {
  // Static only: a 3D box can hold a cloth edge passing through it (both ends
  // outside, no box edge touched) or pierce a face with one of its edges (no
  // corner or face edge touched). Continuous motion from a free state passes
  // a touching configuration first, caught by the distances; this is for the
  // initial state.
  std::ostringstream out;
  for (const ObstaclePtr& obstacle_ptr : *c_.obstacles) {
    const Obstacle& obstacle = *obstacle_ptr;
    if (obstacle.NumBoxEdges() == 0) continue;
    for (const auto& e : c_.mesh->edges) {
      const Eigen::Vector3d a = Vertex(x, e[0]), b = Vertex(x, e[1]);
      if (obstacle.TimeOfImpact(a, b, t, t, c_.margin) <= 1.0) {
        out << "edge (" << e[0] << ", " << e[1] << ") passes through " << obstacle.name();
        return out.str();
      }
    }
    Eigen::Vector3d p[12], q[12];
    for (int k = 0; k < 12; ++k) obstacle.BoxEdge(k, t, &p[k], &q[k]);
    for (const auto& f : c_.mesh->faces) {
      const Eigen::Vector3d a = Vertex(x, f[0]), b = Vertex(x, f[1]), c = Vertex(x, f[2]);
      const Eigen::Vector3d m = (a + b + c) / 3.0;
      const double rho = std::sqrt(
          std::max({(a - m).squaredNorm(), (b - m).squaredNorm(), (c - m).squaredNorm()}));
      if (obstacle.Distance(m, t) > rho) continue;
      for (int k = 0; k < 12; ++k) {
        if (SegmentIntersectsTriangle(p[k], q[k], a, b, c)) {
          out << "an edge of " << obstacle.name() << " passes through face (" << f[0] << ", "
              << f[1] << ", " << f[2] << ")";
          return out.str();
        }
      }
    }
  }
  return "";
}

void BoxEdgePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& e = c_.mesh->edges[pair.edge];
  term->nodes = {e[0], e[1]};
  SetGapCost(std::make_unique<EdgeBoxEdgeGap>((*c_.obstacles)[pair.obstacle].get(), pair.box_edge,
                                              c_.time, c_.d_hat, c_.margin),
             term);
}

bool BoxEdgePairs::LagPairFriction(const double* x, double t, const Pair& pair, const Measured& m,
                                   PrimitiveObstacleFrictionLag* lag) const {
  const auto& e = c_.mesh->edges[pair.edge];
  const Eigen::Vector3d point = (1.0 - m.s) * Vertex(x, e[0]) + m.s * Vertex(x, e[1]);
  *lag = LagPrimitiveObstacleFriction(*(*c_.obstacles)[pair.obstacle], t,
                                      m.gradient[0] + m.gradient[1], point,
                                      NormalForce(pair, m.distance));
  lag->num_nodes = 2;
  lag->nodes = {e[0], e[1], -1};
  lag->alpha = {1.0 - m.s, m.s, 0.0};
  return true;
}

// After ForEachNear, which the base's loops call.
template class PairKind<BoxEdgePairs, BoxEdgePair, NoPairData, PrimitiveObstacleFrictionLag>;

}  // namespace ipstep
