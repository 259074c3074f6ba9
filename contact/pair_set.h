// One kind of contact pair (node-obstacle, edge-obstacle, face-obstacle,
// box-edge, 2D point-edge, 3D point-triangle, 3D edge-edge, ...): the unit the
// contact state (contact/contact_state.h) is made of. A pair kind implements,
// once:
//  * candidates: which pairs of primitives of the collision mesh
//    (contact/collision_mesh.h) and obstacles can come within d_hat
//    (Extend, Missing), kept as the kind's active set (sorted, it only grows
//    within a step);
//  * distance: the smallest gap and number of close combinations (Near), the
//    intersection check (FindPenetration), the barrier gradient for the
//    adaptive stiffness (AddBarrierGradient);
//  * time of impact: the first fraction of a linear motion at which any
//    combination reaches the margin (TimeOfImpact; conservative, never late);
//  * terms: one barrier term per active pair (AddBarrierTerms), optional
//    lagged closest points (Lag) and friction (LagFriction, AddFrictionTerms).
// Geometry queries (TimeOfImpact, FindPenetration, Near, AddBarrierGradient)
// cover every combination of primitives, in the active set or not; only the
// terms are restricted to the set.
//
// Adding a pair kind: one class in contact/pairs/ deriving from
// PairKind<Kind, Pair> (contact/pair_kind.h), which writes the active set,
// Extend, Missing, Near, the barrier gradient, the penetration search over the
// pairs, the barrier-term loop and the friction lag loop; the kind writes its
// candidate search, per-pair distance and derivatives, Extend's rule
// (Admits), TimeOfImpact and its term factory (SetGap, friction terms); and
// one line in contact/pair_kinds.cc.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/collision_mesh.h"
#include "contact/obstacle.h"
#include "core/incremental_potential.h"
#include "core/step_context.h"

namespace ipstep {

// What every pair set reads, filled by the contact state that makes the sets
// (contact/contact_state.cc). Fixed for the state's lifetime, except the
// values behind the pointers, which the state updates and the terms read at
// every evaluation.
struct PairSetContext {
  int dimension = 3;
  int num_coordinates = 0;  // size of a configuration x (dimension x nodes)
  const CollisionMesh* mesh = nullptr;
  const ObstacleList* obstacles = nullptr;
  // Per entry of mesh->nodes: whether that node is free (pairs whose nodes
  // are all fixed get no terms).
  const std::vector<bool>* node_free = nullptr;
  double d_hat = 1e-3;
  // Smallest admissible gap: barrier terms fail to evaluate at or below it,
  // and time of impact stops there.
  double margin = 0.0;
  const double* time = nullptr;   // the obstacles' current time tau [s]
  const double* kappa = nullptr;  // barrier stiffness
  const StepContext* step = nullptr;
  // The terms' owners: the barrier's ("contact") and friction's ("friction")
  // families and the contact state's term groups.
  TermOwner barrier{"contact", 0};
  TermOwner friction{"friction", 0};
};

// Where Extend looks for candidates: positions moving from `start` to `end`
// (end == start: around one configuration). A combination is a candidate when
// its distance at `start`, at the current obstacle time, is below
//   d_hat + (largest reach of its nodes) + (its obstacle's remaining travel),
// or, for pairs between two parts of the mesh, when their bounding boxes over
// start -> end, grown by d_hat + max_reach, overlap.
struct CandidateRegion {
  const double* start = nullptr;
  const double* end = nullptr;
  const std::vector<double>* reach = nullptr;   // per entry of mesh->nodes [m]
  double max_reach = 0.0;                       // [m]
  const std::vector<double>* travel = nullptr;  // per obstacle [m]
};

struct FrictionSettings {
  double mu = 0.0;          // the friction effect's
  double epsilon_v = 1e-3;  // [m/s]
  double self_mu = -1.0;    // self-contact pairs' (contact.self_contact_mu); < 0: mu
  // The coefficient of pairs with obstacle o (its own "mu", else mu) and of
  // self-contact pairs.
  double ForObstacle(const Obstacle& o) const { return o.friction_mu().value_or(mu); }
  double ForSelf() const { return self_mu >= 0.0 ? self_mu : mu; }
};

class PairSet {
 public:
  // The fraction TimeOfImpact returns when no combination reaches the margin.
  static constexpr double kNoImpact = Obstacle::kNoImpact;

