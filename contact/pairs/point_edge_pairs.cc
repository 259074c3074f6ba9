#include "contact/pairs/point_edge_pairs.h"

#include <algorithm>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/contact_terms.h"
#include "contact/friction.h"
#include "geometry/point_edge.h"

namespace ipstep {

PointEdgePairs::PointEdgePairs(const PairSetContext& context, const double* initial)
    : Base(context),
      active_(context.dimension == 2 && !context.mesh->edges.empty()),
      hash_(2, 1.0) {
  if (!active_) return;
  double total = 0.0;
  for (const auto& e : c_.mesh->edges) {
    total += (ToPoint(initial + 2 * e[0], 2) - ToPoint(initial + 2 * e[1], 2)).norm();
  }
  hash_ = SpatialHash(2, std::max(total / c_.mesh->edges.size(), 2.0 * c_.d_hat));
}

bool PointEdgePairs::HasFreeNode(const Pair& pair) const {
  const auto& e = c_.mesh->edges[pair.edge];
  auto free = [&](int node) { return (*c_.node_free)[NodeSlot(*c_.mesh, node)]; };
  return (*c_.node_free)[pair.slot] || free(e[0]) || free(e[1]);
}

double PointEdgePairs::Distance(const double* x, double, const Pair& p) const {
  const auto& e = c_.mesh->edges[p.edge];
  return PointEdgeDistance(Node(x, c_.mesh->nodes[p.slot]), Node(x, e[0]), Node(x, e[1])).distance;
}

PointEdgePairs::Measured PointEdgePairs::Measure(const double* x, double, const Pair& p) const {
  const auto& e = c_.mesh->edges[p.edge];
  const int node = c_.mesh->nodes[p.slot];
  const PointEdgeDistanceResult r = PointEdgeDistance(Node(x, node), Node(x, e[0]), Node(x, e[1]));
  Measured m;
  m.distance = r.distance;
  m.nodes = {node, e[0], e[1]};
  m.gradient = {ToPoint(r.grad_p.data(), 2), ToPoint(r.grad_a.data(), 2),
                ToPoint(r.grad_b.data(), 2)};
  m.alpha = r.alpha;
  return m;
}

void PointEdgePairs::Candidates(const double* a, const double* b, double grow,
                                std::vector<Pair>* pairs) const {
  pairs->clear();
  if (!active_) return;
  const Eigen::Vector3d g = Eigen::Vector3d::Constant(grow);
  hash_.Clear();
  const auto& edges = c_.mesh->edges;
  for (size_t e = 0; e < edges.size(); ++e) {
    const int i = edges[e][0], j = edges[e][1];
    const Eigen::Vector3d ai = ToPoint(a + 2 * i, 2), bi = ToPoint(b + 2 * i, 2);
    const Eigen::Vector3d aj = ToPoint(a + 2 * j, 2), bj = ToPoint(b + 2 * j, 2);
    hash_.Insert(static_cast<int>(e), ai.cwiseMin(bi).cwiseMin(aj.cwiseMin(bj)) - g,
                 ai.cwiseMax(bi).cwiseMax(aj.cwiseMax(bj)) + g);
  }
  for (size_t s = 0; s < c_.mesh->nodes.size(); ++s) {
    const int node = c_.mesh->nodes[s];
    const Eigen::Vector3d pa = ToPoint(a + 2 * node, 2), pb = ToPoint(b + 2 * node, 2);
    hash_.Query(pa.cwiseMin(pb), pa.cwiseMax(pb), &scratch_ids_);
    for (int e : scratch_ids_) {
      if (edges[e][0] == node || edges[e][1] == node) continue;
      pairs->push_back(Pair{static_cast<int>(s), e});
    }
  }
}

template <class F>
void PointEdgePairs::ForEachCandidate(const double* a, const double* b, double grow,
                                      const F& f) const {
  std::vector<Pair> candidates;
  Candidates(a, b, grow, &candidates);
  for (const Pair& pair : candidates) f(pair);
}

double PointEdgePairs::TimeOfImpact(const double* a, const double* b, double, double) const {
  std::vector<Pair> candidates;
  Candidates(a, b, c_.margin, &candidates);
  double first = kNoImpact;
  bool end_too_close = false;
  for (const Pair& p : candidates) {
    const auto& e = c_.mesh->edges[p.edge];
    const int node = c_.mesh->nodes[p.slot];
    first = std::min(first, PointEdgeTimeOfImpact(Node(a, node), Node(b, node), Node(a, e[0]),
                                                  Node(b, e[0]), Node(a, e[1]), Node(b, e[1])));
    end_too_close |= !(Distance(b, 0.0, p) > c_.margin);
  }
  // The impact test stops at contact; the margin is checked at the end.
  if (first > 1.0 && end_too_close) first = 1.0;
  return first;
}

std::string PointEdgePairs::Describe(const Pair& pair) const {
  const auto& e = c_.mesh->edges[pair.edge];
  std::ostringstream out;
  out << "boundary node " << c_.mesh->nodes[pair.slot] << " touches boundary edge (" << e[0] << ", "
      << e[1] << ")";
  return out.str();
}

std::string PointEdgePairs::FindCrossing(const double* x, double) const {
  if (!active_) return "";
  const auto& edges = c_.mesh->edges;
  for (size_t e = 0; e < edges.size(); ++e) {
    const auto& ea = edges[e];
    const Eigen::Vector2d a0 = Node(x, ea[0]), a1 = Node(x, ea[1]);
    const Eigen::Vector2d lo = a0.cwiseMin(a1), hi = a0.cwiseMax(a1);
    for (size_t f = e + 1; f < edges.size(); ++f) {
      const auto& eb = edges[f];
      if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
      const Eigen::Vector2d b0 = Node(x, eb[0]), b1 = Node(x, eb[1]);
      if ((b0.cwiseMin(b1).array() > hi.array()).any() ||
          (lo.array() > b0.cwiseMax(b1).array()).any()) {
        continue;
      }
      if (SegmentsIntersect(a0, a1, b0, b1)) {
        std::ostringstream out;
        out << "boundary edges (" << ea[0] << ", " << ea[1] << ") and (" << eb[0] << ", " << eb[1]
            << ") intersect";
        return out.str();
      }
    }
  }
  return "";
}

void PointEdgePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& e = c_.mesh->edges[pair.edge];
  term->nodes = {c_.mesh->nodes[pair.slot], e[0], e[1]};
  SetGapCost(std::make_unique<PointEdgeGap>(c_.d_hat, c_.margin), term);
}

