#include "contact/adaptive_kappa.h"

#include <algorithm>

#include "contact/barrier.h"

namespace ipstep {

AdaptiveKappa::AdaptiveKappa(double fixed, double node_stiffness, double mean_weight, double d_hat)
    : d_hat_(d_hat),
      kappa_min_(node_stiffness / (mean_weight * BarrierSecondDerivative(0.5 * d_hat, d_hat))),
      kappa_max_(kRange * kappa_min_),
      adaptive_(!(fixed > 0.0)),
      kappa_(adaptive_ ? kappa_min_ : fixed) {}

AdaptiveKappa AdaptiveKappa::ForMesh(const CollisionMesh& mesh, const std::vector<bool>& node_free,
                                     const State& state, const StepContext& context, double fixed,
                                     double d_hat) {
  double mass = 0.0, weight = 0.0;
  int count = 0;
  for (size_t s = 0; s < mesh.nodes.size(); ++s) {
    weight += mesh.weights[s];
    if (!node_free[s]) continue;
    mass += state.mass[mesh.nodes[s]];
    ++count;
  }
  mass = count > 0 ? mass / count : 1.0;
  weight = mesh.nodes.empty() ? 1.0 : weight / mesh.nodes.size();
  const double h = context.time_step > 0.0 ? context.time_step : 1.0;
  const double stiffness = context.inertia_weight > 0.0
                               ? mass * context.inertia_weight / context.potential_weight
                               : mass / (h * h);
  return AdaptiveKappa(fixed, stiffness, weight, d_hat);
}

bool GradientWithout(const IncrementalPotential& potential, std::initializer_list<int> groups,
                     const double* x, Eigen::VectorXd* gradient) {
  const long n = static_cast<long>(potential.dimension()) * potential.num_nodes();
  *gradient = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd part(n);
  bool ok = true;
  for (TermKind kind : {TermKind::kInertia, TermKind::kPotential, TermKind::kDissipation}) {
    double energy = 0.0;
    ok &= potential.EvaluateUnweighted(
        [kind, &groups](const Term& t) {
          if (t.kind != kind) return false;
          for (const int group : groups) {
            if (t.group == group) return false;
          }
          return true;
        },
        x, &energy, part.data());
    if (ok) *gradient += TermWeight(kind, potential.context()) * part;
  }
  return ok;
}

void AdaptiveKappa::Update(double gap,
                           const std::function<void(Eigen::VectorXd*)>& barrier_gradient,
                           const std::function<bool(Eigen::VectorXd*)>& rest_gradient) {
  if (!adaptive_) return;
  if (!balanced_ && gap < d_hat_) {
    Eigen::VectorXd g_b, g_e;
    barrier_gradient(&g_b);
    const bool ok = rest_gradient(&g_e);
    const double norm2 = g_b.squaredNorm();
    if (ok && norm2 > 0.0) {
      kappa_ = std::clamp(-g_b.dot(g_e) / norm2, kappa_min_, kappa_max_);
      balanced_ = true;
    }
  } else if (gap < kShrinkingGapFraction * d_hat_ && gap < previous_gap_) {
    kappa_ = std::min(2.0 * kappa_, kappa_max_);
  }
  previous_gap_ = gap;
}

}  // namespace ipstep
