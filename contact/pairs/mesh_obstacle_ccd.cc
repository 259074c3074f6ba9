// MeshObstaclePairs::TimeOfImpact (contact/pairs/mesh_obstacle_pairs.h): the
// faces' and edges' continuous collision detection against the obstacles'
// face features and box edges, with the bounding-ball rejection.
#include <algorithm>
#include <cmath>

#include "contact/pairs/mesh_obstacle_pairs.h"

namespace ipstep {

double MeshObstaclePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                       double t_b) const {
  if (!active_) return Obstacle::kNoImpact;
  double first = Obstacle::kNoImpact;
  // In the obstacle's frame (features at time 0), the primitive's path lies in
  // the ball around m (the mean of its start vertices, a point of the start
  // primitive) through all its start and end vertices. A feature at distance
  // D from m (D >= d(0), as m is on the primitive) keeps every gap d(s) >=
  // D - rho, above the goal max(margin, phi d(0)) when D - rho > margin and
  // (1 - phi) D > rho; the obstacle's signed distance of m bounds every D.
  const double phi = Obstacle::kEdgeGapFraction;
  auto safe = [&](double d, double rho) { return d - rho > margin_ && (1.0 - phi) * d > rho; };
  for (const ObstaclePtr& obstacle_ptr : *obstacles_) {
    const Obstacle& obstacle = *obstacle_ptr;
    const int features = obstacle.NumFaceFeatures(), box_edges = obstacle.NumBoxEdges();
    if (features == 0 && box_edges == 0) continue;
    const Eigen::Vector3d shift_a = obstacle.Shift(t_a), shift_b = obstacle.Shift(t_b);
    for (size_t f = 0; f < surface_->faces.size() && features > 0; ++f) {
      const auto& face = surface_->faces[f];
      Eigen::Vector3d v0[3], v1[3];
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        v0[i] = Vertex(a, face[i]);
        v1[i] = Vertex(b, face[i]);
        m += (v0[i] - shift_a) / 3.0;
      }
      double rho2 = 0.0;
      for (int i = 0; i < 3; ++i) {
        rho2 = std::max(
            {rho2, (v0[i] - shift_a - m).squaredNorm(), (v1[i] - shift_b - m).squaredNorm()});
      }
      const double rho = std::sqrt(rho2);
      if (safe(obstacle.Distance(m, 0.0), rho)) continue;
      for (int k = 0; k < features; ++k) {
        if (safe((obstacle.FaceFeature(k, 0.0) - m).norm() - obstacle.FeatureRadius(), rho)) {
          continue;
        }
        first = std::min(first, obstacle.FaceTimeOfImpact(k, v0, v1, t_a, t_b, margin_));
        if (first == 0.0) return 0.0;
      }
    }
    for (size_t e = 0; e < surface_->edges.size() && box_edges > 0; ++e) {
      const auto& edge = surface_->edges[e];
      const Eigen::Vector3d a0 = Vertex(a, edge[0]), a1 = Vertex(b, edge[0]);
      const Eigen::Vector3d b0 = Vertex(a, edge[1]), b1 = Vertex(b, edge[1]);
      const Eigen::Vector3d m = 0.5 * (a0 + b0) - shift_a;
      const double rho =
          std::sqrt(std::max({(a0 - shift_a - m).squaredNorm(), (a1 - shift_b - m).squaredNorm(),
                              (b1 - shift_b - m).squaredNorm()}));
      if (safe(obstacle.Distance(m, 0.0), rho)) continue;
      for (int k = 0; k < box_edges; ++k) {
        Eigen::Vector3d p, q;
        obstacle.BoxEdge(k, 0.0, &p, &q);
        if (safe(PointSegmentDistance(m, p, q), rho)) continue;
        first = std::min(first, obstacle.BoxEdgeTimeOfImpact(k, a0, a1, b0, b1, t_a, t_b, margin_));
        if (first == 0.0) return 0.0;
      }
    }
  }
  return first;
}

}  // namespace ipstep
