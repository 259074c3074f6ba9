// --frames=DIR: a ParaView time series of a run. DIR/run.pvd lists, for each
// frame at its simulated time (the `timestep`, so ParaView's time slider shows
// seconds), these parts, each a block of its own with its name:
//   0  "body", DIR/frame_NNNNN.vtu: the nodes (point data "velocity" and,
//      with contact, "contact_force": minus the gradient of the barrier
//      energy, the force the contact terms exert on each node [N]); cells:
//      springs as lines, as triangles the surface triangles the scene declares
//      (a 3D cloth's faces) else those filling the spring network
//      (io/surface_triangles.h), a 2D elastic solid's triangles, a 3D elastic
//      solid's tetrahedra (VTK_TETRA: Clip and Slice cut through them),
//      particles as vertices; cell data "kind" (0 spring, 1 triangle,
//      2 particle, 3 tetrahedron) and, for an elastic solid, the per-element
//      "J", "energy_density" and "von_mises_stress" (io/element_fields.h; 0 on
//      the cells that are not elements and where a field is not defined);
//   1  "obstacles", for scenes with contact obstacles (io/obstacle_mesh.h):
//      DIR/obstacles.vtu when none moves, else DIR/obstacles_NNNNN.vtu;
//   2  "surface", for a 3D elastic solid: its boundary, DIR/surface_NNNNN.vtu: the
//      boundary triangles on the boundary nodes, with the body's point data
//      and, per triangle, the fields of the element it bounds.
// The files are binary (zlib-compressed by default) or ASCII: VtkEncoding, with
// points and fields in Float32 (the default) or Float64: VtkPrecision
// (io/vtk_unstructured_grid.h). tools/animate.py and tools/render_frames.py
// (docs/paraview.md) draw such a directory.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/obstacle.h"
#include "io/element_fields.h"
#include "io/pvd_series.h"
#include "io/vtk_unstructured_grid.h"
#include "sim/simulation.h"

namespace ipstep {

class ContactEffect;

class FrameWriter {
 public:
  // Creates DIR if needed. Throws InputError "output: <output>: cannot create
  // directory ..." if it cannot, OutputError (io/output_file.h) if it cannot
  // write DIR/run.pvd (`output`: the caller's name for the series).
  FrameWriter(const std::string& directory, const Simulation& sim,
              const std::string& output = "frames", VtkEncoding encoding = VtkEncoding::kZlib,
              VtkPrecision precision = VtkPrecision::kFloat32);
  // Writes the simulation's current state as frame `frame` (e.g. the step);
  // throws OutputError if a file cannot be opened or written.
  void Write(int frame);

 private:
  std::vector<Eigen::Vector3d> ContactForces() const;
  // Part 2 of a 3D solid: its boundary with the body's point data and the
  // fields of the elements it bounds.
  void WriteSurface(int frame, const VtkMesh& body, const ElementFields& fields);

  std::string directory_;
  std::string output_;
  VtkEncoding encoding_;
  VtkPrecision precision_;
  const Simulation& sim_;
  std::unique_ptr<PvdSeries> series_;  // DIR/run.pvd
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> particles_;  // nodes without springs
  // A 3D solid's boundary: triangles on the surface nodes (numbered in
  // surface_nodes_, the body's node of each), the element of each triangle.
  std::vector<std::array<int, 3>> surface_;
  std::vector<int> surface_nodes_;
  std::vector<int> surface_elements_;
  ObstacleList obstacles_;
  // The scene's contact (point data "contact_force"), or null.
  const ContactEffect* contact_ = nullptr;
  bool obstacles_move_ = false;
  bool static_obstacles_written_ = false;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();  // of the initial positions
  double extent_ = 1.0;                               // half-width of drawn planes [m]
};

}  // namespace ipstep
