// Pair kind (3D): a face of the collision mesh against a face feature of an
// obstacle (a sphere's centre, a 3D box's corners; Obstacle::FaceDistance),
// with friction (contact/primitive_obstacle_friction.h). Registered before
// the box-edge pairs (contact/pairs/box_edge_pairs.h), the other half of a
// 3D mesh's contact with obstacle features.
//
// Barrier (FaceObstacleGap in contact/contact_terms.h): weight the face's
// (contact/collision_mesh.h). Against a sphere's centre the gap is that of the
// face's closest point lagged as barycentric weights (set when a pair is added
// and by Lag), so that it is convex in the vertices within a solve, like the
// edge-obstacle pairs' (docs/contact.md, "Edges against obstacles"); the
// lagged gap exceeds the true one by about |lag offset|^2 / (2 (R + d)).
// Against box corners (R = 0) that excess is the offset itself, first order
// in how far the cloth slides within a solve, and the barrier then held the
// cloth back too weakly (it stalled against the collision detection at the
// margin while sliding off a box edge), so those pairs use the true distance.
// Evaluation failures, collision detection and the checks use the true
// distances.
//
// Friction: lagged at the true distance, the closest point's barycentric
// weights, the normal from the feature towards it (the sum of the distance's
// vertex gradients) and the normal force kappa w (-B'(d)).
//
// Cost: each face is bounded by a ball (centre: the mean of its vertices;
// radius: the farthest vertex); a face whose ball is far from an obstacle
// skips all of its features with one distance to the obstacle, and each
// feature with one point-feature distance, before any exact distance.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/pair_kind.h"
#include "contact/primitive_obstacle_friction.h"

namespace ipstep {

struct FaceObstaclePair {
  int face;  // index into mesh->faces
  int obstacle;
  int feature;  // Obstacle::FaceFeature
  bool operator<(const FaceObstaclePair& o) const {
    if (face != o.face) return face < o.face;
    return obstacle != o.obstacle ? obstacle < o.obstacle : feature < o.feature;
  }
  bool operator==(const FaceObstaclePair& o) const {
    return face == o.face && obstacle == o.obstacle && feature == o.feature;
  }
};

// Per pair: the lagged barycentric weights (read by the terms of pairs
// against a sphere's centre).
class FaceObstaclePairs : public PairKind<FaceObstaclePairs, FaceObstaclePair, Eigen::Vector3d,
                                          PrimitiveObstacleFrictionLag> {
 public:
  using Pair = FaceObstaclePair;
  // Faces whose nodes are all fixed get no pairs. Empty unless some obstacle
  // has face features (3D spheres and boxes) and the mesh has faces.
  explicit FaceObstaclePairs(const PairSetContext& context);

  const char* name() const override { return "face-obstacle"; }
  bool active() const { return active_; }
  // First fraction of the path from a (obstacle time t_a) to b (t_b) at which
  // a face reaches its collision-detection goal (conservative, see
  // Obstacle::FaceTimeOfImpact); kNoImpact if none.
  double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const override;

  bool TermsReadLags() const override { return !pairs_.empty(); }
  // Re-lags every sphere-face pair's closest point at x; returns the largest
  // relative excess (d_lagged - d) / d of the previous lag over those pairs
  // within d_hat.
  double Lag(const double* x) override;
  void SaveLags() override { saved_ = pairs_.data(); }
  void RestoreLags() override { pairs_.data() = saved_; }

 private:
  using Base =
      PairKind<FaceObstaclePairs, FaceObstaclePair, Eigen::Vector3d, PrimitiveObstacleFrictionLag>;
  friend Base;
  // The distance with its gradients over the face's vertices and the closest
  // point's barycentric weights.
  struct Measured : PairDistance<3> {
    Eigen::Vector3d weights;
  };

  Eigen::Vector3d Vertex(const double* x, int node) const { return ToPoint(x + 3 * node, 3); }
  // Calls f(pair) for every combination whose lower bound at x, time t, is
  // below cutoff(face) + travel[obstacle] (travel null: 0).
  template <class Cutoff, class F>
  void ForEachNear(const double* x, double t, const Cutoff& cutoff,
                   const std::vector<double>* travel, const F& f) const;
  // The base's candidates: within `grow` at x, time t; Extend's: at the
  // region's start, within d_hat + the face's reach + the obstacle's travel.
  template <class F>
  void ForEachCandidateAt(const double* x, double t, double grow, const F& f) const;
  template <class F>
  void ForEachCandidateIn(const CandidateRegion& region, const F& f) const;
  bool HasFreeNode(const Pair& pair) const;
  double Weight(const Pair& pair) const { return c_.mesh->face_weights[pair.face]; }
  double Distance(const double* x, double t, const Pair& pair) const;
  Measured Measure(const double* x, double t, const Pair& pair) const;
  // Extend's distance bound for `face`, before the obstacle's travel.
  double ExtendCutoff(const CandidateRegion& region, int face) const;
  // A new pair's lag: the closest point at the start.
  bool Admits(const CandidateRegion& region, const Pair& pair, Eigen::Vector3d* weights) const;
  std::string Describe(const Pair& pair) const;
  void SetGap(size_t k, Term* term) const;
  bool LagPairFriction(const double* x, double t, const Pair& pair, const Measured& measured,
                       PrimitiveObstacleFrictionLag* lag) const;

  bool active_ = false;
  std::vector<std::array<int, 3>> face_slots_;  // slots of each face's nodes
  std::vector<Eigen::Vector3d> saved_;
};

// Instantiated once, in the .cc (where ForEachNear is defined).
extern template class PairKind<FaceObstaclePairs, FaceObstaclePair, Eigen::Vector3d,
                               PrimitiveObstacleFrictionLag>;

}  // namespace ipstep
