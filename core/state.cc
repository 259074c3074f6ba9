#include "core/state.h"

namespace ipstep {

int State::num_free_nodes() const {
  int count = 0;
  for (NodeKind k : kind) count += (k == NodeKind::kFree);
  return count;
}

void State::PrescribedPositions(double t, Eigen::VectorXd* positions) const {
  for (int i = 0; i < num_nodes(); ++i) {
    if (kind[i] == NodeKind::kFree) continue;
    positions->segment(dimension * i, dimension) =
        x0.segment(dimension * i, dimension) +
        t * prescribed_velocity.segment(dimension * i, dimension);
  }
}

double State::KineticEnergy() const {
  double ke = 0.0;
  for (int i = 0; i < num_nodes(); ++i) {
    ke += 0.5 * mass[i] * v.segment(dimension * i, dimension).squaredNorm();
  }
  return ke;
}

}  // namespace ipstep
