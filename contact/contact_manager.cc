#include "contact/contact_manager.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include <Eigen/Geometry>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/friction.h"
#include "contact/point_edge.h"

namespace ipstep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Obstacles advance to this fraction of the way to their first impact.
constexpr double kObstacleAdvanceFraction = 0.8;
// Adaptive kappa: range above kappa_min, and the gap below which it doubles.
constexpr double kKappaRange = 1e4;
constexpr double kShrinkingGapFraction = 1e-2;
// Edge-obstacle barriers: re-lags of the closest point per step, and the
// relative excess of the lagged gap over the true one that triggers one.
constexpr int kMaxAlphaLags = 3;
constexpr double kAlphaLagTolerance = 1e-2;

Eigen::Vector3d Min3(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.cwiseMin(b); }
Eigen::Vector3d Max3(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return a.cwiseMax(b); }

// Orthonormal tangent basis of the plane orthogonal to unit n (columns).
Eigen::Matrix3d TangentBasis(const Eigen::Vector3d& n, int dimension) {
  Eigen::Matrix3d t = Eigen::Matrix3d::Zero();
  if (dimension == 2) {
    t.col(0) = Eigen::Vector3d(-n[1], n[0], 0.0);
    return t;
  }
  int axis = 0;
  for (int k = 1; k < 3; ++k) {
    if (std::abs(n[k]) < std::abs(n[axis])) axis = k;
  }
  t.col(0) = n.cross(Eigen::Vector3d::Unit(axis)).normalized();
  t.col(1) = n.cross(t.col(0));
  return t;
}

}  // namespace

constexpr char ContactManager::kContactFamily[];
constexpr char ContactManager::kFrictionFamily[];

ContactManager::ContactManager(IncrementalPotential* potential, const State* state,
                               CollisionMesh surface, ContactOptions options)
    : potential_(potential),
      state_(state),
      context_(&potential->context()),
      dim_(state->dimension),
      surface_(std::move(surface)),
      options_(std::move(options)),
      margin_(1e-8 * options_.d_hat),
      accepted_(state->x),
      hash_(state->dimension, 1.0) {
  for (int node : surface_.nodes) slot_free_.push_back(state_->is_free(node));
  for (const auto& e : surface_.edges) {
    std::array<int, 2> slots{};
    for (int end = 0; end < 2; ++end) {
      slots[end] =
          static_cast<int>(std::lower_bound(surface_.nodes.begin(), surface_.nodes.end(), e[end]) -
                           surface_.nodes.begin());
    }
    edge_slots_.push_back(slots);
  }
  for (const Obstacle& o : options_.obstacles) has_moving_obstacles_ |= o.is_moving();
  mesh_pairs_ = std::make_unique<MeshObstaclePairs>(&surface_, &options_.obstacles, slot_free_,
                                                    options_.d_hat, margin_);
  if (options_.self_contact && !surface_.edges.empty()) {
    double total = 0.0;
    for (const auto& e : surface_.edges) {
      total += (ToPoint(state->x.data() + dim_ * e[0], dim_) -
                ToPoint(state->x.data() + dim_ * e[1], dim_))
                   .norm();
    }
    hash_ = SpatialHash(dim_, std::max(total / surface_.edges.size(), 2.0 * options_.d_hat));
  }
  // kappa_min: a barrier at d_hat / 2 as stiff as a node's inertia in E / w_U.
  double mass = 0.0, weight = 0.0;
  int count = 0;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    weight += surface_.weights[s];
    if (!slot_free_[s]) continue;
    mass += state_->mass[surface_.nodes[s]];
    ++count;
  }
  mass = count > 0 ? mass / count : 1.0;
  weight = surface_.nodes.empty() ? 1.0 : weight / surface_.nodes.size();
  const double h = context_->time_step > 0.0 ? context_->time_step : 1.0;
  const double stiffness = context_->inertia_weight > 0.0
                               ? mass * context_->inertia_weight / context_->potential_weight
                               : mass / (h * h);
  kappa_min_ = stiffness / (weight * BarrierSecondDerivative(0.5 * options_.d_hat, options_.d_hat));
  kappa_max_ = kKappaRange * kappa_min_;
  adaptive_ = !(options_.kappa > 0.0);
  kappa_ = adaptive_ ? kappa_min_ : options_.kappa;
  t_n_ = t_next_ = tau_ = state_->time;
}

void ContactManager::EnableFriction(const FrictionOptions& options) {
  friction_enabled_ = true;
  friction_ = options;
}

std::string ContactManager::Summary() const {
  std::ostringstream out;
  out << "contact: " << surface_.nodes.size() << " contact nodes, " << options_.obstacles.size()
      << " obstacles";
  if (options_.self_contact) out << ", self-contact on " << surface_.edges.size() << " edges";
  out << ", d_hat " << options_.d_hat << ", kappa ";
  if (adaptive_) {
    out << "adaptive from " << kappa_min_;
  } else {
    out << kappa_;
  }
  return out.str();
}

double ContactManager::ObstacleTravel(int obstacle) const {
  return options_.obstacles[obstacle].velocity.norm() * std::max(0.0, t_next_ - tau_);
}

