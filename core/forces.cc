#include "core/forces.h"

namespace ipstep {

bool ComputeForces(IncrementalPotential* potential, const State& s, const Eigen::VectorXd& gravity,
                   Eigen::VectorXd* forces, bool impulsive) {
  StepContext& c = potential->context();
  // With v(x) = v + 1 * (x' - x), the gradient of R at x' = x is exactly B v.
  const Eigen::VectorXd saved_x_base = c.x_base, saved_v_base = c.v_base;
  const double saved_slope = c.velocity_slope;
  c.x_base = s.x;
  c.v_base = s.v;
  c.velocity_slope = 1.0;
  Eigen::VectorXd gradient(s.num_dofs());
  double energy = 0.0;
  const bool ok = potential->EvaluateUnweighted(
      [impulsive](const Term& t) {
        return t.kind != TermKind::kInertia && !t.uniform_gravity && (impulsive || !t.impulsive);
      },
      s.x.data(), &energy, gradient.data());
  c.x_base = saved_x_base;
  c.v_base = saved_v_base;
  c.velocity_slope = saved_slope;
  if (!ok) return false;
  const int dim = s.dimension;
  *forces = -gradient;
  for (int i = 0; i < s.num_nodes(); ++i) forces->segment(dim * i, dim) += s.mass[i] * gravity;
  return true;
}

bool ComputeAccelerations(IncrementalPotential* potential, const State& s,
                          const Eigen::VectorXd& gravity, Eigen::VectorXd* accelerations,
                          bool impulsive) {
  Eigen::VectorXd f;
  if (!ComputeForces(potential, s, gravity, &f, impulsive)) return false;
  const int dim = s.dimension;
  accelerations->setZero(s.num_dofs());
  for (int i = 0; i < s.num_nodes(); ++i) {
    if (s.is_free(i)) accelerations->segment(dim * i, dim) = f.segment(dim * i, dim) / s.mass[i];
  }
  return true;
}

bool ComputeEnergies(const IncrementalPotential& potential, const State& s,
                     const Eigen::VectorXd& gravity, bool has_inertia, double impulsive_factor,
                     EnergyReport* report, Eigen::VectorXd* gradient) {
  const int dim = s.dimension;
  double u = 0.0;
  Eigen::VectorXd part;
  if (gradient != nullptr) {
    gradient->setZero(s.num_dofs());
    part.resize(s.num_dofs());
  }
  // The smooth potentials, then the impulsive ones with their factor.
  for (const bool impulsive : {false, true}) {
    double e = 0.0;
    if (!potential.EvaluateUnweighted(
            [impulsive](const Term& t) {
              return t.kind == TermKind::kPotential && !t.uniform_gravity &&
                     t.impulsive == impulsive;
            },
            s.x.data(), &e, gradient != nullptr ? part.data() : nullptr)) {
      return false;
    }
    const double factor = impulsive ? impulsive_factor : 1.0;
    u += factor * e;
    if (gradient != nullptr) *gradient += factor * part;
  }
  for (int i = 0; i < s.num_nodes(); ++i) {
    u -= s.mass[i] * gravity.dot(s.x.segment(dim * i, dim));
    if (gradient != nullptr) gradient->segment(dim * i, dim) -= s.mass[i] * gravity;
  }
  report->potential = u;
  report->kinetic = has_inertia ? s.KineticEnergy() : 0.0;
  return true;
}

bool ComputeDissipation(const IncrementalPotential& potential, const Eigen::VectorXd& x,
                        double* dissipation) {
  return potential.EvaluateUnweighted(
      [](const Term& t) { return t.kind == TermKind::kDissipation; }, x.data(), dissipation,
      nullptr);
}

}  // namespace ipstep
