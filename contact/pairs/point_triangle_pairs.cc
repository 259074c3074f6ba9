#include "contact/pairs/point_triangle_pairs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <utility>

#include "contact/barrier.h"
#include "contact/friction.h"
#include "contact/self_gap_terms.h"
#include "geometry/point_triangle.h"
#include "geometry/self_ccd.h"
#include "geometry/triangle_intersection.h"

namespace ipstep {

namespace {

const std::array<int, 1> Single(int node) { return {node}; }

}  // namespace

PointTrianglePairs::PointTrianglePairs(const PairSetContext& context)
    : Base(context), geometry_(context.mesh) {
  active_ = context.dimension == 3 && !context.mesh->faces.empty();
}

PointTrianglePairs::Measured PointTrianglePairs::Measure(const double* x, double,
                                                         const Pair& pair) const {
  const auto& f = c_.mesh->faces[pair.face];
  const PointTriangleDistanceResult r =
      PointTriangleDistance(SelfContactMesh::Vertex(x, pair.node), SelfContactMesh::Vertex(x, f[0]),
                            SelfContactMesh::Vertex(x, f[1]), SelfContactMesh::Vertex(x, f[2]));
  Measured m;
  m.distance = r.distance;
  m.nodes = {pair.node, f[0], f[1], f[2]};
  m.gradient = {r.grad_p, r.grad_a, r.grad_b, r.grad_c};
  m.weights = r.weights;
  return m;
}

double PointTrianglePairs::Distance(const double* x, double t, const Pair& pair) const {
  return Measure(x, t, pair).distance;
}

bool PointTrianglePairs::HasFreeNode(const Pair& pair) const {
  const std::vector<bool>& free = *c_.node_free;
  const auto& f = c_.mesh->faces[pair.face];
  return free[geometry_.slot(pair.node)] || free[geometry_.slot(f[0])] ||
         free[geometry_.slot(f[1])] || free[geometry_.slot(f[2])];
}

template <class F>
void PointTrianglePairs::ForEachCandidate(const double* a, const double* b, double grow,
                                          const F& f) const {
  if (!active_) return;
  const CollisionMesh& mesh = *c_.mesh;
  // The faces' tree queried with each node, less the faces that contain it.
  auto query = [&](size_t i) { return Single(mesh.nodes[i]); };
  auto keep = [&](size_t i, int face, Pair* pair) {
    const int node = mesh.nodes[i];
    const auto& v = mesh.faces[face];
    *pair = Pair{node, face};
    return v[0] != node && v[1] != node && v[2] != node;
  };
  broad_phase_.ForEachCandidate(a, b, grow, geometry_.num_coordinates(), mesh.faces,
                                mesh.nodes.size(), query, keep, f);
}

bool PointTrianglePairs::Admits(const CandidateRegion& region, const Pair& pair,
                                NoPairData*) const {
  const double* a = region.start;
  const double* b = region.end;
  auto node_reach = [&](int node) {
    return region.reach != nullptr ? (*region.reach)[geometry_.slot(node)] : 0.0;
  };
  auto motion = [&](int node) {
    return (SelfContactMesh::Vertex(b, node) - SelfContactMesh::Vertex(a, node)).norm();
  };
  // Every point of the face moves (over the motion, then within the solve) by
  // at most its vertices' largest displacement.
  const auto& f = c_.mesh->faces[pair.face];
  const double face_reach =
      std::max({node_reach(f[0]) + motion(f[0]), node_reach(f[1]) + motion(f[1]),
                node_reach(f[2]) + motion(f[2])});
  const double limit = c_.d_hat + node_reach(pair.node) + motion(pair.node) + face_reach;
  return Distance(a, *c_.time, pair) < limit;
}

double PointTrianglePairs::TimeOfImpact(const double* a, const double* b, double t_a,
                                        double t_b) const {
  (void)t_a;
  (void)t_b;
  double first = kNoImpact;
  const double margin = c_.margin;
  ForEachCandidate(a, b, margin, [&](const Pair& pair) {
    if (first == 0.0) return;
    const auto& f = c_.mesh->faces[pair.face];
    auto v = [&](const double* x, int node) { return SelfContactMesh::Vertex(x, node); };
    const double s =
        PointTriangleTimeOfImpact(v(a, pair.node), v(a, f[0]), v(a, f[1]), v(a, f[2]),
                                  v(b, pair.node), v(b, f[0]), v(b, f[1]), v(b, f[2]), margin);
    first = std::min(first, s);
  });
  return std::min(first, kNoImpact);
}

std::string PointTrianglePairs::Describe(const Pair& pair) const {
  const auto& f = c_.mesh->faces[pair.face];
  std::ostringstream out;
  out << "node " << pair.node << " touches face (" << f[0] << ", " << f[1] << ", " << f[2] << ")";
  return out.str();
}

std::string PointTrianglePairs::FindCrossing(const double* x, double) const {
  if (!active_) return "";
  // Faces without a common node that intersect (exact predicates).
  const CollisionMesh& mesh = *c_.mesh;
  std::vector<std::pair<int, int>> face_pairs;
  broad_phase_.Overlaps(
      x, x, 0.0, mesh.faces, mesh.faces.size(), [&](size_t i) { return mesh.faces[i]; },
      [&](size_t i, const std::vector<int>* ids) {
        for (int j : *ids) {
          if (j > static_cast<int>(i)) face_pairs.emplace_back(static_cast<int>(i), j);
        }
      });
  for (const auto& [i, j] : face_pairs) {
    const auto& fi = mesh.faces[i];
    const auto& fj = mesh.faces[j];
    bool shared = false;
    for (int p : fi) shared |= p == fj[0] || p == fj[1] || p == fj[2];
    if (shared) continue;
    auto v = [&](int node) { return SelfContactMesh::Vertex(x, node); };
    if (TrianglesIntersect(v(fi[0]), v(fi[1]), v(fi[2]), v(fj[0]), v(fj[1]), v(fj[2]))) {
      std::ostringstream out;
      out << "faces (" << fi[0] << ", " << fi[1] << ", " << fi[2] << ") and (" << fj[0] << ", "
          << fj[1] << ", " << fj[2] << ") intersect";
      return out.str();
    }
  }
  return "";
}

void PointTrianglePairs::SetGap(size_t k, Term* term) const {
  const Pair& pair = pairs_[k];
  const auto& f = c_.mesh->faces[pair.face];
  term->nodes = {pair.node, f[0], f[1], f[2]};
  SetGapCost(std::make_unique<PointTriangleGap>(c_.d_hat, c_.margin), term);
}

bool PointTrianglePairs::LagPairFriction(const double*, double, const Pair& pair, const Measured& m,
                                         SelfFrictionLag* lag) const {
  lag->nodes = m.nodes;
  lag->alpha = {1.0, -m.weights[0], -m.weights[1], -m.weights[2]};
  lag->tangents = SelfTangentBasis(m.gradient[0]);  // grad_p: unit, from the face to the node
  lag->normal_force = NormalForce(pair, m.distance);
  return true;
}

// After ForEachCandidate, which the base's loops call.
template class PairKind<PointTrianglePairs, PointTrianglePair, NoPairData, SelfFrictionLag>;

}  // namespace ipstep