bool ContactManager::PairHasFreeNode(const EdgePair& pair) const {
  const auto& e = surface_.edges[pair.edge];
  return state_->is_free(surface_.nodes[pair.slot]) || state_->is_free(e[0]) ||
         state_->is_free(e[1]);
}

void ContactManager::EdgeCandidates(const double* a, const double* b, double grow,
                                    std::vector<EdgePair>* pairs) const {
  pairs->clear();
  if (!options_.self_contact || surface_.edges.empty()) return;
  const Eigen::Vector3d g = Eigen::Vector3d::Constant(grow);
  hash_.Clear();
  for (size_t e = 0; e < surface_.edges.size(); ++e) {
    const int i = surface_.edges[e][0], j = surface_.edges[e][1];
    const Eigen::Vector3d ai = ToPoint(a + 2 * i, 2), bi = ToPoint(b + 2 * i, 2);
    const Eigen::Vector3d aj = ToPoint(a + 2 * j, 2), bj = ToPoint(b + 2 * j, 2);
    hash_.Insert(static_cast<int>(e), Min3(Min3(ai, bi), Min3(aj, bj)) - g,
                 Max3(Max3(ai, bi), Max3(aj, bj)) + g);
  }
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    const int node = surface_.nodes[s];
    const Eigen::Vector3d pa = ToPoint(a + 2 * node, 2), pb = ToPoint(b + 2 * node, 2);
    hash_.Query(Min3(pa, pb), Max3(pa, pb), &scratch_ids_);
    for (int e : scratch_ids_) {
      const auto& edge = surface_.edges[e];
      if (edge[0] == node || edge[1] == node) continue;
      pairs->push_back(EdgePair{static_cast<int>(s), e});
    }
  }
}

std::vector<ContactManager::EdgeObstaclePair> ContactManager::AllEdgeObstaclePairs(
    bool free_only) const {
  std::vector<EdgeObstaclePair> pairs;
  for (size_t e = 0; e < surface_.edges.size(); ++e) {
    if (free_only && !slot_free_[edge_slots_[e][0]] && !slot_free_[edge_slots_[e][1]]) continue;
    for (size_t o = 0; o < options_.obstacles.size(); ++o) {
      const int features = options_.obstacles[o].NumEdgeFeatures();
      for (int f = 0; f < features; ++f) {
        pairs.push_back(EdgeObstaclePair{static_cast<int>(e), static_cast<int>(o), f});
      }
    }
  }
  return pairs;
}

double ContactManager::EdgeObstacleTimeOfImpact(const double* a, const double* b, double t_a,
                                                double t_b) const {
  double first = Obstacle::kNoImpact;
  for (size_t o = 0; o < options_.obstacles.size(); ++o) {
    const Obstacle& obstacle = options_.obstacles[o];
    const int features = obstacle.NumEdgeFeatures();
    if (features == 0) continue;
    for (size_t e = 0; e < surface_.edges.size(); ++e) {
      const int edge = static_cast<int>(e);
      const Eigen::Vector3d a0 = EdgeEnd(a, edge, 0), a1 = EdgeEnd(b, edge, 0);
      const Eigen::Vector3d b0 = EdgeEnd(a, edge, 1), b1 = EdgeEnd(b, edge, 1);
      for (int f = 0; f < features; ++f) {
        first = std::min(first, obstacle.EdgeTimeOfImpact(f, a0, a1, b0, b1, t_a, t_b, margin_));
        if (first == 0.0) return 0.0;
      }
    }
  }
  return first;
}

std::string ContactManager::EdgeObstacleConflict(const double* a, const double* x, double t) const {
  if (dim_ != 2) return "";
  for (size_t o = 0; o < options_.obstacles.size(); ++o) {
    const Obstacle& obstacle = options_.obstacles[o];
    if (obstacle.type == ObstacleType::kPlane) continue;
    // Features that can cross an edge's interior first, in world coordinates.
    const Eigen::Vector3d shift = obstacle.velocity * t;
    std::vector<Eigen::Vector2d> features;
    if (obstacle.type == ObstacleType::kSphere) {
      features.push_back((obstacle.point + shift).head<2>());
    } else {
      for (int corner = 0; corner < 4; ++corner) {
        features.emplace_back((corner & 1 ? obstacle.upper : obstacle.lower)[0] + shift[0],
                              (corner & 2 ? obstacle.upper : obstacle.lower)[1] + shift[1]);
      }
    }
    for (const auto& e : surface_.edges) {
      const Eigen::Vector3d p = ToPoint(x + 2 * e[0], 2), q = ToPoint(x + 2 * e[1], 2);
      // The segment p -> q read as a point path: it meets the grown obstacle.
      if (obstacle.TimeOfImpact(p, q, t, t, margin_) <= 1.0) {
        std::ostringstream out;
        out << "boundary edge (" << e[0] << ", " << e[1] << ") meets " << obstacle.name;
        return out.str();
      }
      if (a == x) continue;
      for (const Eigen::Vector2d& f : features) {
        if (PointEdgeTimeOfImpact(f, f, Node2(a, e[0]), Node2(x, e[0]), Node2(a, e[1]),
                                  Node2(x, e[1])) <= 1.0) {
          std::ostringstream out;
          out << "boundary edge (" << e[0] << ", " << e[1] << ") sweeps across " << obstacle.name;
          return out.str();
        }
      }
    }
  }
  return "";
}

