// The simulated state: positions, velocities, accelerations (used by Newmark),
// masses and boundary conditions of every node, in 2D or 3D.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/prescribed_motion.h"

namespace ipstep {

enum class NodeKind {
  kFree,    // unknown of the step
  kPinned,  // held at its initial position
  kMoving,  // moved by its prescribed motion (moving Dirichlet: translation, rotation)
};

struct State {
  int dimension = 2;
  double time = 0.0;
  // How far [s] the moving boundaries (staged moving obstacles) are behind
  // `time`: 0, unless a failed step kept a state they had not reached
  // (sim/simulation.h); the next step starts them at time - boundary_lag.
  double boundary_lag = 0.0;
  // Flattened per node: x[dimension * i + k].
  Eigen::VectorXd x;
  Eigen::VectorXd v;
  Eigen::VectorXd a;     // accelerations at `time` (Newmark)
  Eigen::VectorXd mass;  // per node
  std::vector<NodeKind> kind;
  Eigen::VectorXd x0;  // initial positions (pinned and moving nodes follow them)
  // Per node; the zero motion unless kMoving (core/prescribed_motion.h).
  std::vector<PrescribedMotion> motion;

  int num_nodes() const { return static_cast<int>(mass.size()); }
  int num_dofs() const { return static_cast<int>(x.size()); }
  bool is_free(int node) const { return kind[node] == NodeKind::kFree; }
  int num_free_nodes() const;

  // Positions / velocities of the constrained nodes at time t (their
  // PrescribedMotion of x0); free nodes' entries are left alone.
  void PrescribedPositions(double t, Eigen::VectorXd* positions) const;
  void PrescribedVelocities(double t, Eigen::VectorXd* velocities) const;
  // Some node moves (the energy balance then counts the work done on it).
  bool has_prescribed_motion() const;
  // Kinetic energy 1/2 sum m_i |v_i|^2 over all nodes.
  double KineticEnergy() const;
};

}  // namespace ipstep
