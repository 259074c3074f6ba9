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
  // primitive) through all its start and end vertices; for a rotating obstacle
  // (curved paths) in the ball around m of radius max |y_i(0) - m| plus the
  // obstacle's bound on how far a rest-frame path goes (Obstacle::
  // RestPathBound). A feature at distance D from m (D >= d(0), as m is on the
  // primitive) keeps every gap d(s) >= D - rho, above the goal max(margin, phi
  // d(0)) when D - rho > margin and (1 - phi) D > rho; the obstacle's signed
  // distance of m bounds every D.
  const double phi = Obstacle::kEdgeGapFraction;
  auto safe = [&](double d, double rho) { return d - rho > margin_ && (1.0 - phi) * d > rho; };
  // rho for n vertices at rest-frame starts y0 and ends y1 around m.
  auto radius = [](const Obstacle& obstacle, const Eigen::Vector3d* v0, const Eigen::Vector3d* v1,
                   const Eigen::Vector3d* y0, const Eigen::Vector3d* y1, int n,
                   const Eigen::Vector3d& m, double t_a, double t_b) {
    double rho2 = 0.0;
    if (!obstacle.rotates()) {
      for (int i = 0; i < n; ++i) {
        rho2 = std::max({rho2, (y0[i] - m).squaredNorm(), (y1[i] - m).squaredNorm()});
      }
      return std::sqrt(rho2);
    }
    for (int i = 0; i < n; ++i) rho2 = std::max(rho2, (y0[i] - m).squaredNorm());
    return std::sqrt(rho2) + obstacle.RestPathBound(v0, v1, n, t_a, t_b);
  };
  for (const ObstaclePtr& obstacle_ptr : *obstacles_) {
    const Obstacle& obstacle = *obstacle_ptr;
    const int features = obstacle.NumFaceFeatures(), box_edges = obstacle.NumBoxEdges();
    if (features == 0 && box_edges == 0) continue;
    for (size_t f = 0; f < surface_->faces.size() && features > 0; ++f) {
      const auto& face = surface_->faces[f];
      Eigen::Vector3d v0[3], v1[3], y0[3], y1[3];
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        v0[i] = Vertex(a, face[i]);
        v1[i] = Vertex(b, face[i]);
        y0[i] = obstacle.ToRest(v0[i], t_a);
        y1[i] = obstacle.ToRest(v1[i], t_b);
        m += y0[i] / 3.0;
      }
      const double rho = radius(obstacle, v0, v1, y0, y1, 3, m, t_a, t_b);
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
      const Eigen::Vector3d v0[2] = {Vertex(a, edge[0]), Vertex(a, edge[1])};
      const Eigen::Vector3d v1[2] = {Vertex(b, edge[0]), Vertex(b, edge[1])};
      const Eigen::Vector3d y0[2] = {obstacle.ToRest(v0[0], t_a), obstacle.ToRest(v0[1], t_a)};
      const Eigen::Vector3d y1[2] = {obstacle.ToRest(v1[0], t_b), obstacle.ToRest(v1[1], t_b)};
      const Eigen::Vector3d m = obstacle.ToRest(0.5 * (v0[0] + v0[1]), t_a);
      // (The second start vertex is as far from m as the first.)
      const double rho =
          obstacle.rotates()
              ? radius(obstacle, v0, v1, y0, y1, 2, m, t_a, t_b)
              : std::sqrt(std::max({(y0[0] - m).squaredNorm(), (y1[0] - m).squaredNorm(),
                                    (y1[1] - m).squaredNorm()}));
      if (safe(obstacle.Distance(m, 0.0), rho)) continue;
      for (int k = 0; k < box_edges; ++k) {
        Eigen::Vector3d p, q;
        obstacle.BoxEdge(k, 0.0, &p, &q);
        if (safe(PointSegmentDistance(m, p, q), rho)) continue;
        first = std::min(
            first, obstacle.BoxEdgeTimeOfImpact(k, v0[0], v1[0], v0[1], v1[1], t_a, t_b, margin_));
        if (first == 0.0) return 0.0;
      }
    }
  }
  return first;
}

}  // namespace ipstep