std::string ContactManager::FindPenetration(const double* x, double t) const {
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    for (size_t o = 0; o < options_.obstacles.size(); ++o) {
      const double d = options_.obstacles[o].Distance(NodePoint(x, s), t);
      if (!(d > margin_)) {
        std::ostringstream out;
        out << "node " << surface_.nodes[s] << " is inside or touching "
            << options_.obstacles[o].name << " (distance " << d << ")";
        return out.str();
      }
    }
  }
  const std::string conflict = EdgeObstacleConflict(x, x, t);
  if (!conflict.empty()) return conflict;
  for (const EdgeObstaclePair& p : AllEdgeObstaclePairs(false)) {
    const Obstacle& o = options_.obstacles[p.obstacle];
    const double d = o.EdgeDistance(p.feature, EdgeEnd(x, p.edge, 0), EdgeEnd(x, p.edge, 1), t);
    if (!(d > margin_)) {
      const auto& e = surface_.edges[p.edge];
      std::ostringstream out;
      out << "edge (" << e[0] << ", " << e[1] << ") is inside or touching " << o.name
          << " (distance " << d << ")";
      return out.str();
    }
  }
  const std::string mesh = mesh_pairs_->FindPenetration(x, t);
  if (!mesh.empty()) return mesh;
  std::vector<EdgePair> pairs;
  EdgeCandidates(x, x, 0.0, &pairs);
  for (const EdgePair& p : pairs) {
    const auto& e = surface_.edges[p.edge];
    const int node = surface_.nodes[p.slot];
    const double d = PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1])).distance;
    if (!(d > margin_)) {
      std::ostringstream out;
      out << "boundary node " << node << " touches boundary edge (" << e[0] << ", " << e[1]
          << ") (distance " << d << ")";
      return out.str();
    }
  }
  if (options_.self_contact) {
    // Edges crossing without a node on the other edge.
    for (size_t e = 0; e < surface_.edges.size(); ++e) {
      const auto& ea = surface_.edges[e];
      const Eigen::Vector3d lo = Min3(ToPoint(x + 2 * ea[0], 2), ToPoint(x + 2 * ea[1], 2));
      const Eigen::Vector3d hi = Max3(ToPoint(x + 2 * ea[0], 2), ToPoint(x + 2 * ea[1], 2));
      for (size_t f = e + 1; f < surface_.edges.size(); ++f) {
        const auto& eb = surface_.edges[f];
        if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
        const Eigen::Vector3d lo2 = Min3(ToPoint(x + 2 * eb[0], 2), ToPoint(x + 2 * eb[1], 2));
        const Eigen::Vector3d hi2 = Max3(ToPoint(x + 2 * eb[0], 2), ToPoint(x + 2 * eb[1], 2));
        if ((lo2.array() > hi.array()).any() || (lo.array() > hi2.array()).any()) continue;
        if (SegmentsIntersect(Node2(x, ea[0]), Node2(x, ea[1]), Node2(x, eb[0]), Node2(x, eb[1]))) {
          std::ostringstream out;
          out << "boundary edges (" << ea[0] << ", " << ea[1] << ") and (" << eb[0] << ", " << eb[1]
              << ") intersect";
          return out.str();
        }
      }
    }
  }
  return "";
}

void ContactManager::OnAccepted(const double* x) {
  std::copy(x, x + accepted_.size(), accepted_.data());
}

bool ContactManager::IsStepValid(const double* x) const {
  const double* a = accepted_.data();
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    const Eigen::Vector3d pa = NodePoint(a, s), pb = NodePoint(x, s);
    for (const Obstacle& o : options_.obstacles) {
      if (o.TimeOfImpact(pa, pb, tau_, tau_, margin_) <= 1.0) return false;
    }
  }
  if (!EdgeObstacleConflict(a, x, tau_).empty()) return false;
  if (EdgeObstacleTimeOfImpact(a, x, tau_, tau_) <= 1.0) return false;
  if (mesh_pairs_->TimeOfImpact(a, x, tau_, tau_) <= 1.0) return false;
  if (options_.self_contact) {
    std::vector<EdgePair> pairs;
    EdgeCandidates(a, x, margin_, &pairs);
    for (const EdgePair& p : pairs) {
      const auto& e = surface_.edges[p.edge];
      const int node = surface_.nodes[p.slot];
      if (PointEdgeTimeOfImpact(Node2(a, node), Node2(x, node), Node2(a, e[0]), Node2(x, e[0]),
                                Node2(a, e[1]), Node2(x, e[1])) <= 1.0) {
        return false;
      }
      if (!(PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1])).distance > margin_)) {
        return false;
      }
    }
  }
  return true;
}

