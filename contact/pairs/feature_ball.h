// The bounding-ball rejection of the time of impact of the 3D kinds against
// obstacle features (contact/pairs/face_obstacle_pairs.h, box_edge_pairs.h).
// In the obstacle's frame (features at time 0), a primitive's path lies in the
// ball around m (the mean of its start vertices, a point of the start
// primitive) through all its start and end vertices; for a rotating obstacle
// (curved paths) in the ball around m of radius max |y_i(0) - m| plus the
// obstacle's bound on how far a rest-frame path goes (Obstacle::
// RestPathBound). A feature at distance D from m (D >= d(0), as m is on the
// primitive) keeps every gap d(s) >= D - rho, above the goal max(margin, phi
// d(0)) when D - rho > margin and (1 - phi) D > rho; the obstacle's signed
// distance of m bounds every D.
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "contact/obstacle.h"

namespace ipstep {

// Whether a feature at distance d from the ball's centre stays clear of every
// path in the ball of radius rho (phi = Obstacle::kEdgeGapFraction).
inline bool FeatureClearsBall(double d, double rho, double margin) {
  const double phi = Obstacle::kEdgeGapFraction;
  return d - rho > margin && (1.0 - phi) * d > rho;
}

// rho for n vertices moving from v0 (obstacle time t_a) to v1 (t_b), at
// rest-frame starts y0 and ends y1, around m.
inline double PathBallRadius(const Obstacle& obstacle, const Eigen::Vector3d* v0,
                             const Eigen::Vector3d* v1, const Eigen::Vector3d* y0,
                             const Eigen::Vector3d* y1, int n, const Eigen::Vector3d& m, double t_a,
                             double t_b) {
  double rho2 = 0.0;
  if (!obstacle.rotates()) {
    for (int i = 0; i < n; ++i) {
      rho2 = std::max({rho2, (y0[i] - m).squaredNorm(), (y1[i] - m).squaredNorm()});
    }
    return std::sqrt(rho2);
  }
  for (int i = 0; i < n; ++i) rho2 = std::max(rho2, (y0[i] - m).squaredNorm());
  return std::sqrt(rho2) + obstacle.RestPathBound(v0, v1, n, t_a, t_b);
}

}  // namespace ipstep
