#include "contact/pairs/point_triangle_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/self_gap_terms.h"
#include "core/scoped_timer.h"
#include "geometry/point_triangle.h"
#include "geometry/self_ccd.h"
#include "geometry/triangle_intersection.h"

namespace ipstep {

namespace {

const std::array<int, 1> Single(int node) { return {node}; }

}  // namespace

PointTrianglePairs::PointTrianglePairs(const PairSetContext& context)
    : context_(context), geometry_(context.mesh) {
  active_ = context.dimension == 3 && !context.mesh->faces.empty();
}

double PointTrianglePairs::Distance(const double* x, const Pair& pair, Eigen::Vector3d* grad,
                                    Eigen::Vector3d* weights) const {
  const auto& f = context_.mesh->faces[pair.face];
  const PointTriangleDistanceResult r =
      PointTriangleDistance(SelfContactMesh::Vertex(x, pair.node), SelfContactMesh::Vertex(x, f[0]),
                            SelfContactMesh::Vertex(x, f[1]), SelfContactMesh::Vertex(x, f[2]));
  if (grad != nullptr) {
    grad[0] = r.grad_p;
    grad[1] = r.grad_a;
    grad[2] = r.grad_b;
    grad[3] = r.grad_c;
  }
  if (weights != nullptr) *weights = r.weights;
  return r.distance;
}

bool PointTrianglePairs::PairHasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *context_.node_free;
  const auto& f = context_.mesh->faces[pair.face];
  return free[geometry_.slot(pair.node)] || free[geometry_.slot(f[0])] ||
         free[geometry_.slot(f[1])] || free[geometry_.slot(f[2])];
}

template <class F>
void PointTrianglePairs::ForEachCandidate(const double* a, const double* b, double grow,
                                          const F& f) const {
  if (!active_) return;
  const CollisionMesh& mesh = *context_.mesh;
  auto find = [&](std::vector<Pair>* candidates) {
    SelfContactMesh::BuildTree(mesh.faces, a, b, grow, &bvh_);
    for (int node : mesh.nodes) {
      Eigen::Vector3d lower, upper;
      SelfContactMesh::MotionBox(a, b, Single(node), 0.0, &lower, &upper);
      bvh_.Query(lower, upper, &ids_);
      std::sort(ids_.begin(), ids_.end());
      for (int face : ids_) {
        const auto& v = mesh.faces[face];
        if (v[0] == node || v[1] == node || v[2] == node) continue;
        candidates->push_back(Pair{node, face});
      }
    }
  };
  candidates_.ForEach(a, b, geometry_.num_coordinates(), grow, &broad_phase_seconds_, find, f);
}

bool PointTrianglePairs::Extend(const CandidateRegion& region) {
  if (!active_) return false;
  const double* a = region.start;
  const double* b = region.end != nullptr ? region.end : region.start;
  const std::vector<double>* reach = region.reach;
  auto node_reach = [&](int node) {
    return reach != nullptr ? (*reach)[geometry_.slot(node)] : 0.0;
  };
  auto motion = [&](int node) {
    return (SelfContactMesh::Vertex(b, node) - SelfContactMesh::Vertex(a, node)).norm();
  };
  bool added = false;
  ForEachCandidate(a, b, context_.d_hat + region.max_reach, [&](const Pair& pair) {
    if (!PairHasFreeNode(pair) || pairs_.Contains(pair)) return;
    // Every point of the face moves (over the motion, then within the
    // solve) by at most its vertices' largest displacement.
    const auto& f = context_.mesh->faces[pair.face];
    const double face_reach =
        std::max({node_reach(f[0]) + motion(f[0]), node_reach(f[1]) + motion(f[1]),
                  node_reach(f[2]) + motion(f[2])});
    const double limit = context_.d_hat + node_reach(pair.node) + motion(pair.node) + face_reach;
    if (Distance(a, pair) < limit) added |= pairs_.Insert(pair);
  });
  return added;
}

bool PointTrianglePairs::Missing(const double* x) const {
  bool missing = false;
  ForEachCandidate(x, x, context_.d_hat, [&](const Pair& pair) {
    if (missing || !PairHasFreeNode(pair)) return;
    if (Distance(x, pair) < context_.d_hat && !pairs_.Contains(pair)) missing = true;
  });
  return missing;
}

double PointTrianglePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                        double t_b) const {
  (void)t_a;
  (void)t_b;
  double first = kNoImpact;
  const double margin = context_.margin;
  ForEachCandidate(a, b, margin, [&](const Pair& pair) {
    if (first == 0.0) return;
    const auto& f = context_.mesh->faces[pair.face];
    auto v = [&](const double* x, int node) { return SelfContactMesh::Vertex(x, node); };
    const double s =
        PointTriangleTimeOfImpact(v(a, pair.node), v(a, f[0]), v(a, f[1]), v(a, f[2]),
                                  v(b, pair.node), v(b, f[0]), v(b, f[1]), v(b, f[2]), margin);
    first = std::min(first, s);
  });
  return std::min(first, kNoImpact);
}