double ContactManager::MaxStepSize(const double* from, const double* to) const {
  double t = 1.0;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    const Eigen::Vector3d pa = NodePoint(from, s), pb = NodePoint(to, s);
    for (const Obstacle& o : options_.obstacles) {
      t = std::min(t, o.TimeOfImpact(pa, pb, tau_, tau_, margin_));
    }
  }
  if (options_.self_contact) {
    std::vector<EdgePair> pairs;
    EdgeCandidates(from, to, margin_, &pairs);
    for (const EdgePair& p : pairs) {
      const auto& e = surface_.edges[p.edge];
      const int node = surface_.nodes[p.slot];
      t = std::min(t, PointEdgeTimeOfImpact(Node2(from, node), Node2(to, node), Node2(from, e[0]),
                                            Node2(to, e[0]), Node2(from, e[1]), Node2(to, e[1])));
    }
  }
  t = std::min(t, EdgeObstacleTimeOfImpact(from, to, tau_, tau_));
  t = std::min(t, mesh_pairs_->TimeOfImpact(from, to, tau_, tau_));
  t = std::clamp(t, 0.0, 1.0);
  // Edges against circles and boxes: halve until the path is clear.
  if (dim_ == 2 && t > 0.0) {
    Eigen::VectorXd end(accepted_.size());
    for (int halvings = 0; halvings < 60; ++halvings) {
      for (int k = 0; k < end.size(); ++k) end[k] = from[k] + t * (to[k] - from[k]);
      if (EdgeObstacleConflict(from, end.data(), tau_).empty()) break;
      t *= 0.5;
    }
  }
  return t;
}

bool ContactManager::IsFeasible(const double* x) const {
  if (tau_ < t_next_) return false;  // a moving obstacle did not reach its position
  return FindPenetration(x, tau_).empty();
}

double ContactManager::MinDistance(const double* x, double reach) const {
  double best = kInfinity;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    for (const Obstacle& o : options_.obstacles) {
      const double d = o.Distance(NodePoint(x, s), tau_);
      if (d < reach) best = std::min(best, d);
    }
  }
  std::vector<EdgePair> pairs;
  EdgeCandidates(x, x, reach, &pairs);
  for (const EdgePair& p : pairs) {
    const auto& e = surface_.edges[p.edge];
    const int node = surface_.nodes[p.slot];
    const double d = PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1])).distance;
    if (d < reach) best = std::min(best, d);
  }
  for (const EdgeObstaclePair& p : AllEdgeObstaclePairs(false)) {
    const double d = EdgeObstacleDistance(x, p);
    if (d < reach) best = std::min(best, d);
  }
  return std::min(best, mesh_pairs_->MinDistance(x, tau_, reach));
}

int ContactManager::CountPairsWithin(const double* x, double reach) const {
  int count = 0;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    for (const Obstacle& o : options_.obstacles) {
      count += o.Distance(NodePoint(x, s), tau_) < reach;
    }
  }
  std::vector<EdgePair> pairs;
  EdgeCandidates(x, x, reach, &pairs);
  for (const EdgePair& p : pairs) {
    const auto& e = surface_.edges[p.edge];
    const int node = surface_.nodes[p.slot];
    count += PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1])).distance < reach;
  }
  for (const EdgeObstaclePair& p : AllEdgeObstaclePairs(false)) {
    count += EdgeObstacleDistance(x, p) < reach;
  }
  return count + mesh_pairs_->CountWithin(x, tau_, reach);
}

std::vector<std::string> ContactManager::DiagnosticNames() const {
  return {"min_distance", "active_contacts"};
}

std::vector<double> ContactManager::Diagnostics(const double* x) const {
  const double d = MinDistance(x, options_.d_hat);
  return {std::isfinite(d) ? d : std::nan(""),
          static_cast<double>(CountPairsWithin(x, options_.d_hat))};
}

bool ContactManager::ExtendPairs(const double* a, const double* b, const std::vector<double>& reach,
                                 double edge_grow) {
  bool added = false;
  std::vector<ObstaclePair> new_obstacle_pairs;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    if (!slot_free_[s]) continue;
    const Eigen::Vector3d p = NodePoint(a, s);
    for (size_t o = 0; o < options_.obstacles.size(); ++o) {
      const double d = options_.obstacles[o].Distance(p, tau_);
      if (d < options_.d_hat + reach[s] + ObstacleTravel(static_cast<int>(o))) {
        new_obstacle_pairs.push_back(ObstaclePair{static_cast<int>(s), static_cast<int>(o)});
      }
    }
  }
  for (const ObstaclePair& pair : new_obstacle_pairs) {
    auto it = std::lower_bound(obstacle_pairs_.begin(), obstacle_pairs_.end(), pair);
    if (it == obstacle_pairs_.end() || !(*it == pair)) {
      obstacle_pairs_.insert(it, pair);
      added = true;
    }
  }
  for (const EdgeObstaclePair& pair : AllEdgeObstaclePairs(true)) {
    const auto& slots = edge_slots_[pair.edge];
    const double d = EdgeObstacleDistance(a, pair);
    if (!(d < options_.d_hat + std::max(reach[slots[0]], reach[slots[1]]) +
                  ObstacleTravel(pair.obstacle))) {
      continue;
    }
    auto it = std::lower_bound(edge_obstacle_pairs_.begin(), edge_obstacle_pairs_.end(), pair);
    if (it == edge_obstacle_pairs_.end() || !(*it == pair)) {
      double alpha = 0.0;
      PointSegmentDistance(options_.obstacles[pair.obstacle].EdgeFeature(pair.feature, tau_),
                           EdgeEnd(a, pair.edge, 0), EdgeEnd(a, pair.edge, 1), &alpha);
      edge_obstacle_alpha_.insert(
          edge_obstacle_alpha_.begin() + (it - edge_obstacle_pairs_.begin()), alpha);
      edge_obstacle_pairs_.insert(it, pair);
      added = true;
    }
  }
  std::vector<double> travel(options_.obstacles.size());
  for (size_t o = 0; o < travel.size(); ++o) travel[o] = ObstacleTravel(static_cast<int>(o));
  added |= mesh_pairs_->Extend(a, tau_, reach, travel);
  std::vector<EdgePair> candidates;
  EdgeCandidates(a, b, options_.d_hat + edge_grow, &candidates);
  for (const EdgePair& pair : candidates) {
    if (!PairHasFreeNode(pair)) continue;
    auto it = std::lower_bound(edge_pairs_.begin(), edge_pairs_.end(), pair);
    if (it == edge_pairs_.end() || !(*it == pair)) {
      edge_pairs_.insert(it, pair);
      added = true;
    }
  }
  return added;
}

