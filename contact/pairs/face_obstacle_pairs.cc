#include "contact/pairs/face_obstacle_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "contact/contact_terms.h"
#include "contact/pairs/feature_ball.h"

namespace ipstep {

FaceObstaclePairs::FaceObstaclePairs(const PairSetContext& context) : Base(context) {
  for (const ObstaclePtr& o : *c_.obstacles) {
    active_ |= o->NumFaceFeatures() > 0 && !c_.mesh->faces.empty();
  }
  for (const auto& f : c_.mesh->faces) {
    face_slots_.push_back(
        {NodeSlot(*c_.mesh, f[0]), NodeSlot(*c_.mesh, f[1]), NodeSlot(*c_.mesh, f[2])});
  }
}

double FaceObstaclePairs::Distance(const double* x, double t, const Pair& p) const {
  const auto& f = c_.mesh->faces[p.face];
  return (*c_.obstacles)[p.obstacle]->FaceDistance(p.feature, Vertex(x, f[0]), Vertex(x, f[1]),
                                                   Vertex(x, f[2]), t);
}

FaceObstaclePairs::Measured FaceObstaclePairs::Measure(const double* x, double t,
                                                       const Pair& p) const {
  const auto& f = c_.mesh->faces[p.face];
  Measured m;
  m.nodes = f;
  m.distance =
      (*c_.obstacles)[p.obstacle]->FaceDistance(p.feature, Vertex(x, f[0]), Vertex(x, f[1]),
                                                Vertex(x, f[2]), t, m.gradient.data(), &m.weights);
  return m;
}

bool FaceObstaclePairs::HasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *c_.node_free;
  const auto& s = face_slots_[pair.face];
  return free[s[0]] || free[s[1]] || free[s[2]];
}

template <class Cutoff, class F>
void FaceObstaclePairs::ForEachNear(const double* x, double t, const Cutoff& cutoff,
                                    const std::vector<double>* travel, const F& f) const {
  if (!active_) return;
  const ObstacleList& obstacles = *c_.obstacles;
  const int num_obstacles = static_cast<int>(obstacles.size());
  // A feature at distance D from the ball's centre m (minus R for a sphere) is
  // at least D - rho from the face: it can be below the cutoff only if
  // D < cutoff + rho. The obstacle's signed distance of m is a lower bound of
  // every feature's D.
  for (int i = 0; i < static_cast<int>(c_.mesh->faces.size()); ++i) {
    const auto& face = c_.mesh->faces[i];
    const Eigen::Vector3d v[3] = {Vertex(x, face[0]), Vertex(x, face[1]), Vertex(x, face[2])};
    const Eigen::Vector3d m = (v[0] + v[1] + v[2]) / 3.0;
    const double rho = std::sqrt(
        std::max({(v[0] - m).squaredNorm(), (v[1] - m).squaredNorm(), (v[2] - m).squaredNorm()}));
    const double face_cutoff = cutoff(i);
    for (int o = 0; o < num_obstacles; ++o) {
      const Obstacle& obstacle = *obstacles[o];
      const int features = obstacle.NumFaceFeatures();
      if (features == 0) continue;
      const double limit = face_cutoff + (travel ? (*travel)[o] : 0.0) + rho;
      if (!(obstacle.Distance(m, t) < limit)) continue;
      for (int k = 0; k < features; ++k) {
        const double d = (obstacle.FaceFeature(k, t) - m).norm() - obstacle.FeatureRadius();
        if (d < limit) f(Pair{i, o, k});
      }
    }
  }
}

template <class F>
void FaceObstaclePairs::ForEachCandidateAt(const double* x, double t, double grow,
                                           const F& f) const {
  ForEachNear(
      x, t, [grow](int) { return grow; }, nullptr, f);
}

template <class F>
void FaceObstaclePairs::ForEachCandidateIn(const CandidateRegion& region, const F& f) const {
  ForEachNear(
      region.start, *c_.time, [&](int face) { return ExtendCutoff(region, face); }, region.travel,
      f);
}

double FaceObstaclePairs::ExtendCutoff(const CandidateRegion& region, int face) const {
  const std::vector<double>& reach = *region.reach;
  const auto& s = face_slots_[face];
  return c_.d_hat + std::max({reach[s[0]], reach[s[1]], reach[s[2]]});
}