  virtual ~PairSet() = default;
  virtual const char* name() const = 0;

  // Active set.
  // Empties the set, remembering it for ChangedSinceClear.
  virtual void Clear() = 0;
  virtual size_t size() const = 0;
  // Whether the set differs from the one Clear emptied.
  virtual bool ChangedSinceClear() const = 0;
  // Adds the candidates of `region` that have a free node; true if any was new.
  virtual bool Extend(const CandidateRegion& region) = 0;
  // True if a combination with a free node is within d_hat at x (current
  // obstacle time) and not in the set.
  virtual bool Missing(const double* x) const = 0;

  // Geometry over every combination.
  // First fraction s in [0, 1] of the motion a -> b (obstacles moving from
  // time t_a to t_b) at which a combination comes within the margin;
  // conservative (never later than the true first contact); 0 if it starts
  // there; kNoImpact if none. With a == b and t_a == t_b: 0 when x is
  // infeasible, kNoImpact otherwise.
  virtual double TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const = 0;
  // After the sweep of the filter's MaxStepSize (ContactState::Sweep, the
  // smallest TimeOfImpact over all kinds, clamped to [0, 1]): a fraction <= t
  // that a check TimeOfImpact cannot express needs (default: t).
  virtual double ShrinkToClear(const double* from, const double* to, double t) const {
    (void)from;
    (void)to;
    return t;
  }
  // Empty if every combination keeps more than the margin at x, time t, and
  // no primitive passes through another; otherwise a description of the first
  // conflict (naming nodes and obstacles).
  virtual std::string FindPenetration(const double* x, double t) const = 0;
  // Over combinations closer than `reach` at x, time t: lowers *min_distance
  // to their smallest gap and adds their number to *count.
  virtual void Near(const double* x, double t, double reach, double* min_distance,
                    int* count) const = 0;
  // Adds scale * w B'(d) grad d (kappa = 1) of every combination within d_hat
  // at x, time t, to g (the adaptive stiffness's balance; w the pair's weight).
  virtual void AddBarrierGradient(const double* x, double t, double scale,
                                  Eigen::VectorXd* g) const = 0;

  // Terms of the active set.
  // One barrier term per active pair (owner context.barrier, kind
  // kPotential, impulsive), reading time and kappa through the context.
  virtual void AddBarrierTerms(IncrementalPotential* potential) const = 0;
  // True if the terms read lagged data that BeginStep refills (the contact
  // state then rebuilds them every step).
  virtual bool TermsReadLags() const { return false; }
  // Re-lags closest points at x; returns the largest relative excess
  // (d_lagged - d) / d of the previous lag over active pairs within d_hat.
  virtual double Lag(const double* x) {
    (void)x;
    return 0.0;
  }
  virtual void SaveLags() {}
  virtual void RestoreLags() {}

  // Wall time spent in the broad phase (tree builds and box queries, not the
  // exact distances or impact times of the candidates it returns) since the
  // set was made [s]; 0 for kinds without one (they test every combination).
  virtual double BroadPhaseSeconds() const { return 0.0; }

  // Friction of the active pairs within d_hat at x, obstacle time t: lags the
  // normal force kappa w (-B'(d)) and the tangent basis.
  virtual void LagFriction(const double* x, double t) {
    (void)x;
    (void)t;
  }
  // Adds the lagged friction terms (owner context.friction, kind
  // kDissipation); returns the number of contacts with friction.
  virtual int AddFrictionTerms(const FrictionSettings& friction,
                               IncrementalPotential* potential) const {
    (void)friction;
    (void)potential;
    return 0;
  }
};

}  // namespace ipstep
