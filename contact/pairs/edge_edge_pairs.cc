#include "contact/pairs/edge_edge_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/self_gap_terms.h"
#include "geometry/edge_edge_mollifier.h"
#include "geometry/segment_segment.h"
#include "geometry/self_ccd.h"

namespace ipstep {

EdgeEdgePairs::EdgeEdgePairs(const PairSetContext& context, const double* rest)
    : Base(context), geometry_(context.mesh) {
  active_ = context.dimension == 3 && !context.mesh->faces.empty() && !context.mesh->edges.empty();
  if (rest != nullptr) SetRestPositions(rest);
}

void EdgeEdgePairs::SetRestPositions(const double* x) {
  const auto& edges = c_.mesh->edges;
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
  const auto& a = c_.mesh->edges[pair.e];
  const auto& b = c_.mesh->edges[pair.f];
  return SegmentSegmentDistance(SelfContactMesh::Vertex(x, a[0]), SelfContactMesh::Vertex(x, a[1]),
                                SelfContactMesh::Vertex(x, b[0]), SelfContactMesh::Vertex(x, b[1]))
      .distance;
}

EdgeEdgePairs::Measured EdgeEdgePairs::Measure(const double* x, double, const Pair& pair) const {
  const auto& u = c_.mesh->edges[pair.e];
  const auto& v = c_.mesh->edges[pair.f];
  Measured m;
  m.nodes = {u[0], u[1], v[0], v[1]};
  for (int k = 0; k < 4; ++k) m.points[k] = SelfContactMesh::Vertex(x, m.nodes[k]);
  const SegmentSegmentDistanceResult r =
      SegmentSegmentDistance(m.points[0], m.points[1], m.points[2], m.points[3]);
  m.distance = r.distance;
  m.gradient = {r.grad_a0, r.grad_a1, r.grad_b0, r.grad_b1};
  m.s = r.s;
  m.t = r.t;
  return m;
}

bool EdgeEdgePairs::HasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *c_.node_free;
  const auto& a = c_.mesh->edges[pair.e];
  const auto& b = c_.mesh->edges[pair.f];
  return free[geometry_.slot(a[0])] || free[geometry_.slot(a[1])] || free[geometry_.slot(b[0])] ||
         free[geometry_.slot(b[1])];
}

template <class F>
void EdgeEdgePairs::ForEachCandidate(const double* a, const double* b, double grow,
                                     const F& f) const {
  if (!active_) return;
  const auto& edges = c_.mesh->edges;
  // The edges' tree queried with each edge e, keeping the later edges
  // without a common node.
  auto query = [&](size_t e) { return edges[e]; };
  auto keep = [&](size_t e, int other, Pair* pair) {
    const auto& u = edges[e];
    const auto& v = edges[other];
    *pair = Pair{static_cast<int>(e), other};
    return other > static_cast<int>(e) && u[0] != v[0] && u[0] != v[1] && u[1] != v[0] &&
           u[1] != v[1];
  };
  broad_phase_.ForEachCandidate(a, b, grow, geometry_.num_coordinates(), edges, edges.size(), query,
                                keep, f);
}

bool EdgeEdgePairs::Extend(const CandidateRegion& region) {
  if (!active_) return false;
  if (rest_length2_.empty()) SetRestPositions(region.start);
  return Base::Extend(region);
}

bool EdgeEdgePairs::Admits(const CandidateRegion& region, const Pair& pair, NoPairData*) const {
  const double* a = region.start;
  const double* b = region.end;
  auto node_reach = [&](int node) {
    const double r = region.reach != nullptr ? (*region.reach)[geometry_.slot(node)] : 0.0;
    return r + (SelfContactMesh::Vertex(b, node) - SelfContactMesh::Vertex(a, node)).norm();
  };
  const auto& u = c_.mesh->edges[pair.e];
  const auto& v = c_.mesh->edges[pair.f];
  const double limit = c_.d_hat + std::max(node_reach(u[0]), node_reach(u[1])) +
                       std::max(node_reach(v[0]), node_reach(v[1]));
  return Distance(a, pair) < limit;
}

double EdgeEdgePairs::TimeOfImpact(const double* a, const double* b, double t_a, double t_b) const {
  (void)t_a;
  (void)t_b;
  double first = kNoImpact;
  const double margin = c_.margin;
  const auto& edges = c_.mesh->edges;
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

std::string EdgeEdgePairs::Describe(const Pair& pair) const {
  const auto& u = c_.mesh->edges[pair.e];
  const auto& v = c_.mesh->edges[pair.f];
  std::ostringstream out;
  out << "edge (" << u[0] << ", " << u[1] << ") touches edge (" << v[0] << ", " << v[1] << ")";
  return out.str();
}

void EdgeEdgePairs::AddPairBarrierGradient(const Pair& pair, const Measured& m, double scale,
                                           Eigen::VectorXd* g) const {
  const double d = m.distance, d_hat = c_.d_hat;
  const auto& p = m.points;
  const EdgeEdgeMollifier mollifier =
      EdgeEdgeMollify(p[0], p[1], p[2], p[3], MollifierThreshold(pair), true, false);
  Eigen::Matrix<double, 12, 1> grad;
  grad << m.gradient[0], m.gradient[1], m.gradient[2], m.gradient[3];
  grad =
      Barrier(d, d_hat) * mollifier.gradient + mollifier.value * BarrierDerivative(d, d_hat) * grad;
  const double w = scale * Weight(pair);
  for (int k = 0; k < 4; ++k) g->segment<3>(3 * m.nodes[k]) += w * grad.segment<3>(3 * k);
}

void EdgeEdgePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& u = c_.mesh->edges[pair.e];
  const auto& v = c_.mesh->edges[pair.f];
  term->nodes = {u[0], u[1], v[0], v[1]};
  SetGapCost(std::make_unique<EdgeEdgeGap>(c_.d_hat, c_.margin, MollifierThreshold(pair)), term);
}

bool EdgeEdgePairs::LagPairFriction(const double*, double, const Pair& pair, const Measured& m,
                                    SelfFrictionLag* lag) const {
  const auto& p = m.points;
  const double mollifier =
      EdgeEdgeMollify(p[0], p[1], p[2], p[3], MollifierThreshold(pair), false, false).value;
  lag->nodes = m.nodes;
  lag->alpha = {1.0 - m.s, m.s, -(1.0 - m.t), -m.t};
  const Eigen::Vector3d n = (p[0] + m.s * (p[1] - p[0]) - p[2] - m.t * (p[3] - p[2])) / m.distance;
  lag->tangents = SelfTangentBasis(n);
  lag->normal_force = NormalForce(pair, m.distance, mollifier);
  return lag->normal_force > 0.0;
}

// After ForEachCandidate, which the base's loops call.
template class PairKind<EdgeEdgePairs, EdgeEdgePair, NoPairData, SelfFrictionLag>;

}  // namespace ipstep