void ContactManager::RebuildBarrierTerms() {
  potential_->RemoveTerms(kContactFamily);
  const double d_hat = options_.d_hat;
  for (const ObstaclePair& pair : obstacle_pairs_) {
    Term term;
    term.kind = TermKind::kPotential;
    term.family = kContactFamily;
    term.impulsive = true;
    term.nodes = {surface_.nodes[pair.slot]};
    const Obstacle& obstacle = options_.obstacles[pair.obstacle];
    auto cost = std::make_unique<PointObstacleGap>(dim_, &obstacle, &tau_, d_hat, margin_);
    if (obstacle.type == ObstacleType::kPlane) {
      term.gauss_newton_model = true;  // the plane's distance is affine
    } else {
      term.curvature = GapCurvature(cost.get());
    }
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(d_hat, surface_.weights[pair.slot], &kappa_);
    potential_->AddTerm(std::move(term));
  }
  for (size_t k = 0; k < edge_obstacle_pairs_.size(); ++k) {
    const EdgeObstaclePair& pair = edge_obstacle_pairs_[k];
    const auto& e = surface_.edges[pair.edge];
    Term term;
    term.kind = TermKind::kPotential;
    term.family = kContactFamily;
    term.impulsive = true;
    term.nodes = {e[0], e[1]};
    // The lagged closest point keeps a sphere's gap convex; a box corner
    // (radius 0) uses the true distance: with the lag, a corner the edge slides
    // along sees the lagged point's distance sqrt(d^2 + s^2) >> d, the barrier
    // vanishes and the solve stalls against the CCD at d ~ 1e-10 m (a square
    // dropped into a gap between two boxes failed most steps).
    const Obstacle& obstacle = options_.obstacles[pair.obstacle];
    auto cost = std::make_unique<EdgeObstacleGap>(
        dim_, &obstacle, pair.feature, &tau_, d_hat, margin_,
        obstacle.FeatureRadius() > 0.0 ? &edge_obstacle_alpha_[k] : nullptr);
    term.curvature = GapCurvature(cost.get());
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(d_hat, surface_.edge_weights[pair.edge], &kappa_);
    potential_->AddTerm(std::move(term));
  }
  mesh_pairs_->AddBarrierTerms(potential_, kContactFamily, &tau_, &kappa_);
  for (const EdgePair& pair : edge_pairs_) {
    const auto& e = surface_.edges[pair.edge];
    Term term;
    term.kind = TermKind::kPotential;
    term.family = kContactFamily;
    term.impulsive = true;
    term.nodes = {surface_.nodes[pair.slot], e[0], e[1]};
    auto cost = std::make_unique<PointEdgeGap>(d_hat, margin_);
    term.curvature = GapCurvature(cost.get());
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(d_hat, surface_.weights[pair.slot], &kappa_);
    potential_->AddTerm(std::move(term));
  }
}

double ContactManager::LagEdgeAlpha(const double* x) {
  double excess = 0.0;
  for (size_t k = 0; k < edge_obstacle_pairs_.size(); ++k) {
    const EdgeObstaclePair& p = edge_obstacle_pairs_[k];
    const Obstacle& o = options_.obstacles[p.obstacle];
    const Eigen::Vector3d a = EdgeEnd(x, p.edge, 0), b = EdgeEnd(x, p.edge, 1);
    double alpha = 0.0;
    PointSegmentDistance(o.EdgeFeature(p.feature, tau_), a, b, &alpha);
    const double d = o.EdgeDistance(p.feature, a, b, tau_);
    if (d > 0.0 && d < options_.d_hat) {
      const double lagged = o.EdgePointDistance(p.feature, a, b, edge_obstacle_alpha_[k], tau_);
      excess = std::max(excess, (lagged - d) / d);
    }
    edge_obstacle_alpha_[k] = alpha;
  }
  return std::max(excess, mesh_pairs_->Lag(x, tau_));
}

