#include "contact/pairs/edge_edge_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/self_gap_terms.h"
#include "core/scoped_timer.h"
#include "geometry/edge_edge_mollifier.h"
#include "geometry/segment_segment.h"
#include "geometry/self_ccd.h"

namespace ipstep {

EdgeEdgePairs::EdgeEdgePairs(const PairSetContext& context, const double* rest)
    : context_(context), geometry_(context.mesh) {
  active_ = context.dimension == 3 && !context.mesh->faces.empty() && !context.mesh->edges.empty();
  if (rest != nullptr) SetRestPositions(rest);
}

void EdgeEdgePairs::SetRestPositions(const double* x) {
  const auto& edges = context_.mesh->edges;
  rest_length2_.resize(edges.size());
  for (size_t e = 0; e < edges.size(); ++e) {
    rest_length2_[e] =
        (SelfContactMesh::Vertex(x, edges[e][1]) - SelfContactMesh::Vertex(x, edges[e][0]))
            .squaredNorm();
  }
}

double EdgeEdgePairs::MollifierThreshold(const Pair& pair) const {
  if (rest_length2_.empty()) return 0.0;
  return ipstep::MollifierThreshold(rest_length2_[pair.e], rest_length2_[pair.f]);
}

double EdgeEdgePairs::Distance(const double* x, const Pair& pair) const {
  const auto& a = context_.mesh->edges[pair.e];
  const auto& b = context_.mesh->edges[pair.f];
  return SegmentSegmentDistance(SelfContactMesh::Vertex(x, a[0]), SelfContactMesh::Vertex(x, a[1]),
                                SelfContactMesh::Vertex(x, b[0]), SelfContactMesh::Vertex(x, b[1]))
      .distance;
}

bool EdgeEdgePairs::PairHasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *context_.node_free;
  const auto& a = context_.mesh->edges[pair.e];
  const auto& b = context_.mesh->edges[pair.f];
  return free[geometry_.slot(a[0])] || free[geometry_.slot(a[1])] || free[geometry_.slot(b[0])] ||
         free[geometry_.slot(b[1])];
}

template <class F>
void EdgeEdgePairs::ForEachCandidate(const double* a, const double* b, double grow,
                                     const F& f) const {
  if (!active_) return;
  const auto& edges = context_.mesh->edges;
  auto find = [&](std::vector<Pair>* candidates) {
    SelfContactMesh::BuildTree(edges, a, b, grow, &bvh_);
    for (size_t e = 0; e < edges.size(); ++e) {
      Eigen::Vector3d lower, upper;
      SelfContactMesh::MotionBox(a, b, edges[e], 0.0, &lower, &upper);
      bvh_.Query(lower, upper, &ids_);
      std::sort(ids_.begin(), ids_.end());
      for (int other : ids_) {
        if (other <= static_cast<int>(e)) continue;
        const auto& u = edges[e];
        const auto& v = edges[other];
        if (u[0] == v[0] || u[0] == v[1] || u[1] == v[0] || u[1] == v[1]) continue;
        candidates->push_back(Pair{static_cast<int>(e), other});
      }
    }
  };
  candidates_.ForEach(a, b, geometry_.num_coordinates(), grow, &broad_phase_seconds_, find, f);
}

bool EdgeEdgePairs::Extend(const CandidateRegion& region) {
  if (!active_) return false;
  const double* a = region.start;
  const double* b = region.end != nullptr ? region.end : region.start;
  if (rest_length2_.empty()) SetRestPositions(a);
  const std::vector<double>* reach = region.reach;
  auto node_reach = [&](int node) {
    const double r = reach != nullptr ? (*reach)[geometry_.slot(node)] : 0.0;
    return r + (SelfContactMesh::Vertex(b, node) - SelfContactMesh::Vertex(a, node)).norm();
  };
  const auto& edges = context_.mesh->edges;
  bool added = false;
  ForEachCandidate(a, b, context_.d_hat + region.max_reach, [&](const Pair& pair) {
    if (!PairHasFreeNode(pair) || pairs_.Contains(pair)) return;
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    const double limit = context_.d_hat + std::max(node_reach(u[0]), node_reach(u[1])) +
                         std::max(node_reach(v[0]), node_reach(v[1]));
    if (Distance(a, pair) < limit) added |= pairs_.Insert(pair);
  });
  return added;
}

bool EdgeEdgePairs::Missing(const double* x) const {
  bool missing = false;
  ForEachCandidate(x, x, context_.d_hat, [&](const Pair& pair) {
    if (missing || !PairHasFreeNode(pair)) return;
    if (Distance(x, pair) < context_.d_hat && !pairs_.Contains(pair)) missing = true;
  });
  return missing;
}

double EdgeEdgePairs::TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const {
  (void)t_a;
  (void)t_b;
  double first = kNoImpact;
  const double margin = context_.margin;
  const auto& edges = context_.mesh->edges;
  ForEachCandidate(a, b, margin, [&](const Pair& pair) {
    if (first == 0.0) return;
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    auto p = [&](const double* x, int node) { return SelfContactMesh::Vertex(x, node); };
    first = std::min(
        first, EdgeEdgeTimeOfImpact(p(a, u[0]), p(a, u[1]), p(a, v[0]), p(a, v[1]), p(b, u[0]),
                                    p(b, u[1]), p(b, v[0]), p(b, v[1]), margin));
  });
  return std::min(first, kNoImpact);
}

