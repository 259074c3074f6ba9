// PairKind<Kind, Pair, Data, FrictionLag>: the PairSet (contact/pair_set.h)
// of a pair kind whose combinations are one Pair type, written once in terms
// of what only the kind knows (CRTP: Kind derives from PairKind<Kind, ...>).
// The base keeps the active set (SortedPairs<Pair, Data>) and writes Clear,
// size, ChangedSinceClear, Extend, Missing, Near, the pair-distance part of
// FindPenetration, AddBarrierGradient, AddBarrierTerms and the friction lag
// loop; every loop visits the kind's combinations in the order its
// candidate search gives them (sums into a gradient keep that order).
//
// The kind provides (private, with `friend Base;`):
//   template <class F> void ForEachCandidate(const double* a, const double* b,
//                                            double grow, const F& f) const;
//       calls f(pair) for every combination that can come within `grow` over
//       the motion a -> b (every combination for kinds without a broad phase);
//       or, for a candidate search that reads the obstacle time or Extend's
//       region (per-node reach, per-obstacle travel), instead of it (the
//       face-obstacle and box-edge kinds):
//   template <class F> void ForEachCandidateAt(const double* x, double t,
//                                              double grow, const F& f) const;
//       the combinations that can be within `grow` at x, obstacle time t;
//   template <class F> void ForEachCandidateIn(const CandidateRegion& r,
//                                              const F& f) const;
//       Extend's candidates in r (r.end set), a superset of those Admits takes;
//   bool HasFreeNode(const Pair&) const;
//   double Weight(const Pair&) const;            // the barrier's w
//   double Distance(const double* x, double t, const Pair&) const;
//   Measured Measure(const double* x, double t, const Pair&) const;
//       the distance with its gradient over the pair's nodes: any type with
//       the fields of PairDistance<N> (and whatever its friction lag reads);
//   bool Admits(const CandidateRegion& r, const Pair&, Data* data) const;
//       Extend's rule for a new candidate with a free node (r.end set), and
//       the data it starts with;
//   std::string Describe(const Pair&) const;     // "node 3 touches face (...)"
//   void SetGap(size_t k, Term* term) const;     // nodes, cost and curvature
//                                                // of active pair k's term
//   TimeOfImpact (PairSet's), and optionally:
//   std::string FindCrossing(const double* x, double t) const;  // checks
//       beyond the pairs' distances (default: none);
//   void AddPairBarrierGradient(...) const;      // default w B'(d) grad d;
//   with friction (FrictionLag not NoFrictionLag):
//   bool LagPairFriction(const double* x, double t, const Pair&,
//                        const Measured&, FrictionLag*) const;
//       an active pair within d_hat's lag (false: none), its normal force
//       from NormalForce;
//   int FrictionTerms(const std::vector<FrictionLag>&, const FrictionSettings&,
//                     IncrementalPotential*) const;
//       the terms of the lags (default, for SelfFrictionLag: one SelfFriction
//       term per lag, AddSelfFrictionTerms in contact/self_gap_terms.h; for
//       PrimitiveObstacleFrictionLag: one PrimitiveObstacleFriction term per
//       lag, contact/primitive_obstacle_friction.h).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/pair_set.h"
#include "contact/primitive_obstacle_friction.h"
#include "contact/self_gap_terms.h"
#include "contact/sorted_pairs.h"

namespace ipstep {

// A pair's distance at x and its gradient over the pair's N nodes (the first
// `dimension` components of each are used).
template <int N>
struct PairDistance {
  double distance = 0.0;
  std::array<int, N> nodes{};
  std::array<Eigen::Vector3d, N> gradient;
};

// FrictionLag of a kind without friction.
struct NoFrictionLag {};

// Term::cost and Term::curvature of a gap term on `cost`.
template <class Gap>
void SetGapCost(std::unique_ptr<Gap> cost, Term* term) {
  term->curvature = GapCurvature(cost.get());
  term->cost = std::move(cost);
}

template <class Kind, class Pair, class Data = NoPairData, class FrictionLag = NoFrictionLag>
class PairKind : public PairSet {
 public:
  explicit PairKind(const PairSetContext& context) : c_(context) {}