void ContactManager::LagFriction(const double* x, double t) {
  lagged_obstacle_.clear();
  lagged_edge_.clear();
  if (!friction_enabled_ || !(friction_.mu > 0.0)) return;
  const double d_hat = options_.d_hat;
  for (const ObstaclePair& pair : obstacle_pairs_) {
    const Obstacle& o = options_.obstacles[pair.obstacle];
    Eigen::Vector3d n;
    const double d = o.Distance(NodePoint(x, pair.slot), t, &n);
    if (!(d > 0.0 && d < d_hat)) continue;
    const double lambda = -kappa_ * surface_.weights[pair.slot] * BarrierDerivative(d, d_hat);
    lagged_obstacle_.push_back(LaggedObstacleFriction{surface_.nodes[pair.slot],
                                                      TangentBasis(n, dim_), o.velocity, lambda});
  }
  for (const EdgePair& pair : edge_pairs_) {
    const auto& e = surface_.edges[pair.edge];
    const int node = surface_.nodes[pair.slot];
    const PointEdgeDistanceResult r =
        PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1]));
    if (!(r.distance > 0.0 && r.distance < d_hat)) continue;
    const double lambda =
        -kappa_ * surface_.weights[pair.slot] * BarrierDerivative(r.distance, d_hat);
    const Eigen::Vector2d tangent(-r.grad_p[1], r.grad_p[0]);
    lagged_edge_.push_back(LaggedEdgeFriction{node, e[0], e[1], tangent, r.alpha, lambda});
  }
}

void ContactManager::RebuildFrictionTerms() {
  if (!friction_enabled_) return;
  potential_->RemoveTerms(kFrictionFamily);
  num_friction_contacts_ = 0;
  // 3D: one term per contact (side 0); 2D: the exact split, one term per side.
  const double eps_v = friction_.epsilon_v;
  const double c = kFrictionSpeedScale * eps_v;
  const std::vector<int> sides = dim_ == 2 ? std::vector<int>{1, -1} : std::vector<int>{0};
  auto add = [&](std::vector<int> nodes, std::unique_ptr<ceres::CostFunction> cost, double scale,
                 int side) {
    Term term;
    term.kind = TermKind::kDissipation;
    term.family = kFrictionFamily;
    term.impulsive = true;
    term.nodes = std::move(nodes);
    term.cost = std::move(cost);
    if (side == 0) {
      term.loss = std::make_unique<FrictionLoss>(scale);
    } else {
      term.loss = std::make_unique<OneSidedFrictionLoss>(scale, c, eps_v);
    }
    potential_->AddTerm(std::move(term));
  };
  for (const LaggedObstacleFriction& f : lagged_obstacle_) {
    for (int side : sides) {
      add({f.node},
          std::make_unique<ObstacleFriction>(context_, f.node, f.tangents, f.obstacle_velocity,
                                             eps_v, side, c),
          friction_.mu * f.normal_force, side);
    }
    ++num_friction_contacts_;
  }
  for (const LaggedEdgeFriction& f : lagged_edge_) {
    for (int side : {1, -1}) {
      add({f.p, f.a, f.b},
          std::make_unique<EdgeFriction>(context_, f.p, f.a, f.b, f.tangent, f.alpha, side, c),
          friction_.mu * f.normal_force, side);
    }
    ++num_friction_contacts_;
  }
}

void ContactManager::AdvanceObstacles(const double* x) {
  if (!has_moving_obstacles_) {
    tau_ = t_next_;
    return;
  }
  double first = Obstacle::kNoImpact;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    const Eigen::Vector3d p = NodePoint(x, s);
    for (const Obstacle& o : options_.obstacles) {
      if (!o.is_moving()) continue;
      first = std::min(first, o.TimeOfImpact(p, p, tau_, t_next_, margin_));
    }
  }
  first = std::min(first, EdgeObstacleTimeOfImpact(x, x, tau_, t_next_));
  first = std::min(first, mesh_pairs_->TimeOfImpact(x, x, tau_, t_next_));
  if (first > 1.0) {
    tau_ = t_next_;
  } else {
    tau_ += kObstacleAdvanceFraction * first * (t_next_ - tau_);
  }
}

