// --frames=DIR: a ParaView time series of a run. DIR/run.pvd lists, for each
// frame at its simulated time (the `timestep`, so ParaView's time slider shows
// seconds), the body DIR/frame_NNNNN.vtu (points, springs as lines, as
// triangles the surface triangles the scene declares (a 3D cloth's faces, a 3D
// elastic solid's boundary), else those filling the spring network
// (io/surface_triangles.h), or a 2D elastic solid's triangles, particles
// as vertices; point data "velocity" and, with contact,
// "contact_force": minus the gradient of the barrier energy, the force the
// contact terms exert on each node [N]) as part 0 and, for scenes with
// contact obstacles, the obstacles (io/obstacle_mesh.h) as part 1:
// DIR/obstacles.vtu when none moves, else DIR/obstacles_NNNNN.vtu per frame.
// tools/animate.py draws such a directory.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/obstacle.h"
#include "io/pvd_series.h"
#include "sim/simulation.h"

namespace ipstep {

class FrameWriter {
 public:
  // Creates DIR if needed. Throws InputError "output: <output>: cannot create
  // directory ..." if it cannot, OutputError (io/output_file.h) if it cannot
  // write DIR/run.pvd (`output`: the caller's name for the series).
  FrameWriter(const std::string& directory, const Simulation& sim,
              const std::string& output = "frames");
  // Writes the simulation's current state as frame `frame` (e.g. the step);
  // throws OutputError if a file cannot be opened or written.
  void Write(int frame);

 private:
  std::string directory_;
  std::string output_;
  const Simulation& sim_;
  std::unique_ptr<PvdSeries> series_;  // DIR/run.pvd
  std::vector<std::array<int, 3>> triangles_;
  std::vector<int> particles_;  // nodes without springs
  ObstacleList obstacles_;
  bool has_contact_ = false;  // the scene has contact: point data "contact_force"
  bool obstacles_move_ = false;
  bool static_obstacles_written_ = false;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();  // of the initial positions
  double extent_ = 1.0;                               // half-width of drawn planes [m]
};

}  // namespace ipstep
