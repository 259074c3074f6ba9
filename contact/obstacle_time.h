// The time at which the contact state sees the obstacles within a step.
// Moving obstacles are advanced in stages: each solve uses them at a time tau,
// and Advance moves tau towards t_{n+1} as far as continuous collision
// detection against the current solution allows (0.8 of the way to the first
// impact), piece by piece between the obstacles' stop times (their "until":
// within a piece every obstacle's motion is smooth, as continuous collision
// detection needs). The step is feasible only once tau = t_{n+1}.
// Also the moving
// obstacles' work on the body over a step (Work).
#pragma once

#include <functional>
#include <vector>

#include "contact/obstacle.h"

namespace ipstep {

class ObstacleTime {
 public:
  // `obstacles` must outlive this.
  ObstacleTime(const ObstacleList* obstacles, double t0);

  // A step from t_n of length h: tau = t_n - lag (obstacles that a failed
  // step left behind start there, State::boundary_lag), t_{n+1} = t_n + h.
  void BeginStep(double t_n, double h, double lag = 0.0);
  // first_impact(t_a, t_b): the first fraction of the obstacles' motion from
  // t_a to t_b at which they reach the body (> 1: none).
  void Advance(const std::function<double(double, double)>& first_impact);
  bool reached_end() const { return !(tau_ < t_next_); }

  double tau() const { return tau_; }
  // Read by the terms at every evaluation; the contact state may set it to
  // evaluate at another time.
  double* pointer() { return &tau_; }
  // The obstacles' time at the start of the step (t_n - lag).
  double t_n() const { return t_n_; }
  double t_next() const { return t_next_; }
  bool has_moving_obstacles() const { return has_moving_; }
  // Per obstacle: how much it can still change the distance of a point in the
  // step [m] (Obstacle::DistanceChangeBound): its travel without rotation; a
  // rotating obstacle's also depends on radius[o], the largest distance of
  // the points that matter from its centre (zero for the others; an empty
  // vector: all zero).
  std::vector<double> Travel(const std::vector<double>& radius = {}) const;

  // The moving obstacles' work on the body over the step: the integral of
  // dU_b/dt (the barrier energy's rate at fixed positions, central differences
  // in the obstacle time) by the trapezoidal rule between (x_start, t_n()) and
  // (x_end, t_{n+1}) (one end if the other cannot be evaluated; 0 without
  // moving obstacles). barrier_energy(x, t, &U) returns false when U cannot
  // be evaluated.
  // x has `size` coordinates. A step in which an obstacle stops is
  // integrated piece by piece between the stop times.
  double Work(const double* x_start, const double* x_end, int size,
              const std::function<bool(const double*, double, double*)>& barrier_energy) const;

  static constexpr double kAdvanceFraction = 0.8;

 private:
  // The first stop time of a moving obstacle in (t, t_{n+1}), else t_{n+1}.
  double NextStop(double t) const;

  const ObstacleList* obstacles_;
  bool has_moving_ = false;
  double t_n_;
  double t_next_;
  double tau_;
};

}  // namespace ipstep