void ContactManager::UpdateKappa(const double* x_n) {
  if (!adaptive_) return;
  const double d_hat = options_.d_hat;
  const double gap = MinDistance(x_n, d_hat);
  if (!kappa_balanced_ && gap < d_hat) {
    // g_B: gradient of sum_pairs w_U w_i B(d) (kappa = 1); g_E: of the rest of E.
    const int n = static_cast<int>(accepted_.size());
    Eigen::VectorXd g_b = Eigen::VectorXd::Zero(n), g_e = Eigen::VectorXd::Zero(n);
    const double w_u = context_->potential_weight;
    for (size_t s = 0; s < surface_.nodes.size(); ++s) {
      for (const Obstacle& o : options_.obstacles) {
        Eigen::Vector3d grad;
        const double d = o.Distance(NodePoint(x_n, s), tau_, &grad);
        if (!(d > 0.0 && d < d_hat)) continue;
        const double scale = w_u * surface_.weights[s] * BarrierDerivative(d, d_hat);
        for (int k = 0; k < dim_; ++k) g_b[dim_ * surface_.nodes[s] + k] += scale * grad[k];
      }
    }
    std::vector<EdgePair> pairs;
    EdgeCandidates(x_n, x_n, d_hat, &pairs);
    for (const EdgePair& p : pairs) {
      const auto& e = surface_.edges[p.edge];
      const int node = surface_.nodes[p.slot];
      const PointEdgeDistanceResult r =
          PointEdgeDistance(Node2(x_n, node), Node2(x_n, e[0]), Node2(x_n, e[1]));
      if (!(r.distance > 0.0 && r.distance < d_hat)) continue;
      const double scale = w_u * surface_.weights[p.slot] * BarrierDerivative(r.distance, d_hat);
      g_b.segment<2>(2 * node) += scale * r.grad_p;
      g_b.segment<2>(2 * e[0]) += scale * r.grad_a;
      g_b.segment<2>(2 * e[1]) += scale * r.grad_b;
    }
    for (const EdgeObstaclePair& p : AllEdgeObstaclePairs(false)) {
      Eigen::Vector3d grad[2];
      const double d = EdgeObstacleDistance(x_n, p, &grad[0], &grad[1]);
      if (!(d > 0.0 && d < d_hat)) continue;
      const double scale = w_u * surface_.edge_weights[p.edge] * BarrierDerivative(d, d_hat);
      for (int end = 0; end < 2; ++end) {
        const int node = surface_.edges[p.edge][end];
        for (int k = 0; k < dim_; ++k) g_b[dim_ * node + k] += scale * grad[end][k];
      }
    }
    mesh_pairs_->AddBarrierGradient(x_n, tau_, w_u, &g_b);
    const TermKind kinds[3] = {TermKind::kInertia, TermKind::kPotential, TermKind::kDissipation};
    Eigen::VectorXd gradient(n);
    bool ok = true;
    for (TermKind kind : kinds) {
      double energy = 0.0;
      ok &= potential_->EvaluateUnweighted(
          [kind](const Term& t) {
            return t.kind == kind && t.family != kContactFamily && t.family != kFrictionFamily;
          },
          x_n, &energy, gradient.data());
      if (ok) g_e += TermWeight(kind, *context_) * gradient;
    }
    for (int i = 0; i < state_->num_nodes(); ++i) {
      if (state_->is_free(i)) continue;
      g_b.segment(dim_ * i, dim_).setZero();
      g_e.segment(dim_ * i, dim_).setZero();
    }
    const double norm2 = g_b.squaredNorm();
    if (ok && norm2 > 0.0) {
      kappa_ = std::clamp(-g_b.dot(g_e) / norm2, kappa_min_, kappa_max_);
      kappa_balanced_ = true;
    }
  } else if (gap < kShrinkingGapFraction * d_hat && gap < previous_min_gap_) {
    kappa_ = std::min(2.0 * kappa_, kappa_max_);
  }
  previous_min_gap_ = gap;
}

void ContactManager::BeginStep(const double* x_n) {
  t_n_ = state_->time;
  t_next_ = t_n_ + context_->time_step;
  tau_ = t_n_;
  // The barrier energy at x_n before and after this step's stiffness and pairs
  // (for the energy balance: PrescribedWork).
  double energy_before = 0.0;
  const bool before_ok = BarrierEnergy(x_n, t_n_, &energy_before);
  OnAccepted(x_n);
  UpdateKappa(x_n);

  // Candidate pairs for this step: reach from the predictor's displacement.
  const std::vector<ObstaclePair> old_obstacle_pairs = obstacle_pairs_;
  const std::vector<EdgePair> old_edge_pairs = edge_pairs_;
  const std::vector<EdgeObstaclePair> old_edge_obstacle_pairs = edge_obstacle_pairs_;
  obstacle_pairs_.clear();
  edge_pairs_.clear();
  edge_obstacle_pairs_.clear();
  edge_obstacle_alpha_.clear();
  mesh_pairs_->Clear();
  alpha_lags_ = 0;
  const Eigen::VectorXd& x_tilde = context_->x_tilde;
  std::vector<double> reach(surface_.nodes.size());
  double max_reach = 0.0;
  for (size_t s = 0; s < surface_.nodes.size(); ++s) {
    const int node = surface_.nodes[s];
    double r2 = 0.0;
    for (int k = 0; k < dim_; ++k) {
      const double d = x_tilde[dim_ * node + k] - x_n[dim_ * node + k];
      r2 += d * d;
    }
    reach[s] = 2.0 * std::sqrt(r2);
    max_reach = std::max(max_reach, reach[s]);
  }
  // Quasi-static steps have no predictor: the solution may be anywhere (a body
  // in the air falls onto an obstacle within one step), so every node-obstacle
  // pair is a candidate (terms out of reach are exactly zero).
  if (!(context_->inertia_weight > 0.0)) {
    std::fill(reach.begin(), reach.end(), kInfinity);
  }
  ExtendPairs(x_n, x_tilde.data(), reach, max_reach);

  LagFriction(x_n, t_n_);
  lags_done_ = 1;
  AdvanceObstacles(x_n);
  LagEdgeAlpha(x_n);
  // Edge-obstacle and face terms point into their lags, refilled above.
  if (obstacle_pairs_ != old_obstacle_pairs || edge_pairs_ != old_edge_pairs ||
      edge_obstacle_pairs_ != old_edge_obstacle_pairs || !edge_obstacle_pairs_.empty() ||
      !mesh_pairs_->empty()) {
    RebuildBarrierTerms();
  }
  RebuildFrictionTerms();
  double energy_after = 0.0;
  begin_energy_input_ =
      before_ok && BarrierEnergy(x_n, t_n_, &energy_after) ? energy_after - energy_before : 0.0;
}