bool FaceObstaclePairs::Admits(const CandidateRegion& region, const Pair& pair,
                               Eigen::Vector3d* weights) const {
  const double cutoff = ExtendCutoff(region, pair.face) + (*region.travel)[pair.obstacle];
  if (!(Distance(region.start, *c_.time, pair) < cutoff)) return false;
  *weights = Measure(region.start, *c_.time, pair).weights;
  return true;
}

double FaceObstaclePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                       double t_b) const {
  if (!active_) return kNoImpact;
  double first = kNoImpact;
  for (const ObstaclePtr& obstacle_ptr : *c_.obstacles) {
    const Obstacle& obstacle = *obstacle_ptr;
    const int features = obstacle.NumFaceFeatures();
    if (features == 0) continue;
    for (const auto& face : c_.mesh->faces) {
      Eigen::Vector3d v0[3], v1[3], y0[3], y1[3];
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        v0[i] = Vertex(a, face[i]);
        v1[i] = Vertex(b, face[i]);
        y0[i] = obstacle.ToRest(v0[i], t_a);
        y1[i] = obstacle.ToRest(v1[i], t_b);
        m += y0[i] / 3.0;
      }
      const double rho = PathBallRadius(obstacle, v0, v1, y0, y1, 3, m, t_a, t_b);
      if (FeatureClearsBall(obstacle.Distance(m, 0.0), rho, c_.margin)) continue;
      for (int k = 0; k < features; ++k) {
        const double d = (obstacle.FaceFeature(k, 0.0) - m).norm() - obstacle.FeatureRadius();
        if (FeatureClearsBall(d, rho, c_.margin)) continue;
        first = std::min(first, obstacle.FaceTimeOfImpact(k, v0, v1, t_a, t_b, c_.margin));
        if (first == 0.0) return 0.0;
      }
    }
  }
  return first;
}

std::string FaceObstaclePairs::Describe(const Pair& pair) const {
  const auto& f = c_.mesh->faces[pair.face];
  std::ostringstream out;
  out << "face (" << f[0] << ", " << f[1] << ", " << f[2] << ") is inside or touching "
      << (*c_.obstacles)[pair.obstacle]->name();
  return out.str();
}

void FaceObstaclePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& f = c_.mesh->faces[pair.face];
  term->nodes = {f[0], f[1], f[2]};
  const Obstacle& obstacle = *(*c_.obstacles)[pair.obstacle];
  SetGapCost(std::make_unique<FaceObstacleGap>(
                 &obstacle, pair.feature, c_.time, c_.d_hat, c_.margin,
                 obstacle.FeatureRadius() > 0.0 ? &pairs_.data()[k] : nullptr),
             term);
}

double FaceObstaclePairs::Lag(const double* x) {
  const double t = *c_.time;
  double excess = 0.0;
  std::vector<Eigen::Vector3d>& weights = pairs_.data();
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const Pair& p = pairs_[k];
    const Obstacle& o = *(*c_.obstacles)[p.obstacle];
    if (!(o.FeatureRadius() > 0.0)) continue;  // true distance
    const auto& f = c_.mesh->faces[p.face];
    const Measured m = Measure(x, t, p);
    if (m.distance > 0.0 && m.distance < c_.d_hat) {
      const double lagged = o.FacePointDistance(p.feature, Vertex(x, f[0]), Vertex(x, f[1]),
                                                Vertex(x, f[2]), weights[k], t);
      excess = std::max(excess, (lagged - m.distance) / m.distance);
    }
    weights[k] = m.weights;
  }
  return excess;
}

bool FaceObstaclePairs::LagPairFriction(const double* x, double t, const Pair& pair,
                                        const Measured& m,
                                        PrimitiveObstacleFrictionLag* lag) const {
  const auto& f = c_.mesh->faces[pair.face];
  const Eigen::Vector3d& w = m.weights;
  const Eigen::Vector3d point =
      w[0] * Vertex(x, f[0]) + w[1] * Vertex(x, f[1]) + w[2] * Vertex(x, f[2]);
  *lag = LagPrimitiveObstacleFriction(*(*c_.obstacles)[pair.obstacle], t,
                                      m.gradient[0] + m.gradient[1] + m.gradient[2], point,
                                      NormalForce(pair, m.distance));
  lag->num_nodes = 3;
  lag->nodes = f;
  lag->alpha = {w[0], w[1], w[2]};
  return true;
}

// After ForEachNear, which the base's loops call.
template class PairKind<FaceObstaclePairs, FaceObstaclePair, Eigen::Vector3d,
                        PrimitiveObstacleFrictionLag>;

}  // namespace ipstep