  void Clear() override { pairs_.Clear(); }
  size_t size() const override { return pairs_.size(); }
  bool ChangedSinceClear() const override { return pairs_.Changed(); }
  const std::vector<Pair>& pairs() const { return pairs_.pairs(); }

  // (Defined below the class, not inline: a kind's header declares the
  // instantiation extern and its .cc, where ForEachCandidate is, makes it.)
  bool Extend(const CandidateRegion& region) override;
  bool Missing(const double* x) const override;
  // The first combination within the margin, else the kind's FindCrossing.
  std::string FindPenetration(const double* x, double t) const override;
  void Near(const double* x, double t, double reach, double* min_distance,
            int* count) const override;
  void AddBarrierGradient(const double* x, double t, double scale,
                          Eigen::VectorXd* g) const override;
  void AddBarrierTerms(IncrementalPotential* potential) const override;
  void LagFriction(const double* x, double t) override;
  int AddFrictionTerms(const FrictionSettings& friction,
                       IncrementalPotential* potential) const override;

 protected:
  // The default per-combination barrier gradient: scale w B'(d) grad d.
  template <int N>
  void AddPairBarrierGradient(const Pair& pair, const PairDistance<N>& measured, double scale,
                              Eigen::VectorXd* g) const {
    const int dim = c_.dimension;
    const double factor =
        scale * kind().Weight(pair) * BarrierDerivative(measured.distance, c_.d_hat);
    for (int k = 0; k < N; ++k) {
      g->segment(dim * measured.nodes[k], dim) += factor * measured.gradient[k].head(dim);
    }
  }
  std::string FindCrossing(const double* x, double t) const {
    (void)x;
    (void)t;
    return "";
  }
  // The default friction terms, of 3D self-contact lags and of 3D faces' and
  // edges' lags against obstacles.
  int FrictionTerms(const std::vector<SelfFrictionLag>& lags, const FrictionSettings& friction,
                    IncrementalPotential* potential) const {
    return AddSelfFrictionTerms(lags, c_.step, c_.friction, friction, potential);
  }
  int FrictionTerms(const std::vector<PrimitiveObstacleFrictionLag>& lags,
                    const FrictionSettings& friction, IncrementalPotential* potential) const {
    return AddPrimitiveObstacleFrictionTerms(lags, c_.step, c_.friction, friction, potential);
  }
  // The lagged normal force kappa w (-B'(d)) (times `factor`, a mollifier).
  double NormalForce(const Pair& pair, double d, double factor = 1.0) const {
    return -*c_.kappa * kind().Weight(pair) * factor * BarrierDerivative(d, c_.d_hat);
  }
  // The candidates of the loops below, by default the kind's ForEachCandidate:
  // around x (any obstacle time) and, for Extend, over the region's motion
  // grown by d_hat + max_reach.
  template <class F>
  void ForEachCandidateAt(const double* x, double t, double grow, const F& f) const {
    (void)t;
    kind().ForEachCandidate(x, x, grow, f);
  }
  template <class F>
  void ForEachCandidateIn(const CandidateRegion& r, const F& f) const {
    kind().ForEachCandidate(r.start, r.end, c_.d_hat + r.max_reach, f);
  }

  PairSetContext c_;
  SortedPairs<Pair, Data> pairs_;

 private:
  const Kind& kind() const { return static_cast<const Kind&>(*this); }

