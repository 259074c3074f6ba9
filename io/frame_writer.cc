#include "io/frame_writer.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>

#include "contact/contact_effect.h"
#include "core/input_error.h"
#include "io/element_fields.h"
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

bool IsSolid3d(const Scene& scene) { return scene.solid && scene.dimension == 3; }

// The triangles of the body: a 2D solid's elements, none for a 3D solid
// (tetrahedra; its boundary is the surface part), otherwise the declared
// surface (a 3D cloth's faces) or the triangles filling the spring network
// (io/surface_triangles.h).
std::vector<std::array<int, 3>> PictureTriangles(const Scene& scene) {
  if (IsSolid3d(scene)) return {};
  if (scene.solid && scene.dimension == 2) {
    std::vector<std::array<int, 3>> triangles;
    for (const std::array<int, 4>& e : scene.solid->mesh.elements) {
      triangles.push_back({e[0], e[1], e[2]});
    }
    return triangles;
  }
  return SurfaceTriangles(scene);
}

// The element of each boundary triangle of a 3D solid (the one with that face).
std::vector<int> FaceElements(const SimplexMesh& mesh,
                              const std::vector<std::array<int, 3>>& triangles) {
  std::map<std::array<int, 3>, int> element_of;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> face;
      for (int k = 0, n = 0; k < 4; ++k) {
        if (k != skip) face[n++] = mesh.elements[e][k];
      }
      std::sort(face.begin(), face.end());
      element_of[face] = e;
    }
  }
  std::vector<int> elements;
  for (std::array<int, 3> t : triangles) {
    std::sort(t.begin(), t.end());
    const auto found = element_of.find(t);
    elements.push_back(found == element_of.end() ? -1 : found->second);
  }
  return elements;
}

// The cell data of a solid's elements, by name.
using NamedField = std::pair<const char*, const std::vector<double>*>;
std::array<NamedField, 3> NamedFields(const ElementFields& f) {
  return {{{"J", &f.J},
           {"energy_density", &f.energy_density},
           {"von_mises_stress", &f.von_mises_stress}}};
}

std::string Numbered(const char* stem, int frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%05d.vtu", stem, frame);
  return name;
}

}  // namespace