std::string EdgeEdgePairs::FindPenetration(const double* x, double t) const {
  (void)t;
  std::ostringstream out;
  const auto& edges = context_.mesh->edges;
  ForEachCandidate(x, x, context_.margin, [&](const Pair& pair) {
    if (!out.str().empty()) return;
    const double d = Distance(x, pair);
    if (d > context_.margin) return;
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    out << "edge (" << u[0] << ", " << u[1] << ") touches edge (" << v[0] << ", " << v[1]
        << ") (distance " << d << ")";
  });
  return out.str();
}

void EdgeEdgePairs::Near(const double* x, double t, double reach, double* min_distance,
                         int* count) const {
  (void)t;
  ForEachCandidate(x, x, reach, [&](const Pair& pair) {
    const double d = Distance(x, pair);
    if (d < reach) {
      *min_distance = std::min(*min_distance, d);
      ++*count;
    }
  });
}

void EdgeEdgePairs::AddBarrierGradient(const double* x, double t, double scale,
                                       Eigen::VectorXd* g) const {
  (void)t;
  const double d_hat = context_.d_hat;
  const auto& edges = context_.mesh->edges;
  ForEachCandidate(x, x, d_hat, [&](const Pair& pair) {
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    const int nodes[4] = {u[0], u[1], v[0], v[1]};
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) p[k] = SelfContactMesh::Vertex(x, nodes[k]);
    const SegmentSegmentDistanceResult r = SegmentSegmentDistance(p[0], p[1], p[2], p[3]);
    const double d = r.distance;
    if (!(d > 0.0 && d < d_hat)) return;
    // grad (m B) = B grad m + m B' grad d (the mollified barrier of the terms).
    const EdgeEdgeMollifier m =
        EdgeEdgeMollify(p[0], p[1], p[2], p[3], MollifierThreshold(pair), true, false);
    Eigen::Matrix<double, 12, 1> grad;
    grad << r.grad_a0, r.grad_a1, r.grad_b0, r.grad_b1;
    grad = Barrier(d, d_hat) * m.gradient + m.value * BarrierDerivative(d, d_hat) * grad;
    const double w = scale * context_.mesh->edge_weights[pair.e];
    for (int k = 0; k < 4; ++k) g->segment<3>(3 * nodes[k]) += w * grad.segment<3>(3 * k);
  });
}

void EdgeEdgePairs::AddBarrierTerms(IncrementalPotential* potential) const {
  const auto& edges = context_.mesh->edges;
  for (const Pair& pair : pairs_.pairs()) {
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(context_.barrier);
    term.impulsive = true;
    term.nodes = {u[0], u[1], v[0], v[1]};
    auto cost =
        std::make_unique<EdgeEdgeGap>(context_.d_hat, context_.margin, MollifierThreshold(pair));
    const EdgeEdgeGap* gap = cost.get();
    term.curvature = [gap](const double* const* x, const double* c, double* curvature) {
      return gap->Curvature(x, c, curvature);
    };
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(context_.d_hat, context_.mesh->edge_weights[pair.e],
                                              context_.kappa);
    potential->AddTerm(std::move(term));
  }
}

void EdgeEdgePairs::LagFriction(const double* x, double t) {
  (void)t;
  friction_.clear();
  const double d_hat = context_.d_hat;
  const auto& edges = context_.mesh->edges;
  for (const Pair& pair : pairs_.pairs()) {
    const auto& u = edges[pair.e];
    const auto& v = edges[pair.f];
    SelfFrictionLag lag;
    lag.nodes = {u[0], u[1], v[0], v[1]};
    Eigen::Vector3d p[4];
    for (int k = 0; k < 4; ++k) p[k] = SelfContactMesh::Vertex(x, lag.nodes[k]);
    const SegmentSegmentDistanceResult r = SegmentSegmentDistance(p[0], p[1], p[2], p[3]);
    if (!(r.distance > 0.0 && r.distance < d_hat)) continue;
    const double m =
        EdgeEdgeMollify(p[0], p[1], p[2], p[3], MollifierThreshold(pair), false, false).value;
    lag.alpha = {1.0 - r.s, r.s, -(1.0 - r.t), -r.t};
    const Eigen::Vector3d n =
        (p[0] + r.s * (p[1] - p[0]) - p[2] - r.t * (p[3] - p[2])) / r.distance;
    lag.tangents = SelfTangentBasis(n);
    lag.normal_force = -*context_.kappa * context_.mesh->edge_weights[pair.e] * m *
                       BarrierDerivative(r.distance, d_hat);
    if (lag.normal_force > 0.0) friction_.push_back(lag);
  }
}

int EdgeEdgePairs::AddFrictionTerms(const FrictionSettings& friction,
                                    IncrementalPotential* potential) const {
  return AddSelfFrictionTerms(friction_, context_.step, context_.friction, friction, potential);
}

}  // namespace ipstep