bool ContactManager::BarrierEnergy(const double* x, double t, double* energy) {
  const double saved_tau = tau_;
  tau_ = t;
  const bool ok = potential_->EvaluateUnweighted(
      [](const Term& term) { return term.family == kContactFamily; }, x, energy, nullptr);
  tau_ = saved_tau;
  return ok;
}

double ContactManager::PrescribedWork(const double* x_start, const double* x_end) {
  if (!has_moving_obstacles_ || !(t_next_ > t_n_)) return begin_energy_input_;
  const double h = t_next_ - t_n_, delta = 1e-6 * h;
  // dU_b/dt at fixed positions by central differences in the obstacle time.
  const auto rate = [&](const double* x, double t, double* value) {
    double up = 0.0, down = 0.0;
    if (!BarrierEnergy(x, t + delta, &up) || !BarrierEnergy(x, t - delta, &down)) return false;
    *value = (up - down) / (2.0 * delta);
    return true;
  };
  double at_start = 0.0, at_end = 0.0;
  const bool start_ok = rate(x_start, t_n_, &at_start);
  const bool end_ok = rate(x_end, t_next_, &at_end);
  double work = 0.0;
  if (start_ok && end_ok) {
    work = 0.5 * h * (at_start + at_end);
  } else if (start_ok || end_ok) {
    work = h * (start_ok ? at_start : at_end);
  }
  return begin_energy_input_ + work;
}

bool ContactManager::RefreshTerms(const double* x) {
  bool changed = false;
  if (tau_ < t_next_) {
    AdvanceObstacles(x);
    changed = true;
  }
  // Pairs within d_hat of the solution that the set missed (with margin d_hat).
  const std::vector<double> reach(surface_.nodes.size(), options_.d_hat);
  const double gap_reach = options_.d_hat;
  const size_t before = obstacle_pairs_.size() + edge_pairs_.size() + edge_obstacle_pairs_.size() +
                        mesh_pairs_->size();
  // Only add pairs if some pair within d_hat is missing.
  bool missing = false;
  for (size_t s = 0; s < surface_.nodes.size() && !missing; ++s) {
    if (!slot_free_[s]) continue;
    for (size_t o = 0; o < options_.obstacles.size(); ++o) {
      if (options_.obstacles[o].Distance(NodePoint(x, s), tau_) < options_.d_hat &&
          !std::binary_search(obstacle_pairs_.begin(), obstacle_pairs_.end(),
                              ObstaclePair{static_cast<int>(s), static_cast<int>(o)})) {
        missing = true;
        break;
      }
    }
  }
  if (!missing) {
    for (const EdgeObstaclePair& p : AllEdgeObstaclePairs(true)) {
      if (EdgeObstacleDistance(x, p) < options_.d_hat &&
          !std::binary_search(edge_obstacle_pairs_.begin(), edge_obstacle_pairs_.end(), p)) {
        missing = true;
        break;
      }
    }
  }
  if (!missing) missing = mesh_pairs_->Missing(x, tau_);
  if (!missing && options_.self_contact) {
    std::vector<EdgePair> pairs;
    EdgeCandidates(x, x, options_.d_hat, &pairs);
    for (const EdgePair& p : pairs) {
      if (!PairHasFreeNode(p)) continue;
      const auto& e = surface_.edges[p.edge];
      const int node = surface_.nodes[p.slot];
      if (PointEdgeDistance(Node2(x, node), Node2(x, e[0]), Node2(x, e[1])).distance <
              options_.d_hat &&
          !std::binary_search(edge_pairs_.begin(), edge_pairs_.end(), p)) {
        missing = true;
        break;
      }
    }
  }
  if (missing || changed) {
    ExtendPairs(x, x, reach, gap_reach);
    if (obstacle_pairs_.size() + edge_pairs_.size() + edge_obstacle_pairs_.size() +
            mesh_pairs_->size() !=
        before) {
      RebuildBarrierTerms();
      changed = true;
    }
  }
  // Edge-obstacle and face-sphere barriers use the closest point lagged at the
  // start of the solve; re-lag and solve again while it is more than 1 %
  // farther than the true closest point for a pair in reach (at most
  // kMaxAlphaLags times).
  if (!changed && (!edge_obstacle_pairs_.empty() || !mesh_pairs_->empty()) &&
      alpha_lags_ < kMaxAlphaLags) {
    std::vector<double> saved = edge_obstacle_alpha_;
    const MeshObstaclePairs::Lags saved_mesh = mesh_pairs_->SavedLags();
    if (LagEdgeAlpha(x) > kAlphaLagTolerance) {
      ++alpha_lags_;
      changed = true;
    } else {
      edge_obstacle_alpha_ = saved;
      mesh_pairs_->RestoreLags(saved_mesh);
    }
  }
  if (!changed && friction_enabled_ && lags_done_ < friction_.iterations) {
    LagFriction(x, tau_);
    RebuildFrictionTerms();
    ++lags_done_;
    changed = true;
  }
  return changed;
}

}  // namespace ipstep
