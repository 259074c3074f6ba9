#include "contact/obstacle_time.h"

#include <algorithm>

#include <Eigen/Core>

namespace ipstep {

ObstacleTime::ObstacleTime(const ObstacleList* obstacles, double t0)
    : obstacles_(obstacles), t_n_(t0), t_next_(t0), tau_(t0) {
  for (const ObstaclePtr& o : *obstacles_) has_moving_ |= o->is_moving();
}

void ObstacleTime::BeginStep(double t_n, double h, double lag) {
  t_n_ = t_n - std::max(0.0, lag);
  t_next_ = t_n + h;
  tau_ = t_n_;
}

double ObstacleTime::NextStop(double t) const {
  double stop = t_next_;
  for (const ObstaclePtr& o : *obstacles_) {
    if (o->is_moving() && o->until() > t && o->until() < stop) stop = o->until();
  }
  return stop;
}

void ObstacleTime::Advance(const std::function<double(double, double)>& first_impact) {
  if (!has_moving_) {
    tau_ = t_next_;
    return;
  }
  // Piece by piece between the obstacles' stop times, where every motion is
  // smooth (contact/obstacle.h).
  while (tau_ < t_next_) {
    const double end = NextStop(tau_);
    const double first = first_impact(tau_, end);
    if (first > 1.0) {
      tau_ = end;
    } else {
      tau_ += kAdvanceFraction * first * (end - tau_);
      return;
    }
  }
}

std::vector<double> ObstacleTime::Travel(const std::vector<double>& radius) const {
  std::vector<double> travel;
  for (size_t k = 0; k < obstacles_->size(); ++k) {
    const Obstacle& o = *(*obstacles_)[k];
    const double r = k < radius.size() ? radius[k] : 0.0;
    travel.push_back(tau_ < t_next_ ? o.DistanceChangeBound(tau_, t_next_, r) : 0.0);
  }
  return travel;
}

double ObstacleTime::Work(
    const double* x_start, const double* x_end, int size,
    const std::function<bool(const double*, double, double*)>& barrier_energy) const {
  if (!has_moving_ || !(t_next_ > t_n_)) return 0.0;
  const double h = t_next_ - t_n_, delta = 1e-6 * h;
  const auto rate = [&](const double* x, double t, double* value) {
    double up = 0.0, down = 0.0;
    if (!barrier_energy(x, t + delta, &up) || !barrier_energy(x, t - delta, &down)) return false;
    *value = (up - down) / (2.0 * delta);
    return true;
  };
  if (NextStop(t_n_) < t_next_) {
    // An obstacle stops within the step: the rule piece by piece between the
    // stop times (one-sided differences inside each piece), the positions
    // interpolated linearly.
    Eigen::VectorXd x(size);
    const auto at = [&](double t) {
      const double s = (t - t_n_) / h;
      for (int k = 0; k < size; ++k) x[k] = x_start[k] + s * (x_end[k] - x_start[k]);
      return x.data();
    };
    const auto one_sided = [&](double t, double dt, double* value) {
      double here = 0.0, there = 0.0;
      const double* xt = at(t);
      if (!barrier_energy(xt, t, &here) || !barrier_energy(xt, t + dt, &there)) return false;
      *value = (there - here) / dt;
      return true;
    };
    double work = 0.0;
    for (double a = t_n_; a < t_next_;) {
      const double b = NextStop(a);
      double r_a = 0.0, r_b = 0.0;
      const bool a_ok = one_sided(a, delta, &r_a), b_ok = one_sided(b, -delta, &r_b);
      if (a_ok && b_ok) work += 0.5 * (b - a) * (r_a + r_b);
      if (a_ok != b_ok) work += (b - a) * (a_ok ? r_a : r_b);
      a = b;
    }
    return work;
  }
  double at_start = 0.0, at_end = 0.0;
  const bool start_ok = rate(x_start, t_n_, &at_start);
  const bool end_ok = rate(x_end, t_next_, &at_end);
  if (start_ok && end_ok) return 0.5 * h * (at_start + at_end);
  if (start_ok || end_ok) return h * (start_ok ? at_start : at_end);
  return 0.0;
}

}  // namespace ipstep
