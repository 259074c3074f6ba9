#include "sim/prescribed_staging.h"

#include <cmath>

namespace ipstep {

PrescribedStaging::PrescribedStaging(const State& state, const Eigen::VectorXd& from,
                                     const Eigen::VectorXd& target)
    : target_(target) {
  const int dim = state.dimension;
  for (int i = 0; i < state.num_nodes(); ++i) {
    if (state.is_free(i)) continue;
    for (int k = 0; k < dim; ++k) {
      if (from[dim * i + k] != target[dim * i + k]) prescribed_.push_back(dim * i + k);
    }
  }
  if (prescribed_.empty()) lambda_ = 1.0;
}

bool PrescribedStaging::Next(const IncrementalPotential& potential, Eigen::VectorXd* x,
                             const Eigen::VectorXd* solution) {
  if (reached()) return true;
  if (stages_ > 0) {
    solutions_.push_back(solution ? *solution : *x);
    progress_.push_back(lambda_);
    if (solutions_.size() > 2) {
      solutions_.erase(solutions_.begin());
      progress_.erase(progress_.begin());
    }
  }
  // Paths from x: the prescribed coordinates to their targets, the free ones
  // held, or (from the third stage on) along the secant to lambda = 1.
  Eigen::VectorXd held = *x;
  for (int c : prescribed_) held[c] = target_[c];
  std::vector<Eigen::VectorXd> paths = {held};
  if (solutions_.size() == 2 && progress_[1] > progress_[0]) {
    const double ratio = (1.0 - progress_[1]) / (progress_[1] - progress_[0]);
    Eigen::VectorXd secant = *x + ratio * (solutions_[1] - solutions_[0]);
    for (int c = 0; c < secant.size(); ++c) {
      if (!std::isfinite(secant[c])) secant[c] = (*x)[c];
    }
    for (int c : prescribed_) secant[c] = target_[c];
    paths.insert(paths.begin(), secant);
  }
  potential.NotifyAccepted(x->data());
  double best = 0.0;
  const Eigen::VectorXd* chosen = nullptr;
  for (const Eigen::VectorXd& to : paths) {
    if (potential.IsStepValid(to.data())) {
      // The whole path is free: the prescribed nodes reach their targets.
      *x = to;
      lambda_ = 1.0;
      ++stages_;
      return true;
    }
    const double s = potential.MaxStepSize(x->data(), to.data());
    if (s > best) {
      best = s;
      chosen = &to;
    }
  }
  if (chosen == nullptr) return false;
  const double fraction = kStageFraction * best;
  *x += fraction * (*chosen - *x);
  lambda_ += fraction * (1.0 - lambda_);
  ++stages_;
  return true;
}

}  // namespace ipstep
