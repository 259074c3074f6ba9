// Broad phase of 3D self-contact on an n x n cloth folded on itself
// (tests/support/cloth_meshes.h): candidate pairs and build + query time of the BVH
// (geometry/bvh.h) and of the spatial hash (geometry/spatial_hash.h, cell size
// the mean edge length, as the 2D self-contact uses), for point-triangle
// (faces in the structure, nodes as queries) and edge-edge (edges both). The
// boxes are grown by d_hat. Not a test: timings are printed, nothing checked
// beyond both structures finding the same close pairs. Times include the
// exact distance of every candidate (the narrow phase a pair kind runs next),
// as the hash returns a superset (boxes sharing a cell).
//   broad_phase_bench [n=100] [repeats=10] [gap / d_hat = 0.5]
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "contact/pairs/self_contact_mesh.h"
#include "geometry/bvh.h"
#include "geometry/point_triangle.h"
#include "geometry/segment_segment.h"
#include "geometry/spatial_hash.h"
#include "tests/support/cloth_meshes.h"

namespace {

using ipstep::Bvh;
using ipstep::CollisionMesh;
using ipstep::SelfContactMesh;
using ipstep::SpatialHash;
using Clock = std::chrono::steady_clock;

double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

struct Result {
  long point_triangle = 0, edge_edge = 0;  // candidates of the broad phase
  long pt_close = 0, ee_close = 0;         // of which within d_hat (exact distance)
  double pt_ms = 0.0, ee_ms = 0.0;
};

template <size_t N>
void Boxes(const std::vector<std::array<int, N>>& primitives, const double* x, double grow,
           std::vector<Eigen::Vector3d>* lower, std::vector<Eigen::Vector3d>* upper) {
  lower->resize(primitives.size());
  upper->resize(primitives.size());
  for (size_t i = 0; i < primitives.size(); ++i) {
    SelfContactMesh::MotionBox(x, x, primitives[i], grow, &(*lower)[i], &(*upper)[i]);
  }
}

bool Incident(const std::array<int, 3>& f, int node) {
  return f[0] == node || f[1] == node || f[2] == node;
}
bool Incident(const std::array<int, 2>& e, const std::array<int, 2>& f) {
  return e[0] == f[0] || e[0] == f[1] || e[1] == f[0] || e[1] == f[1];
}

// Counts candidate pairs with a structure exposing Query(lower, upper, ids).
template <class Build, class Query>
Result Run(const CollisionMesh& mesh, const double* x, double d_hat, const Build& build,
           const Query& query) {
  Result r;
  std::vector<Eigen::Vector3d> lower, upper;
  std::vector<int> ids;
  auto t0 = Clock::now();
  Boxes(mesh.faces, x, d_hat, &lower, &upper);
  build(lower, upper);
  for (int node : mesh.nodes) {
    const Eigen::Vector3d p = SelfContactMesh::Vertex(x, node);
    query(p, p, &ids);
    for (int f : ids) {
      const auto& v = mesh.faces[f];
      if (Incident(v, node)) continue;
      ++r.point_triangle;
      r.pt_close += ipstep::PointTriangleDistance(p, SelfContactMesh::Vertex(x, v[0]),
                                                  SelfContactMesh::Vertex(x, v[1]),
                                                  SelfContactMesh::Vertex(x, v[2]))
                        .distance < d_hat;
    }
  }
  auto t1 = Clock::now();
  Boxes(mesh.edges, x, d_hat, &lower, &upper);
  build(lower, upper);
  std::vector<Eigen::Vector3d> raw_lower, raw_upper;
  Boxes(mesh.edges, x, 0.0, &raw_lower, &raw_upper);
  for (size_t e = 0; e < mesh.edges.size(); ++e) {
    query(raw_lower[e], raw_upper[e], &ids);
    for (int f : ids) {
      const auto& u = mesh.edges[e];
      const auto& v = mesh.edges[f];
      if (f <= static_cast<int>(e) || Incident(u, v)) continue;
      ++r.edge_edge;
      r.ee_close += ipstep::SegmentSegmentDistance(
                        SelfContactMesh::Vertex(x, u[0]), SelfContactMesh::Vertex(x, u[1]),
                        SelfContactMesh::Vertex(x, v[0]), SelfContactMesh::Vertex(x, v[1]))
                        .distance < d_hat;
    }
  }
  auto t2 = Clock::now();
  r.pt_ms = Ms(t0, t1);
  r.ee_ms = Ms(t1, t2);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 100;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 10;
  const double a = 0.01, d_hat = 1e-3;
  const double gap = (argc > 3 ? std::atof(argv[3]) : 0.5) * d_hat;
  CollisionMesh mesh;
  const std::vector<double> x = ipstep::testing::FoldedCloth(n, a, gap, &mesh);
  std::printf("%d x %d folded cloth: %zu nodes, %zu faces, %zu edges, d_hat %g, gap %g\n", n, n,
              mesh.nodes.size(), mesh.faces.size(), mesh.edges.size(), d_hat, gap);
  Bvh bvh;
  SpatialHash hash(3, a);
  auto bvh_build = [&](const std::vector<Eigen::Vector3d>& lo,
                       const std::vector<Eigen::Vector3d>& hi) { bvh.Build(lo, hi); };
  auto bvh_query = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                       std::vector<int>* ids) { bvh.Query(lo, hi, ids); };
  auto hash_build = [&](const std::vector<Eigen::Vector3d>& lo,
                        const std::vector<Eigen::Vector3d>& hi) {
    hash.Clear();
    for (size_t i = 0; i < lo.size(); ++i) hash.Insert(static_cast<int>(i), lo[i], hi[i]);
  };
  auto hash_query = [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                        std::vector<int>* ids) { hash.Query(lo, hi, ids); };
  std::vector<Result> bvh_runs, hash_runs;
  for (int k = 0; k < repeats; ++k) {
    bvh_runs.push_back(Run(mesh, x.data(), d_hat, bvh_build, bvh_query));
    hash_runs.push_back(Run(mesh, x.data(), d_hat, hash_build, hash_query));
  }
  auto report = [](const char* name, std::vector<Result> runs) {
    auto median = [&](double Result::*field) {
      std::sort(runs.begin(), runs.end(),
                [&](const Result& p, const Result& q) { return p.*field < q.*field; });
      return runs[runs.size() / 2].*field;
    };
    const double pt = median(&Result::pt_ms), ee = median(&Result::ee_ms);
    std::printf(
        "%-13s point-triangle: %7ld candidates, %6ld close, %7.2f ms | edge-edge: %7ld "
        "candidates, %6ld close, %7.2f ms\n",
        name, runs[0].point_triangle, runs[0].pt_close, pt, runs[0].edge_edge, runs[0].ee_close,
        ee);
  };
  report("bvh", bvh_runs);
  report("spatial hash", hash_runs);
  return 0;
}
