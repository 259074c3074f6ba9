#include "core/state.h"

namespace ipstep {

int State::num_free_nodes() const {
  int count = 0;
  for (NodeKind k : kind) count += (k == NodeKind::kFree);
  return count;
}

namespace {

Eigen::Vector3d Padded(const Eigen::VectorXd& x, int dimension, int node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(dimension) = x.segment(dimension * node, dimension);
  return p;
}

}  // namespace

void State::PrescribedPositions(double t, Eigen::VectorXd* positions) const {
  for (int i = 0; i < num_nodes(); ++i) {
    if (kind[i] == NodeKind::kFree) continue;
    positions->segment(dimension * i, dimension) =
        motion[i].Position(Padded(x0, dimension, i), t).head(dimension);
  }
}

void State::PrescribedVelocities(double t, Eigen::VectorXd* velocities) const {
  for (int i = 0; i < num_nodes(); ++i) {
    if (kind[i] == NodeKind::kFree) continue;
    velocities->segment(dimension * i, dimension) =
        motion[i].Velocity(Padded(x0, dimension, i), t).head(dimension);
  }
}

bool State::has_prescribed_motion() const {
  for (int i = 0; i < num_nodes(); ++i) {
    if (kind[i] != NodeKind::kFree && !motion[i].is_still()) return true;
  }
  return false;
}

double State::KineticEnergy() const {
  double ke = 0.0;
  for (int i = 0; i < num_nodes(); ++i) {
    ke += 0.5 * mass[i] * v.segment(dimension * i, dimension).squaredNorm();
  }
  return ke;
}

}  // namespace ipstep
