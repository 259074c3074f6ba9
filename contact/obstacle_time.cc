#include "contact/obstacle_time.h"

#include <algorithm>

namespace ipstep {

ObstacleTime::ObstacleTime(const ObstacleList* obstacles, double t0)
    : obstacles_(obstacles), t_n_(t0), t_next_(t0), tau_(t0) {
  for (const ObstaclePtr& o : *obstacles_) has_moving_ |= o->is_moving();
}

void ObstacleTime::BeginStep(double t_n, double h) {
  t_n_ = t_n;
  t_next_ = t_n + h;
  tau_ = t_n;
}

void ObstacleTime::Advance(const std::function<double(double, double)>& first_impact) {
  if (!has_moving_) {
    tau_ = t_next_;
    return;
  }
  const double first = first_impact(tau_, t_next_);
  if (first > 1.0) {
    tau_ = t_next_;
  } else {
    tau_ += kAdvanceFraction * first * (t_next_ - tau_);
  }
}

std::vector<double> ObstacleTime::Travel() const {
  std::vector<double> travel;
  for (const ObstaclePtr& o_ptr : *obstacles_) {
    const Obstacle& o = *o_ptr;
    travel.push_back(o.velocity().norm() * std::max(0.0, t_next_ - tau_));
  }
  return travel;
}

double ObstacleTime::Work(
    const double* x_start, const double* x_end,
    const std::function<bool(const double*, double, double*)>& barrier_energy) const {
  if (!has_moving_ || !(t_next_ > t_n_)) return 0.0;
  const double h = t_next_ - t_n_, delta = 1e-6 * h;
  const auto rate = [&](const double* x, double t, double* value) {
    double up = 0.0, down = 0.0;
    if (!barrier_energy(x, t + delta, &up) || !barrier_energy(x, t - delta, &down)) return false;
    *value = (up - down) / (2.0 * delta);
    return true;
  };
  double at_start = 0.0, at_end = 0.0;
  const bool start_ok = rate(x_start, t_n_, &at_start);
  const bool end_ok = rate(x_end, t_next_, &at_end);
  if (start_ok && end_ok) return 0.5 * h * (at_start + at_end);
  if (start_ok || end_ok) return h * (start_ok ? at_start : at_end);
  return 0.0;
}

}  // namespace ipstep
