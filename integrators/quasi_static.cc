#include "integrators/quasi_static.h"

namespace ipstep {

void QuasiStatic::SetWeights(double h, StepContext* c) const {
  c->time_step = h;
  c->inertia_weight = 0.0;
  c->potential_weight = 1.0;
  c->dissipation_weight = h;
  c->velocity_slope = 1.0 / h;
}

void QuasiStatic::Predict(const State& s, const Eigen::VectorXd&, double, StepContext* c,
                          Eigen::VectorXd* guess) const {
  c->x_start = s.x;
  c->x_base = s.x;
  c->v_base.setZero();
  c->x_tilde = s.x;
  *guess = s.x;
}

void QuasiStatic::Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt&, double h,
                         State* s) const {
  s->v = (x_next - s->x) / h;
  s->a.setZero();
  s->x = x_next;
}

}  // namespace ipstep
