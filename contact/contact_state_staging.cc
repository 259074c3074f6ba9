// The contact state's moving obstacles (contact/contact_state.h, "Moving
// obstacles"): the obstacle time advanced as far as continuous collision
// detection allows, with the nodes held or along the secant through the last
// two stages' solutions, the start that secant proposes, and the reach of
// rotating obstacles.
#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "contact/contact_state.h"
#include "contact/obstacle.h"

namespace ipstep {

void ContactState::AdvanceObstacles(const double* x) {
  time_.Advance([&](double t_a, double t_b) { return Sweep(x, x, t_a, t_b); });
}

double ContactState::AdvanceObstaclesAlongSecant(const double* x) {
  has_proposal_ = false;
  const int n = static_cast<int>(num_coordinates_);
  stage_solutions_.push_back(Eigen::Map<const Eigen::VectorXd>(x, n));
  stage_times_.push_back(time_.tau());
  if (stage_solutions_.size() > 2) {
    stage_solutions_.erase(stage_solutions_.begin());
    stage_times_.erase(stage_times_.begin());
  }
  const double tau0 = time_.tau(), t_next = time_.t_next();
  AdvanceObstacles(x);
  ++stages_;
  if (stages_ < kSecantFromStage || stage_solutions_.size() < 2 ||
      !(stage_times_[1] > stage_times_[0])) {
    return 0.0;
  }
  held_tau_ = time_.tau();
  // x(t) = x + (t - tau0) / (t_next - tau0) (x_ext - x) for the free nodes.
  const Eigen::Map<const Eigen::VectorXd> x_now(x, n);
  Eigen::VectorXd direction = ((t_next - tau0) / (stage_times_[1] - stage_times_[0])) *
                              (stage_solutions_[1] - stage_solutions_[0]);
  for (int i = 0; i < state_->num_nodes(); ++i) {
    if (!state_->is_free(i)) direction.segment(dim_ * i, dim_).setZero();
  }
  const auto along = [&](double t) -> Eigen::VectorXd {
    return x_now + ((t - tau0) / (t_next - tau0)) * direction;
  };
  double* tau = time_.pointer();
  *tau = tau0;
  time_.Advance([&](double t_a, double t_b) {
    const Eigen::VectorXd a = along(t_a), b = along(t_b);
    return Sweep(a.data(), b.data(), t_a, t_b);
  });
  if (!(time_.tau() > held_tau_)) {
    *tau = held_tau_;
    return 0.0;
  }
  proposal_ = along(time_.tau());
  has_proposal_ = true;
  return (proposal_ - x_now).cwiseAbs().maxCoeff();
}

bool ContactState::ProposeStart(double* x) {
  if (!has_proposal_) return false;
  has_proposal_ = false;
  std::copy(proposal_.data(), proposal_.data() + proposal_.size(), x);
  return true;
}

void ContactState::StartRejected() { *time_.pointer() = held_tau_; }

std::vector<double> ContactState::RotationRadii(const double* a, const double* b,
                                                double reach) const {
  std::vector<double> radius(options_.obstacles.size(), 0.0);
  for (size_t o = 0; o < options_.obstacles.size(); ++o) {
    const Obstacle& obstacle = *options_.obstacles[o];
    if (!obstacle.rotates()) continue;
    const Eigen::Vector3d center = obstacle.RotationCenterAt(time_.tau());
    double farthest = 0.0;
    for (const int node : mesh_.nodes) {
      farthest = std::max({farthest, (ToPoint(a + dim_ * node, dim_) - center).norm(),
                           (ToPoint(b + dim_ * node, dim_) - center).norm()});
    }
    radius[o] = farthest + reach;
  }
  return radius;
}

}  // namespace ipstep
