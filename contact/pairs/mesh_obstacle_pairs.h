// Pair kind (3D): the collision mesh's faces against the obstacles' face
// features (sphere centre, 3D box corners; Obstacle::FaceDistance) and its
// edges against 3D box edges (Obstacle::BoxEdgeDistance), with friction
// (contact/primitive_obstacle_friction.h).
//
// Barrier (FaceObstacleGap, EdgeBoxEdgeGap in contact/contact_terms.h): weight
// the face's / edge's weight (contact/collision_mesh.h). Against a sphere's
// centre the gap is that of the face's closest point lagged as barycentric
// weights (set when a pair is added and by Lag), so that it is convex in the
// vertices within a solve, like the edge-obstacle pairs' (docs/contact.md,
// "Edges against obstacles"); the lagged gap exceeds the true one by about
// |lag offset|^2 / (2 (R + d)). Against box corners and box edges (R = 0) that
// excess is the offset itself, first order in how far the cloth slides within
// a solve, and the barrier then held the cloth back too weakly (it stalled
// against the collision detection at the margin while sliding off a box edge),
// so those pairs use the true distance. Evaluation failures, collision
// detection and the checks use the true distances.
//
// Cost: each face or edge is bounded by a ball (centre: the mean of its
// vertices; for a path, of the start vertices; radius: the farthest vertex
// over the path); a primitive whose ball is far from an obstacle skips all of
// its features with one distance to the obstacle, and each feature with one
// point-feature distance, before any exact distance.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_set.h"
#include "contact/primitive_obstacle_friction.h"
#include "contact/sorted_pairs.h"

namespace ipstep {

class MeshObstaclePairs : public PairSet {
 public:
  // Faces and edges whose nodes are all fixed get no pairs. Empty unless some
  // obstacle has face features or box edges (3D spheres and boxes).
  explicit MeshObstaclePairs(const PairSetContext& context);

  const char* name() const override { return "mesh-obstacle"; }
  bool active() const { return active_; }
  bool empty() const { return face_pairs_.empty() && box_edge_pairs_.empty(); }
  size_t size() const override { return face_pairs_.size() + box_edge_pairs_.size(); }
  void Clear() override {
    face_pairs_.Clear();
    box_edge_pairs_.Clear();
  }
  bool ChangedSinceClear() const override {
    return face_pairs_.Changed() || box_edge_pairs_.Changed();
  }
  bool Extend(const CandidateRegion& region) override {
    return Extend(region.start, *c_.time, *region.reach, *region.travel);
  }
  bool Missing(const double* x) const override { return Missing(x, *c_.time); }
  double Lag(const double* x) override { return Lag(x, *c_.time); }
  void SaveLags() override { saved_lag_ = face_pairs_.data(); }
  void RestoreLags() override { face_pairs_.data() = saved_lag_; }
  bool TermsReadLags() const override { return !empty(); }
  void AddBarrierTerms(IncrementalPotential* potential) const override {
    AddBarrierTerms(potential, c_.barrier, c_.time, c_.kappa);
  }
  // Friction (contact/pairs/mesh_obstacle_friction.cc): lagged closest
  // point, normal and normal force of every active pair within d_hat.
  void LagFriction(const double* x, double t) override;
  int AddFrictionTerms(const FrictionSettings& friction,
                       IncrementalPotential* potential) const override;
  void Near(const double* x, double t, double reach, double* min_distance,
            int* count) const override {
    *min_distance = std::min(*min_distance, MinDistance(x, t, reach));
    *count += CountWithin(x, t, reach);
  }

  // The PairSet operations above in terms of an explicit obstacle time t.
  // Adds the pairs of primitives with a free node whose distance at x (obstacle
  // time t) is below d_hat + reach + travel[obstacle], reach the largest of the
  // primitive's nodes' `reach` (per slot); new pairs are lagged at x. True if
  // any pair was added (the barrier terms must then be rebuilt).
  bool Extend(const double* x, double t, const std::vector<double>& reach,
              const std::vector<double>& travel);
  // True if a pair within d_hat at x is not in the set.
  bool Missing(const double* x, double t) const;

  // Re-lags every sphere-face pair's closest point at x; returns the largest
  // relative excess (d_lagged - d) / d of the previous lag over those pairs
  // within d_hat.
  double Lag(const double* x, double t);

