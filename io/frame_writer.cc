#include "io/frame_writer.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "contact/contact_filter.h"
#include "core/input_error.h"
#include "io/obstacle_mesh.h"
#include "io/surface_triangles.h"
#include "io/vtk_unstructured_grid.h"
#include "problems/solid.h"

namespace ipstep {
namespace {

Eigen::Vector3d NodePosition(const Eigen::VectorXd& x, int dimension, int node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int k = 0; k < dimension; ++k) p[k] = x[dimension * node + k];
  return p;
}

// The triangles drawn: a 2D solid's elements, otherwise the declared surface
// (a 3D solid's boundary, a 3D cloth's faces) or the triangles filling the
// spring network (io/surface_triangles.h).
std::vector<std::array<int, 3>> PictureTriangles(const Scene& scene) {
  if (scene.solid && scene.dimension == 2) {
    std::vector<std::array<int, 3>> triangles;
    for (const std::array<int, 4>& e : scene.solid->mesh.elements) {
      triangles.push_back({e[0], e[1], e[2]});
    }
    return triangles;
  }
  return SurfaceTriangles(scene);
}

std::string Numbered(const char* stem, int frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%05d.vtu", stem, frame);
  return name;
}

}  // namespace

FrameWriter::FrameWriter(const std::string& directory, const Simulation& sim,
                         const std::string& output)
    : directory_(directory), output_(output), sim_(sim) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error || !std::filesystem::is_directory(directory)) {
    throw InputError("output", output,
                     "cannot create directory '" + directory +
                         "': " + (error ? error.message() : std::string("not a directory")));
  }
  series_ =
      std::make_unique<PvdSeries>((std::filesystem::path(directory) / "run.pvd").string(), output);
  const Scene& scene = sim.scene();
  triangles_ = PictureTriangles(scene);
  std::vector<bool> has_spring(scene.num_nodes(), scene.solid != nullptr);
  for (const Spring& s : scene.springs) has_spring[s.i] = has_spring[s.j] = true;
  for (int i = 0; i < scene.num_nodes(); ++i) {
    if (!has_spring[i]) particles_.push_back(i);
  }
  for (const auto& filter : sim.potential().step_filters()) {
    if (const auto* contact = dynamic_cast<const ContactFilter*>(filter.get())) {
      has_contact_ = true;
      for (const ObstaclePtr& o : contact->obstacles()) {
        obstacles_.push_back(o);
        obstacles_move_ = obstacles_move_ || o->is_moving();
      }
    }
  }
  const State& s = sim.state();
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  for (int i = 0; i < s.num_nodes(); ++i) {
    const Eigen::Vector3d p = NodePosition(s.x, s.dimension, i);
    lo = i == 0 ? p : lo.cwiseMin(p);
    hi = i == 0 ? p : hi.cwiseMax(p);
  }
  centre_ = 0.5 * (lo + hi);
  extent_ = std::max(1.0, 1.5 * (hi - lo).norm());
}

void FrameWriter::Write(int frame) {
  const State& s = sim_.state();
  const int dim = s.dimension;
  VtkMesh body;
  std::vector<Eigen::Vector3d> velocity;
  for (int i = 0; i < s.num_nodes(); ++i) {
    body.points.push_back(NodePosition(s.x, dim, i));
    velocity.push_back(NodePosition(s.v, dim, i));
  }
  body.point_vectors.push_back({"velocity", velocity});
  if (has_contact_) {
    // -grad of the barrier energy (the contact terms, unweighted) at x; zero
    // where it cannot be evaluated.
    Eigen::VectorXd gradient = Eigen::VectorXd::Zero(s.x.size());
    double energy = 0.0;
    const bool ok = sim_.potential().EvaluateUnweighted(
        [](const Term& term) { return term.family == ContactFilter::kContactFamily; }, s.x.data(),
        &energy, gradient.data());
    std::vector<Eigen::Vector3d> force;
    for (int i = 0; i < s.num_nodes(); ++i) {
      force.push_back(ok ? Eigen::Vector3d(-NodePosition(gradient, dim, i))
                         : Eigen::Vector3d::Zero());
    }
    body.point_vectors.push_back({"contact_force", force});
  }
  std::vector<int> kind;  // 0 spring, 1 triangle, 2 particle
  for (const Spring& spring : sim_.scene().springs) {
    body.AddCell(VtkCell::kLine, {spring.i, spring.j});
    kind.push_back(0);
  }
  for (const std::array<int, 3>& t : triangles_) {
    body.AddCell(VtkCell::kTriangle, {t[0], t[1], t[2]});
    kind.push_back(1);
  }
  for (int i : particles_) {
    body.AddCell(VtkCell::kVertex, {i});
    kind.push_back(2);
  }
  body.cell_integers.push_back({"kind", kind});
  const std::string body_file = Numbered("frame", frame);
  WriteVtu(body, (std::filesystem::path(directory_) / body_file).string(), output_);
  series_->Add(s.time, 0, body_file);
  if (obstacles_.empty()) return;
  std::string obstacle_file = "obstacles.vtu";
  if (obstacles_move_) obstacle_file = Numbered("obstacles", frame);
  if (obstacles_move_ || !static_obstacles_written_) {
    WriteVtu(ObstacleMesh(obstacles_, s.time, centre_, extent_),
             (std::filesystem::path(directory_) / obstacle_file).string(), output_);
    static_obstacles_written_ = true;
  }
  series_->Add(s.time, 1, obstacle_file);
}

}  // namespace ipstep