FrameWriter::FrameWriter(const std::string& directory, const Simulation& sim,
                         const std::string& output, VtkEncoding encoding, VtkPrecision precision)
    : directory_(directory),
      output_(output),
      encoding_(encoding),
      precision_(precision),
      sim_(sim) {
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
  if (IsSolid3d(scene)) {
    surface_ = SurfaceTriangles(scene);
    surface_elements_ = FaceElements(scene.solid->mesh, surface_);
    std::vector<int> local(scene.num_nodes(), -1);
    for (std::array<int, 3>& t : surface_) {
      for (int& node : t) {
        if (local[node] < 0) {
          local[node] = static_cast<int>(surface_nodes_.size());
          surface_nodes_.push_back(node);
        }
        node = local[node];
      }
    }
  }
  std::vector<bool> has_spring(scene.num_nodes(), scene.solid != nullptr);
  for (const Spring& s : scene.springs) has_spring[s.i] = has_spring[s.j] = true;
  for (int i = 0; i < scene.num_nodes(); ++i) {
    if (!has_spring[i]) particles_.push_back(i);
  }
  contact_ = sim.FindEffect<ContactEffect>();
  if (contact_ != nullptr) {
    for (const ObstaclePtr& o : contact_->obstacles()) {
      obstacles_.push_back(o);
      obstacles_move_ = obstacles_move_ || o->is_moving();
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
  const Scene& scene = sim_.scene();
  const int dim = s.dimension;
  VtkMesh body;
  std::vector<Eigen::Vector3d> velocity;
  for (int i = 0; i < s.num_nodes(); ++i) {
    body.points.push_back(NodePosition(s.x, dim, i));
    velocity.push_back(NodePosition(s.v, dim, i));
  }
  body.point_vectors.push_back({"velocity", velocity});
  if (contact_ != nullptr) body.point_vectors.push_back({"contact_force", ContactForces()});
  std::vector<int> kind;  // 0 spring, 1 triangle, 2 particle, 3 tetrahedron
  for (const Spring& spring : scene.springs) {
    body.AddCell(VtkCell::kLine, {spring.i, spring.j});
    kind.push_back(0);
  }
  const size_t first_element = body.cells.size();
  for (const std::array<int, 3>& t : triangles_) {
    body.AddCell(VtkCell::kTriangle, {t[0], t[1], t[2]});
    kind.push_back(1);
  }
  if (IsSolid3d(scene)) {
    for (const std::array<int, 4>& e : scene.solid->mesh.elements) {
      body.AddCell(VtkCell::kTetra, {e[0], e[1], e[2], e[3]});
      kind.push_back(3);
    }
  }
  for (int i : particles_) {
    body.AddCell(VtkCell::kVertex, {i});
    kind.push_back(2);
  }
  body.cell_integers.push_back({"kind", kind});
  ElementFields fields;
  if (scene.solid) {
    // The solid's elements are the body's triangles (2D) or tetrahedra (3D),
    // in order, after the springs; the other cells get 0.
    fields = SolidElementFields(*scene.solid, s.x);
    for (const auto& [name, values] : NamedFields(fields)) {
      std::vector<double> per_cell(body.cells.size(), 0.0);
      std::copy(values->begin(), values->end(), per_cell.begin() + first_element);
      body.cell_scalars.push_back({name, per_cell});
    }
  }
  const std::string body_file = Numbered("frame", frame);
  WriteVtu(body, (std::filesystem::path(directory_) / body_file).string(), output_, encoding_,
           precision_);
  series_->Add(s.time, 0, "body", body_file);
  if (!obstacles_.empty()) {
    std::string obstacle_file = "obstacles.vtu";
    if (obstacles_move_) obstacle_file = Numbered("obstacles", frame);
    if (obstacles_move_ || !static_obstacles_written_) {
      WriteVtu(ObstacleMesh(obstacles_, s.time, centre_, extent_),
               (std::filesystem::path(directory_) / obstacle_file).string(), output_, encoding_,
               precision_);
      static_obstacles_written_ = true;
    }
    series_->Add(s.time, 1, "obstacles", obstacle_file);
  }
  if (IsSolid3d(scene)) WriteSurface(frame, body, fields);
}

std::vector<Eigen::Vector3d> FrameWriter::ContactForces() const {
  // The contact effect's barrier forces at x; zero where they cannot be evaluated.
  const State& s = sim_.state();
  Eigen::VectorXd forces;
  const bool ok = contact_ != nullptr && contact_->state().BarrierForces(s.x.data(), &forces);
  std::vector<Eigen::Vector3d> force;
  for (int i = 0; i < s.num_nodes(); ++i) {
    force.push_back(ok ? Eigen::Vector3d(NodePosition(forces, s.dimension, i))
                       : Eigen::Vector3d::Zero());
  }
  return force;
}

void FrameWriter::WriteSurface(int frame, const VtkMesh& body, const ElementFields& fields) {
  VtkMesh surface;
  for (int node : surface_nodes_) surface.points.push_back(body.points[node]);
  for (const auto& [name, values] : body.point_vectors) {
    std::vector<Eigen::Vector3d> on_surface;
    for (int node : surface_nodes_) on_surface.push_back(values[node]);
    surface.point_vectors.push_back({name, on_surface});
  }
  for (const std::array<int, 3>& t : surface_) {
    surface.AddCell(VtkCell::kTriangle, {t[0], t[1], t[2]});
  }
  for (const auto& [name, values] : NamedFields(fields)) {
    std::vector<double> per_face;
    for (int e : surface_elements_) per_face.push_back(e < 0 ? 0.0 : (*values)[e]);
    surface.cell_scalars.push_back({name, per_face});
  }
  const std::string file = Numbered("surface", frame);
  WriteVtu(surface, (std::filesystem::path(directory_) / file).string(), output_, encoding_,
           precision_);
  series_->Add(sim_.state().time, 2, "surface", file);
}

}  // namespace ipstep