std::string PointTrianglePairs::FindPenetration(const double* x, double t) const {
  (void)t;
  if (!active_) return "";
  std::ostringstream out;
  ForEachCandidate(x, x, context_.margin, [&](const Pair& pair) {
    if (!out.str().empty()) return;
    const double d = Distance(x, pair);
    if (d > context_.margin) return;
    const auto& f = context_.mesh->faces[pair.face];
    out << "node " << pair.node << " touches face (" << f[0] << ", " << f[1] << ", " << f[2]
        << ") (distance " << d << ")";
  });
  if (!out.str().empty()) return out.str();
  // Faces without a common node that intersect (exact predicates).
  const CollisionMesh& mesh = *context_.mesh;
  std::vector<std::pair<int, int>> face_pairs;
  {
    ScopedTimer timer(&broad_phase_seconds_);
    SelfContactMesh::BuildTree(mesh.faces, x, x, 0.0, &bvh_);
    for (size_t i = 0; i < mesh.faces.size(); ++i) {
      Eigen::Vector3d lower, upper;
      SelfContactMesh::MotionBox(x, x, mesh.faces[i], 0.0, &lower, &upper);
      bvh_.Query(lower, upper, &ids_);
      for (int j : ids_) {
        if (j > static_cast<int>(i)) face_pairs.emplace_back(static_cast<int>(i), j);
      }
    }
  }
  for (const auto& [i, j] : face_pairs) {
    const auto& fi = mesh.faces[i];
    const auto& fj = mesh.faces[j];
    bool shared = false;
    for (int p : fi) shared |= p == fj[0] || p == fj[1] || p == fj[2];
    if (shared) continue;
    auto v = [&](int node) { return SelfContactMesh::Vertex(x, node); };
    if (TrianglesIntersect(v(fi[0]), v(fi[1]), v(fi[2]), v(fj[0]), v(fj[1]), v(fj[2]))) {
      out << "faces (" << fi[0] << ", " << fi[1] << ", " << fi[2] << ") and (" << fj[0] << ", "
          << fj[1] << ", " << fj[2] << ") intersect";
      return out.str();
    }
  }
  return "";
}

void PointTrianglePairs::Near(const double* x, double t, double reach, double* min_distance,
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

void PointTrianglePairs::AddBarrierGradient(const double* x, double t, double scale,
                                            Eigen::VectorXd* g) const {
  (void)t;
  const double d_hat = context_.d_hat;
  ForEachCandidate(x, x, d_hat, [&](const Pair& pair) {
    Eigen::Vector3d grad[4];
    const double d = Distance(x, pair, grad);
    if (!(d > 0.0 && d < d_hat)) return;
    const double factor =
        scale * context_.mesh->weights[geometry_.slot(pair.node)] * BarrierDerivative(d, d_hat);
    const auto& f = context_.mesh->faces[pair.face];
    const int nodes[4] = {pair.node, f[0], f[1], f[2]};
    for (int k = 0; k < 4; ++k) g->segment<3>(3 * nodes[k]) += factor * grad[k];
  });
}

void PointTrianglePairs::AddBarrierTerms(IncrementalPotential* potential) const {
  for (const Pair& pair : pairs_.pairs()) {
    const auto& f = context_.mesh->faces[pair.face];
    Term term;
    term.kind = TermKind::kPotential;
    term.SetOwner(context_.barrier);
    term.impulsive = true;
    term.nodes = {pair.node, f[0], f[1], f[2]};
    auto cost = std::make_unique<PointTriangleGap>(context_.d_hat, context_.margin);
    const PointTriangleGap* gap = cost.get();
    term.curvature = [gap](const double* const* x, const double* c, double* curvature) {
      return gap->Curvature(x, c, curvature);
    };
    term.cost = std::move(cost);
    term.loss = std::make_unique<BarrierLoss>(
        context_.d_hat, context_.mesh->weights[geometry_.slot(pair.node)], context_.kappa);
    potential->AddTerm(std::move(term));
  }
}

void PointTrianglePairs::LagFriction(const double* x, double t) {
  (void)t;
  friction_.clear();
  const double d_hat = context_.d_hat;
  for (const Pair& pair : pairs_.pairs()) {
    Eigen::Vector3d grad[4], w;
    const double d = Distance(x, pair, grad, &w);
    if (!(d > 0.0 && d < d_hat)) continue;
    const auto& f = context_.mesh->faces[pair.face];
    SelfFrictionLag lag;
    lag.nodes = {pair.node, f[0], f[1], f[2]};
    lag.alpha = {1.0, -w[0], -w[1], -w[2]};
    lag.tangents = SelfTangentBasis(grad[0]);  // grad_p: unit, from the face to the node
    lag.normal_force = -*context_.kappa * context_.mesh->weights[geometry_.slot(pair.node)] *
                       BarrierDerivative(d, d_hat);
    friction_.push_back(lag);
  }
}

int PointTrianglePairs::AddFrictionTerms(const FrictionSettings& friction,
                                         IncrementalPotential* potential) const {
  return AddSelfFrictionTerms(friction_, context_.step, context_.friction, friction, potential);
}

}  // namespace ipstep