bool PointEdgePairs::LagPairFriction(const double*, double, const Pair& pair, const Measured& m,
                                     PointEdgeFrictionLag* lag) const {
  const Eigen::Vector2d tangent(-m.gradient[0][1], m.gradient[0][0]);
  *lag = PointEdgeFrictionLag{m.nodes[0], m.nodes[1], m.nodes[2],
                              tangent,    m.alpha,    NormalForce(pair, m.distance)};
  return true;
}

int PointEdgePairs::FrictionTerms(const std::vector<PointEdgeFrictionLag>& lags,
                                  const FrictionSettings& friction,
                                  IncrementalPotential* potential) const {
  const double eps_v = friction.epsilon_v;
  const double c = kFrictionSpeedScale * eps_v;
  const double mu = friction.ForSelf();
  if (!(mu > 0.0)) return 0;
  for (const PointEdgeFrictionLag& f : lags) {
    for (int side : {1, -1}) {
      Term term;
      term.kind = TermKind::kDissipation;
      term.SetOwner(c_.friction);
      term.impulsive = true;
      term.nodes = {f.p, f.a, f.b};
      term.cost =
          std::make_unique<EdgeFriction>(c_.step, f.p, f.a, f.b, f.tangent, f.alpha, side, c);
      term.loss = std::make_unique<OneSidedFrictionLoss>(mu * f.normal_force, c, eps_v);
      potential->AddTerm(std::move(term));
    }
  }
  return static_cast<int>(lags.size());
}

// After ForEachCandidate, which the base's loops call.
template class PairKind<PointEdgePairs, PointEdgePair, NoPairData, PointEdgeFrictionLag>;

}  // namespace ipstep
