#include "integrators/backward_euler.h"

namespace ipstep {

void BackwardEuler::SetWeights(double h, StepContext* c) const {
  c->time_step = h;
  c->inertia_weight = 1.0;
  c->potential_weight = h * h;
  c->dissipation_weight = h * h * h;
  c->velocity_slope = 1.0 / h;
}

void BackwardEuler::Predict(const State& s, const Eigen::VectorXd& gravity, double h,
                            StepContext* c, Eigen::VectorXd* guess) const {
  const int dim = s.dimension;
  c->x_start = s.x;
  c->x_base = s.x;
  c->v_base.setZero();
  for (int i = 0; i < s.num_nodes(); ++i) {
    c->x_tilde.segment(dim * i, dim) =
        s.x.segment(dim * i, dim) + h * s.v.segment(dim * i, dim) + h * h * gravity;
  }
  *guess = c->x_tilde;
}

void BackwardEuler::Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt&, double h,
                           State* s) const {
  const Eigen::VectorXd v_next = (x_next - s->x) / h;
  s->a = (v_next - s->v) / h;
  s->v = v_next;
  s->x = x_next;
}

}  // namespace ipstep
