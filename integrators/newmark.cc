#include "integrators/newmark.h"

#include <cmath>

#include "core/forces.h"

namespace ipstep {

void Newmark::SetWeights(double h, StepContext* c) const {
  c->time_step = h;
  c->inertia_weight = 1.0;
  c->potential_weight = beta_ * h * h;
  c->dissipation_weight = beta_ * beta_ * h * h * h / gamma_;
  c->velocity_slope = gamma_ / (beta_ * h);
}

bool Newmark::InitializeState(IncrementalPotential* potential, const Eigen::VectorXd& gravity,
                              State* s) const {
  return ComputeAccelerations(potential, *s, gravity, &s->a, /*impulsive=*/false);
}

Eigen::VectorXd Newmark::ExplicitPart(const State& s, double h) const {
  return s.x + h * s.v + h * h * (0.5 - beta_) * s.a;
}

void Newmark::Predict(const State& s, const Eigen::VectorXd& gravity, double h, StepContext* c,
                      Eigen::VectorXd* guess) const {
  const int dim = s.dimension;
  c->x_start = s.x;
  c->x_base = ExplicitPart(s, h);
  c->v_base = s.v + h * (1.0 - gamma_) * s.a;
  for (int i = 0; i < s.num_nodes(); ++i) {
    c->x_tilde.segment(dim * i, dim) = c->x_base.segment(dim * i, dim) + beta_ * h * h * gravity;
  }
  // Guess: constant acceleration over the step.
  *guess = s.x + h * s.v + 0.5 * h * h * s.a;
}

void Newmark::Update(const Eigen::VectorXd& x_next, const ImpulsiveForcesAt& impulsive_forces,
                     double h, State* s) const {
  Eigen::VectorXd forces;
  if (impulsive_forces(x_next, &forces)) {
    UpdateWithImpulses(x_next, forces, h, s);
    return;
  }
  const Eigen::VectorXd a_next = (x_next - ExplicitPart(*s, h)) / (beta_ * h * h);
  s->v += h * ((1.0 - gamma_) * s->a + gamma_ * a_next);
  s->a = a_next;
  s->x = x_next;
}

void Newmark::UpdateWithImpulses(const Eigen::VectorXd& x_next,
                                 const Eigen::VectorXd& impulsive_forces, double h,
                                 State* s) const {
  const int dim = s->dimension;
  Eigen::VectorXd impulse_acceleration(impulsive_forces.size());
  for (int i = 0; i < s->num_nodes(); ++i) {
    impulse_acceleration.segment(dim * i, dim) =
        s->is_free(i) ? Eigen::VectorXd(impulsive_forces.segment(dim * i, dim) / s->mass[i])
                      : Eigen::VectorXd::Zero(dim);
  }
  const Eigen::VectorXd a_next =
      (x_next - ExplicitPart(*s, h)) / (beta_ * h * h) - impulse_acceleration;
  s->v += h * ((1.0 - gamma_) * s->a + gamma_ * a_next) + 2.0 * beta_ * h * impulse_acceleration;
  s->a = a_next;
  s->x = x_next;
}

void Newmark::LocalErrorVector(const State& before, const State& after, double h,
                               Eigen::VectorXd* error) const {
  *error = h * h * (std::abs(beta_ - 1.0 / 6.0) + std::abs(gamma_ - 0.5)) * (after.a - before.a);
}

}  // namespace ipstep
