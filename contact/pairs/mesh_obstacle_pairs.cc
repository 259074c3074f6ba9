#include "contact/pairs/mesh_obstacle_pairs.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "geometry/point_triangle.h"

namespace ipstep {

MeshObstaclePairs::MeshObstaclePairs(const PairSetContext& context)
    : c_(context),
      surface_(context.mesh),
      obstacles_(context.obstacles),
      slot_free_(*context.node_free),
      d_hat_(context.d_hat),
      margin_(context.margin) {
  for (const ObstaclePtr& o_ptr : *obstacles_) {
    const Obstacle& o = *o_ptr;
    active_ |= (o.NumFaceFeatures() > 0 && !surface_->faces.empty()) ||
               (o.NumBoxEdges() > 0 && !surface_->edges.empty());
  }
  for (const auto& f : surface_->faces) {
    face_slots_.push_back(
        {NodeSlot(*surface_, f[0]), NodeSlot(*surface_, f[1]), NodeSlot(*surface_, f[2])});
  }
  for (const auto& e : surface_->edges) {
    edge_slots_.push_back({NodeSlot(*surface_, e[0]), NodeSlot(*surface_, e[1])});
  }
}

bool MeshObstaclePairs::FaceIsFree(int face) const {
  const auto& s = face_slots_[face];
  return slot_free_[s[0]] || slot_free_[s[1]] || slot_free_[s[2]];
}

bool MeshObstaclePairs::EdgeIsFree(int edge) const {
  const auto& s = edge_slots_[edge];
  return slot_free_[s[0]] || slot_free_[s[1]];
}

double MeshObstaclePairs::FaceReach(int face, const std::vector<double>& reach) const {
  const auto& s = face_slots_[face];
  return std::max({reach[s[0]], reach[s[1]], reach[s[2]]});
}

double MeshObstaclePairs::EdgeReach(int edge, const std::vector<double>& reach) const {
  const auto& s = edge_slots_[edge];
  return std::max(reach[s[0]], reach[s[1]]);
}

double MeshObstaclePairs::Distance(const double* x, double t, const FacePair& p,
                                   Eigen::Vector3d* grad, Eigen::Vector3d* weights) const {
  const auto& f = surface_->faces[p.face];
  return (*obstacles_)[p.obstacle]->FaceDistance(p.feature, Vertex(x, f[0]), Vertex(x, f[1]),
                                                 Vertex(x, f[2]), t, grad, weights);
}

double MeshObstaclePairs::Distance(const double* x, double t, const BoxEdgePair& p,
                                   Eigen::Vector3d* grad, double* s) const {
  const auto& e = surface_->edges[p.edge];
  return (*obstacles_)[p.obstacle]->BoxEdgeDistance(p.box_edge, Vertex(x, e[0]), Vertex(x, e[1]), t,
                                                    grad ? &grad[0] : nullptr,
                                                    grad ? &grad[1] : nullptr, s);
}

template <class Cutoff, class OnFace, class OnEdge>
void MeshObstaclePairs::ForEachNear(const double* x, double t, bool free_only,
                                    const Cutoff& face_cutoff, const Cutoff& edge_cutoff,
                                    const std::vector<double>* travel, const OnFace& on_face,
                                    const OnEdge& on_edge) const {
  if (!active_) return;
  const ObstacleList& obstacles = *obstacles_;
  const int num_obstacles = static_cast<int>(obstacles.size());
  // A feature at distance D from the ball's centre m (minus R for a sphere) is
  // at least D - rho from the primitive: it can be below the cutoff only if
  // D < cutoff + rho. The obstacle's signed distance of m is a lower bound of
  // every feature's D.
  for (int f = 0; f < static_cast<int>(surface_->faces.size()); ++f) {
    if (free_only && !FaceIsFree(f)) continue;
    const auto& face = surface_->faces[f];
    const Eigen::Vector3d v[3] = {Vertex(x, face[0]), Vertex(x, face[1]), Vertex(x, face[2])};
    const Eigen::Vector3d m = (v[0] + v[1] + v[2]) / 3.0;
    const double rho = std::sqrt(
        std::max({(v[0] - m).squaredNorm(), (v[1] - m).squaredNorm(), (v[2] - m).squaredNorm()}));
    const double cutoff = face_cutoff(f);
    for (int o = 0; o < num_obstacles; ++o) {
      const Obstacle& obstacle = *obstacles[o];
      const int features = obstacle.NumFaceFeatures();
      if (features == 0) continue;
      const double limit = cutoff + (travel ? (*travel)[o] : 0.0) + rho;
      if (!(obstacle.Distance(m, t) < limit)) continue;
      for (int k = 0; k < features; ++k) {
        const double d = (obstacle.FaceFeature(k, t) - m).norm() - obstacle.FeatureRadius();
        if (d < limit) on_face(FacePair{f, o, k});
      }
    }
  }
  for (int e = 0; e < static_cast<int>(surface_->edges.size()); ++e) {
    if (free_only && !EdgeIsFree(e)) continue;
    const auto& edge = surface_->edges[e];
    const Eigen::Vector3d a = Vertex(x, edge[0]), b = Vertex(x, edge[1]);
    const Eigen::Vector3d m = 0.5 * (a + b);
    const double rho = 0.5 * (b - a).norm();
    const double cutoff = edge_cutoff(e);
    for (int o = 0; o < num_obstacles; ++o) {
      const Obstacle& obstacle = *obstacles[o];
      const int box_edges = obstacle.NumBoxEdges();
      if (box_edges == 0) continue;
      const double limit = cutoff + (travel ? (*travel)[o] : 0.0) + rho;
      if (!(obstacle.Distance(m, t) < limit)) continue;
      for (int k = 0; k < box_edges; ++k) {
        Eigen::Vector3d p, q;
        obstacle.BoxEdge(k, t, &p, &q);
        if (PointSegmentDistance(m, p, q) < limit) on_edge(BoxEdgePair{e, o, k});
      }
    }
  }
}

bool MeshObstaclePairs::Extend(const double* x, double t, const std::vector<double>& reach,
                               const std::vector<double>& travel) {
  bool added = false;
  auto face_cutoff = [&](int f) { return d_hat_ + FaceReach(f, reach); };
  auto edge_cutoff = [&](int e) { return d_hat_ + EdgeReach(e, reach); };
  ForEachNear(
      x, t, true, std::function<double(int)>(face_cutoff), std::function<double(int)>(edge_cutoff),
      &travel,
      [&](const FacePair& p) {
        if (!(Distance(x, t, p) < face_cutoff(p.face) + travel[p.obstacle])) return;
        if (face_pairs_.Contains(p)) return;
        Eigen::Vector3d w;  // a new pair's lag
        Distance(x, t, p, nullptr, &w);
        added |= face_pairs_.Insert(p, w);
      },
      [&](const BoxEdgePair& p) {
        if (Distance(x, t, p) < edge_cutoff(p.edge) + travel[p.obstacle]) {
          added |= box_edge_pairs_.Insert(p);
        }
      });
  return added;
}

bool MeshObstaclePairs::Missing(const double* x, double t) const {
  bool missing = false;
  auto cutoff = std::function<double(int)>([&](int) { return d_hat_; });
  ForEachNear(
      x, t, true, cutoff, cutoff, nullptr,
      [&](const FacePair& p) {
        if (!missing && Distance(x, t, p) < d_hat_ && !face_pairs_.Contains(p)) {
          missing = true;
        }
      },
      [&](const BoxEdgePair& p) {
        if (!missing && Distance(x, t, p) < d_hat_ && !box_edge_pairs_.Contains(p)) {
          missing = true;
        }
      });
  return missing;
}

double MeshObstaclePairs::Lag(const double* x, double t) {
  double excess = 0.0;
  for (size_t k = 0; k < face_pairs_.size(); ++k) {
    const FacePair& p = face_pairs_[k];
    if (!((*obstacles_)[p.obstacle]->FeatureRadius() > 0.0)) continue;  // true distance
    const auto& f = surface_->faces[p.face];
    Eigen::Vector3d w;
    const double d = Distance(x, t, p, nullptr, &w);
    if (d > 0.0 && d < d_hat_) {
      const double lagged = (*obstacles_)[p.obstacle]->FacePointDistance(
          p.feature, Vertex(x, f[0]), Vertex(x, f[1]), Vertex(x, f[2]), face_pairs_.data()[k], t);
      excess = std::max(excess, (lagged - d) / d);
    }
    face_pairs_.data()[k] = w;
  }
  return excess;
}

void MeshObstaclePairs::AddBarrierTerms(IncrementalPotential* potential, const TermOwner& owner,
                                        const double* time, const double* kappa) const {
  for (size_t k = 0; k < face_pairs_.size(); ++k) {
    const FacePair& p = face_pairs_[k];
    const auto& f = surface_->faces[p.face];
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(owner);
    term.impulsive = true;
    term.nodes = {f[0], f[1], f[2]};
    const Obstacle& obstacle = *(*obstacles_)[p.obstacle];
    auto cost = std::make_unique<FaceObstacleGap>(
        &obstacle, p.feature, time, d_hat_, margin_,
        obstacle.FeatureRadius() > 0.0 ? &face_pairs_.data()[k] : nullptr);
    term.curvature = GapCurvature(cost.get());
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(d_hat_, surface_->face_weights[p.face], kappa);
    potential->AddTerm(std::move(term));
  }
  for (size_t k = 0; k < box_edge_pairs_.size(); ++k) {
    const BoxEdgePair& p = box_edge_pairs_[k];
    const auto& e = surface_->edges[p.edge];
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(owner);
    term.impulsive = true;
    term.nodes = {e[0], e[1]};
    auto cost = std::make_unique<EdgeBoxEdgeGap>((*obstacles_)[p.obstacle].get(), p.box_edge, time,
                                                 d_hat_, margin_);
    term.curvature = GapCurvature(cost.get());
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(d_hat_, surface_->edge_weights[p.edge], kappa);
    potential->AddTerm(std::move(term));
  }
}

std::string MeshObstaclePairs::FindPenetration(const double* x, double t) const {
  std::ostringstream out;
  auto cutoff = std::function<double(int)>([&](int) { return margin_; });
  ForEachNear(
      x, t, false, cutoff, cutoff, nullptr,
      [&](const FacePair& p) {
        const double d = Distance(x, t, p);
        if (!out.str().empty() || d > margin_) return;
        const auto& f = surface_->faces[p.face];
        out << "face (" << f[0] << ", " << f[1] << ", " << f[2] << ") is inside or touching "
            << (*obstacles_)[p.obstacle]->name() << " (distance " << d << ")";
      },
      [&](const BoxEdgePair& p) {
        const double d = Distance(x, t, p);
        if (!out.str().empty() || d > margin_) return;
        const auto& e = surface_->edges[p.edge];
        out << "edge (" << e[0] << ", " << e[1] << ") touches an edge of "
            << (*obstacles_)[p.obstacle]->name() << " (distance " << d << ")";
      });
  if (!out.str().empty()) return out.str();
  // Static only: a 3D box can hold a cloth edge passing through it (both ends
  // outside, no box edge touched) or pierce a face with one of its edges (no
  // corner or face edge touched). Continuous motion from a free state passes
  // a touching configuration first, caught above; this is for the initial
  // state.
  for (const ObstaclePtr& obstacle_ptr : *obstacles_) {
    const Obstacle& obstacle = *obstacle_ptr;
    if (obstacle.NumBoxEdges() == 0) continue;
    for (const auto& e : surface_->edges) {
      const Eigen::Vector3d a = Vertex(x, e[0]), b = Vertex(x, e[1]);
      if (obstacle.TimeOfImpact(a, b, t, t, margin_) <= 1.0) {
        out << "edge (" << e[0] << ", " << e[1] << ") passes through " << obstacle.name();
        return out.str();
      }
    }
    Eigen::Vector3d p[12], q[12];
    for (int k = 0; k < 12; ++k) obstacle.BoxEdge(k, t, &p[k], &q[k]);
    for (const auto& f : surface_->faces) {
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

double MeshObstaclePairs::MinDistance(const double* x, double t, double reach) const {
  double best = std::numeric_limits<double>::infinity();
  auto cutoff = std::function<double(int)>([&](int) { return reach; });
  ForEachNear(
      x, t, false, cutoff, cutoff, nullptr,
      [&](const FacePair& p) {
        const double d = Distance(x, t, p);
        if (d < reach) best = std::min(best, d);
      },
      [&](const BoxEdgePair& p) {
        const double d = Distance(x, t, p);
        if (d < reach) best = std::min(best, d);
      });
  return best;
}

int MeshObstaclePairs::CountWithin(const double* x, double t, double reach) const {
  int count = 0;
  auto cutoff = std::function<double(int)>([&](int) { return reach; });
  ForEachNear(
      x, t, false, cutoff, cutoff, nullptr,
      [&](const FacePair& p) { count += Distance(x, t, p) < reach; },
      [&](const BoxEdgePair& p) { count += Distance(x, t, p) < reach; });
  return count;
}

void MeshObstaclePairs::AddBarrierGradient(const double* x, double t, double scale,
                                           Eigen::VectorXd* g) const {
  auto cutoff = std::function<double(int)>([&](int) { return d_hat_; });
  auto add = [&](const std::vector<int>& nodes, const Eigen::Vector3d* grad, double d,
                 double weight) {
    if (!(d > 0.0 && d < d_hat_)) return;
    const double factor = scale * weight * BarrierDerivative(d, d_hat_);
    for (size_t i = 0; i < nodes.size(); ++i) g->segment<3>(3 * nodes[i]) += factor * grad[i];
  };
  ForEachNear(
      x, t, false, cutoff, cutoff, nullptr,
      [&](const FacePair& p) {
        Eigen::Vector3d grad[3];
        const double d = Distance(x, t, p, grad);
        const auto& f = surface_->faces[p.face];
        add({f[0], f[1], f[2]}, grad, d, surface_->face_weights[p.face]);
      },
      [&](const BoxEdgePair& p) {
        Eigen::Vector3d grad[2];
        const double d = Distance(x, t, p, grad);
        const auto& e = surface_->edges[p.edge];
        add({e[0], e[1]}, grad, d, surface_->edge_weights[p.edge]);
      });
}

}  // namespace ipstep
