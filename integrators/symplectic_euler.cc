#include "integrators/symplectic_euler.h"

namespace ipstep {

// The potential is still built (forces come from the same energy terms); its
// weights make R's gradient equal B v at x = x_n (see core/forces.h).
void SymplecticEuler::SetWeights(double h, StepContext* c) const {
  c->time_step = h;
  c->inertia_weight = 0.0;
  c->potential_weight = 1.0;
  c->dissipation_weight = 1.0;
  c->velocity_slope = 1.0;
}

void SymplecticEuler::Advance(const Eigen::VectorXd& forces, double h, State* s) const {
  const int dim = s->dimension;
  for (int i = 0; i < s->num_nodes(); ++i) {
    if (!s->is_free(i)) continue;
    auto v = s->v.segment(dim * i, dim);
    const Eigen::VectorXd a = forces.segment(dim * i, dim) / s->mass[i];
    v += h * a;
    s->a.segment(dim * i, dim) = a;
    s->x.segment(dim * i, dim) += h * v;
  }
}

}  // namespace ipstep
