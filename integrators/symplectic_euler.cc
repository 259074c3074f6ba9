#include "integrators/symplectic_euler.h"

namespace ipstep {

// The potential is still built: the forces come from the same energy terms,
// which ComputeForces (core/forces.h) evaluates unweighted with its own
// velocity map, v(x) = v_n + 1 (x - x_n), so that R's gradient at x_n is B v_n;
// these weights do not scale the forces. They matter where the potential is
// built: w_I = 0 builds no inertia terms (Simulation::BuildPotential) and
// sizes contact's adaptive barrier stiffness by m / h^2
// (contact/adaptive_kappa.cc); with w_U = w_R = 1 the weighted terms are the
// unweighted ones, and the slope 1 is the one ComputeForces uses.
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