  // Barrier terms of every pair (owner `owner`, kind kPotential, impulsive),
  // reading the obstacle time and kappa through the pointers. The terms point
  // into the lags: rebuild after Extend.
  void AddBarrierTerms(IncrementalPotential* potential, const TermOwner& owner, const double* time,
                       const double* kappa) const;

  // First fraction of the path from a (obstacle time t_a) to b (t_b) at which
  // a face or an edge reaches its collision-detection goal (conservative, see
  // Obstacle::FaceTimeOfImpact); Obstacle::kNoImpact if none.
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;
  // Empty if every face and edge keeps more than `margin` from the features at
  // x, time t, no cloth edge passes through a 3D box and no box edge through a
  // face; otherwise a description of the first conflict.
  std::string FindPenetration(const double* x, double t) const override;
  // Smallest distance / number of face-feature and edge-box-edge combinations
  // (all, pinned or not) closer than `reach`.
  double MinDistance(const double* x, double t, double reach) const;
  int CountWithin(const double* x, double t, double reach) const;
  // Adds scale * w B'(d) grad d of every combination within d_hat (true
  // distance) to g (kappa = 1), for the adaptive kappa's balance.
  void AddBarrierGradient(const double* x, double t, double scale,
                          Eigen::VectorXd* g) const override;

 private:
  struct FacePair {
    int face;
    int obstacle;
    int feature;
    bool operator<(const FacePair& o) const {
      if (face != o.face) return face < o.face;
      return obstacle != o.obstacle ? obstacle < o.obstacle : feature < o.feature;
    }
    bool operator==(const FacePair& o) const {
      return face == o.face && obstacle == o.obstacle && feature == o.feature;
    }
  };
  struct BoxEdgePair {
    int edge;
    int obstacle;
    int box_edge;
    bool operator<(const BoxEdgePair& o) const {
      if (edge != o.edge) return edge < o.edge;
      return obstacle != o.obstacle ? obstacle < o.obstacle : box_edge < o.box_edge;
    }
    bool operator==(const BoxEdgePair& o) const {
      return edge == o.edge && obstacle == o.obstacle && box_edge == o.box_edge;
    }
  };

  Eigen::Vector3d Vertex(const double* x, int node) const { return ToPoint(x + 3 * node, 3); }
  bool FaceIsFree(int face) const;
  bool EdgeIsFree(int edge) const;
  double FaceReach(int face, const std::vector<double>& reach) const;
  double EdgeReach(int edge, const std::vector<double>& reach) const;
  // True distances at x, time t (gradients, lag when not null).
  double Distance(const double* x, double t, const FacePair& p, Eigen::Vector3d* grad = nullptr,
                  Eigen::Vector3d* weights = nullptr) const;
  double Distance(const double* x, double t, const BoxEdgePair& p, Eigen::Vector3d* grad = nullptr,
                  double* s = nullptr) const;
  // Calls face(FacePair) and edge(BoxEdgePair) for every combination whose
  // lower bound at x, time t, is below threshold(obstacle, primitive's reach)
  // = cutoff + travel[obstacle], where cutoff is `cutoff(face/edge index)`.
  template <class Cutoff, class OnFace, class OnEdge>
  void ForEachNear(const double* x, double t, bool free_only, const Cutoff& face_cutoff,
                   const Cutoff& edge_cutoff, const std::vector<double>* travel,
                   const OnFace& on_face, const OnEdge& on_edge) const;

  PairSetContext c_;
  const CollisionMesh* surface_;
  const ObstacleList* obstacles_;
  std::vector<bool> slot_free_;
  double d_hat_;
  double margin_;
  bool active_ = false;
  std::vector<std::array<int, 3>> face_slots_;
  std::vector<std::array<int, 2>> edge_slots_;

  // The active sets (contact/sorted_pairs.h); a face pair's data: its lagged
  // barycentric weights.
  SortedPairs<FacePair, Eigen::Vector3d> face_pairs_;
  SortedPairs<BoxEdgePair> box_edge_pairs_;
  std::vector<Eigen::Vector3d> saved_lag_;
  std::vector<PrimitiveObstacleFrictionLag> friction_;
};

}  // namespace ipstep
