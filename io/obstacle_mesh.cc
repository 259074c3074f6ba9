#include "io/obstacle_mesh.h"

#include <cmath>

#include <Eigen/Geometry>

#include "contact/obstacles/box_obstacle.h"
#include "contact/obstacles/obstacle_visitor.h"
#include "contact/obstacles/plane_obstacle.h"
#include "contact/obstacles/sphere_obstacle.h"

namespace ipstep {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kCircleSegments = 64;
constexpr int kSphereRings = 12;    // latitude bands
constexpr int kSphereSectors = 24;  // longitude bands

int AddPoint(VtkMesh* mesh, const Eigen::Vector3d& p) {
  mesh->points.push_back(p);
  return static_cast<int>(mesh->points.size()) - 1;
}

void AddPlane(const PlaneObstacle& o, const Eigen::Vector3d& point, const Eigen::Vector3d& centre,
              double extent, VtkMesh* mesh) {
  const Eigen::Vector3d n = o.normal();
  const Eigen::Vector3d foot = centre - n * n.dot(centre - point);
  if (o.dimension() == 2) {
    const Eigen::Vector3d tangent(-n[1], n[0], 0.0);
    const int a = AddPoint(mesh, foot - extent * tangent);
    const int b = AddPoint(mesh, foot + extent * tangent);
    mesh->AddCell(VtkCell::kLine, {a, b});
    return;
  }
  const Eigen::Vector3d axis =
      std::abs(n[0]) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d u = n.cross(axis).normalized(), v = n.cross(u);
  std::vector<int> quad;
  for (const auto& [su, sv] :
       {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}}) {
    quad.push_back(AddPoint(mesh, foot + extent * (su * u + sv * v)));
  }
  mesh->AddCell(VtkCell::kQuad, quad);
}

void AddSphere(const SphereObstacle& o, const Eigen::Vector3d& c, VtkMesh* mesh) {
  const double r = o.radius();
  if (o.dimension() == 2) {
    std::vector<int> polygon;
    for (int s = 0; s < kCircleSegments; ++s) {
      const double angle = 2.0 * kPi * s / kCircleSegments;
      polygon.push_back(
          AddPoint(mesh, c + r * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0)));
    }
    mesh->AddCell(VtkCell::kPolygon, polygon);
    return;
  }
  // Poles and rings; triangles at the poles, quads between rings.
  const int south = AddPoint(mesh, c - r * Eigen::Vector3d::UnitZ());
  std::vector<int> first_of_ring;
  for (int ring = 1; ring < kSphereRings; ++ring) {
    const double polar = kPi * ring / kSphereRings;
    first_of_ring.push_back(static_cast<int>(mesh->points.size()));
    for (int s = 0; s < kSphereSectors; ++s) {
      const double azimuth = 2.0 * kPi * s / kSphereSectors;
      AddPoint(mesh,
               c + r * Eigen::Vector3d(std::sin(polar) * std::cos(azimuth),
                                       std::sin(polar) * std::sin(azimuth), -std::cos(polar)));
    }
  }
  const int north = AddPoint(mesh, c + r * Eigen::Vector3d::UnitZ());
  const auto at = [&](int ring, int s) { return first_of_ring[ring] + s % kSphereSectors; };
  for (int s = 0; s < kSphereSectors; ++s) {
    mesh->AddCell(VtkCell::kTriangle, {south, at(0, s + 1), at(0, s)});
    for (int ring = 0; ring + 1 < kSphereRings - 1; ++ring) {
      mesh->AddCell(VtkCell::kQuad,
                    {at(ring, s), at(ring, s + 1), at(ring + 1, s + 1), at(ring + 1, s)});
    }
    mesh->AddCell(VtkCell::kTriangle,
                  {north, at(kSphereRings - 2, s), at(kSphereRings - 2, s + 1)});
  }
}

void AddBox(const BoxObstacle& o, VtkMesh* mesh) {
  const Eigen::Vector3d lo = o.lower(), hi = o.upper();
  if (o.dimension() == 2) {
    mesh->AddCell(VtkCell::kPolygon,
                  {AddPoint(mesh, {lo[0], lo[1], 0}), AddPoint(mesh, {hi[0], lo[1], 0}),
                   AddPoint(mesh, {hi[0], hi[1], 0}), AddPoint(mesh, {lo[0], hi[1], 0})});
    return;
  }
  // Corner k has the upper bound in axis j where bit j of k is set.
  int corner[8];
  for (int k = 0; k < 8; ++k) {
    corner[k] =
        AddPoint(mesh, {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]});
  }
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& face : faces) {
    mesh->AddCell(VtkCell::kQuad,
                  {corner[face[0]], corner[face[1]], corner[face[2]], corner[face[3]]});
  }
}

// Each shape drawn at rest (a plane around the rest-frame image of the
// drawing's centre), its points then carried to time t by the obstacle's
// motion (Obstacle::ToWorld: translation and rotation).
class ShapeDrawer : public ObstacleVisitor {
 public:
  ShapeDrawer(double t, const Eigen::Vector3d& centre, double extent, VtkMesh* mesh)
      : t_(t), centre_(centre), extent_(extent), mesh_(mesh) {}
  void Visit(const PlaneObstacle& plane) override {
    const size_t first = mesh_->points.size();
    AddPlane(plane, plane.point(), plane.ToRest(centre_, t_), extent_, mesh_);
    ToWorld(plane, first);
  }
  void Visit(const SphereObstacle& sphere) override {
    const size_t first = mesh_->points.size();
    AddSphere(sphere, sphere.center(), mesh_);
    ToWorld(sphere, first);
  }
  void Visit(const BoxObstacle& box) override {
    const size_t first = mesh_->points.size();
    AddBox(box, mesh_);
    ToWorld(box, first);
  }

 private:
  void ToWorld(const Obstacle& obstacle, size_t first) {
    for (size_t k = first; k < mesh_->points.size(); ++k) {
      mesh_->points[k] = obstacle.ToWorld(mesh_->points[k], t_);
    }
  }

  double t_;
  Eigen::Vector3d centre_;
  double extent_;
  VtkMesh* mesh_;
};

}  // namespace

VtkMesh ObstacleMesh(const ObstacleList& obstacles, double t, const Eigen::Vector3d& centre,
                     double extent) {
  VtkMesh mesh;
  std::vector<int> owner;
  ShapeDrawer drawer(t, centre, extent, &mesh);
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const size_t cells = mesh.cells.size();
    obstacles[i]->Accept(drawer);
    owner.insert(owner.end(), mesh.cells.size() - cells, static_cast<int>(i));
  }
  mesh.cell_integers.push_back({"obstacle", owner});
  return mesh;
}

}  // namespace ipstep
