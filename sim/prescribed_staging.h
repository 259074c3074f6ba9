// Prescribed (moving and pinned) nodes staged like moving obstacles
// (contact/obstacle_time.h): a step whose prescribed nodes would move into an
// obstacle or a body at once (the straight path from x_n with them at their
// t_{n+1} positions is not feasible, and neither is the predictor's) moves
// them in stages. Each stage moves every prescribed node along the straight
// line from its position at x_n to its target, to the progress lambda in
// [0, 1], then the step is solved for the free nodes; the next stage starts
// from that solution. From the third stage on the free nodes are moved along
// too, by the secant through the last two stages' solutions extrapolated to
// lambda = 1 (a body pressed by the nodes then moves with them instead of
// stopping each stage at the gap the barrier leaves). A stage goes
// kStageFraction of the way to the first impact on its path (the filters'
// MaxStepSize), the secant path or, if that one is shorter, the one with the
// free nodes held; the prescribed nodes reach their targets once that path is
// free up to lambda = 1.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

class PrescribedStaging {
 public:
  // `from`: x_n; `target`: x_n with the prescribed nodes at t_{n+1}.
  PrescribedStaging(const State& state, const Eigen::VectorXd& from, const Eigen::VectorXd& target);

  // Moves x, the solution at the current progress (x_n before the first
  // stage), to the start of the next stage; false when no stage can advance
  // (the first impact is at the start of both paths). `solution`, when not
  // null, is the last stage's solution for the secant if x was moved since
  // (a moving obstacle's staged start, ContactFilter::ProposeStart).
  bool Next(const IncrementalPotential& potential, Eigen::VectorXd* x,
            const Eigen::VectorXd* solution = nullptr);
  bool reached() const { return lambda_ >= 1.0; }
  double progress() const { return lambda_; }
  int stages() const { return stages_; }

  static constexpr double kStageFraction = 0.8;

 private:
  std::vector<int> prescribed_;  // coordinates of prescribed nodes
  Eigen::VectorXd target_;
  double lambda_ = 0.0;
  int stages_ = 0;
  // The last two stages' solutions and their progress (the secant).
  std::vector<Eigen::VectorXd> solutions_;
  std::vector<double> progress_;
};

}  // namespace ipstep
