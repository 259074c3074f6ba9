// The barrier stiffness kappa of the contact state, adaptive as in IPC (Li et
// al. 2020) unless a fixed value is given:
//  * kappa_min: the stiffness at which a barrier at d_hat / 2 is as stiff as a
//    node's inertia (mean free contact node mass m over the potential weight
//    w_U per unit contact weight; quasi-static: m / h^2);
//  * when contact first appears (smallest gap below d_hat), kappa balances the
//    barrier gradient g_B (kappa = 1) against the gradient g_E of the rest of
//    the incremental potential: kappa = -g_B.g_E / |g_B|^2, clamped to
//    [kappa_min, kappa_max = 1e4 kappa_min];
//  * at the start of a later step it doubles (up to kappa_max) while the
//    smallest gap is below d_hat / 100 and still shrinking.
#pragma once

#include <functional>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/collision_mesh.h"
#include "core/incremental_potential.h"
#include "core/state.h"

namespace ipstep {

class AdaptiveKappa {
 public:
  // fixed > 0: kappa stays `fixed`. node_stiffness: m w_I / w_U (or m / h^2);
  // mean_weight: the mean contact weight.
  AdaptiveKappa(double fixed, double node_stiffness, double mean_weight, double d_hat);
  // The scale from the mesh: the mean mass of its free nodes, their inertia
  // weight (or h^2 without inertia), the mean contact weight.
  static AdaptiveKappa ForMesh(const CollisionMesh& mesh, const std::vector<bool>& node_free,
                               const State& state, const StepContext& context, double fixed,
                               double d_hat);

  // At the start of a step, with the smallest gap at x_n (infinity if none).
  // barrier_gradient(g) fills g_B; rest_gradient(g) fills g_E and returns
  // false if the potential cannot be evaluated (both zero on fixed nodes).
  void Update(double gap, const std::function<void(Eigen::VectorXd*)>& barrier_gradient,
              const std::function<bool(Eigen::VectorXd*)>& rest_gradient);

  double value() const { return kappa_; }
  // Read by the barrier terms at every evaluation.
  const double* pointer() const { return &kappa_; }
  double min() const { return kappa_min_; }
  double max() const { return kappa_max_; }
  bool adaptive() const { return adaptive_; }

  static constexpr double kRange = 1e4;                  // kappa_max / kappa_min
  static constexpr double kShrinkingGapFraction = 1e-2;  // of d_hat

 private:
  double d_hat_;
  double kappa_min_;
  double kappa_max_;
  bool adaptive_;
  double kappa_;
  bool balanced_ = false;
  double previous_gap_ = std::numeric_limits<double>::infinity();
};

// The weighted gradient at x of every term of the potential outside the term
// `groups` (g_E); false if they cannot be evaluated.
bool GradientWithout(const IncrementalPotential& potential, std::initializer_list<int> groups,
                     const double* x, Eigen::VectorXd* gradient);

}  // namespace ipstep