  std::vector<FrictionLag> friction_;
};

template <class Kind, class Pair, class Data, class FrictionLag>
bool PairKind<Kind, Pair, Data, FrictionLag>::Extend(const CandidateRegion& region) {
  CandidateRegion r = region;
  if (r.end == nullptr) r.end = r.start;
  bool added = false;
  kind().ForEachCandidateIn(r, [&](const Pair& pair) {
    if (!kind().HasFreeNode(pair) || pairs_.Contains(pair)) return;
    Data data{};
    if (kind().Admits(r, pair, &data)) added |= pairs_.Insert(pair, data);
  });
  return added;
}

template <class Kind, class Pair, class Data, class FrictionLag>
bool PairKind<Kind, Pair, Data, FrictionLag>::Missing(const double* x) const {
  bool missing = false;
  kind().ForEachCandidateAt(x, *c_.time, c_.d_hat, [&](const Pair& pair) {
    if (missing || !kind().HasFreeNode(pair)) return;
    if (kind().Distance(x, *c_.time, pair) < c_.d_hat && !pairs_.Contains(pair)) missing = true;
  });
  return missing;
}

template <class Kind, class Pair, class Data, class FrictionLag>
std::string PairKind<Kind, Pair, Data, FrictionLag>::FindPenetration(const double* x,
                                                                     double t) const {
  std::string found;
  kind().ForEachCandidateAt(x, t, c_.margin, [&](const Pair& pair) {
    if (!found.empty()) return;
    const double d = kind().Distance(x, t, pair);
    if (d > c_.margin) return;
    std::ostringstream out;
    out << kind().Describe(pair) << " (distance " << d << ")";
    found = out.str();
  });
  return found.empty() ? kind().FindCrossing(x, t) : found;
}

template <class Kind, class Pair, class Data, class FrictionLag>
void PairKind<Kind, Pair, Data, FrictionLag>::Near(const double* x, double t, double reach,
                                                   double* min_distance, int* count) const {
  kind().ForEachCandidateAt(x, t, reach, [&](const Pair& pair) {
    const double d = kind().Distance(x, t, pair);
    if (d < reach) {
      *min_distance = std::min(*min_distance, d);
      ++*count;
    }
  });
}

template <class Kind, class Pair, class Data, class FrictionLag>
void PairKind<Kind, Pair, Data, FrictionLag>::AddBarrierGradient(const double* x, double t,
                                                                 double scale,
                                                                 Eigen::VectorXd* g) const {
  kind().ForEachCandidateAt(x, t, c_.d_hat, [&](const Pair& pair) {
    const auto measured = kind().Measure(x, t, pair);
    if (!(measured.distance > 0.0 && measured.distance < c_.d_hat)) return;
    kind().AddPairBarrierGradient(pair, measured, scale, g);
  });
}

template <class Kind, class Pair, class Data, class FrictionLag>
void PairKind<Kind, Pair, Data, FrictionLag>::AddBarrierTerms(
    IncrementalPotential* potential) const {
  for (size_t k = 0; k < pairs_.size(); ++k) {
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(c_.barrier);
    term.impulsive = true;
    kind().SetGap(k, &term);
    term.loss = std::make_unique<BarrierLoss>(c_.d_hat, kind().Weight(pairs_[k]), c_.kappa);
    potential->AddTerm(std::move(term));
  }
}

template <class Kind, class Pair, class Data, class FrictionLag>
void PairKind<Kind, Pair, Data, FrictionLag>::LagFriction(const double* x, double t) {
  if constexpr (!std::is_same_v<FrictionLag, NoFrictionLag>) {
    friction_.clear();
    for (const Pair& pair : pairs_.pairs()) {
      const auto measured = kind().Measure(x, t, pair);
      if (!(measured.distance > 0.0 && measured.distance < c_.d_hat)) continue;
      FrictionLag lag;
      if (kind().LagPairFriction(x, t, pair, measured, &lag)) friction_.push_back(lag);
    }
  }
}

template <class Kind, class Pair, class Data, class FrictionLag>
int PairKind<Kind, Pair, Data, FrictionLag>::AddFrictionTerms(
    const FrictionSettings& friction, IncrementalPotential* potential) const {
  if constexpr (std::is_same_v<FrictionLag, NoFrictionLag>) {
    (void)friction;
    (void)potential;
    return 0;
  } else {
    return kind().FrictionTerms(friction_, friction, potential);
  }
}

}  // namespace ipstep
