// One energy term of the incremental potential: a Ceres cost function over the
// positions of a few nodes (one parameter block of `dimension` doubles per node),
// optionally with a loss function, and the family it belongs to.
//
// A term's cost function computes the UNWEIGHTED residual r of its energy,
// e = 1/2 rho(|r|^2) (rho = identity without a loss). The step weight of the
// family (StepContext::inertia_weight, potential_weight, dissipation_weight) is
// applied on top: by WeightedCostFunction / WeightedLoss when the term is given to
// a ceres::Problem as it is (gauss_newton), by NewtonModelCost when its Newton
// model is (newton, dogleg: solver/newton_model_cost.h), and directly by the
// evaluators (IncrementalPotential, core/term_hessian.h). So one definition
// serves every optimiser.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ceres/cost_function.h>
#include <ceres/loss_function.h>
#include <Eigen/Core>

#include "core/step_context.h"

namespace ipstep {

// Second derivatives of a term's residuals, contracted with coefficients c (one
// per residual): C = sum_k c_k Hess(r_k)(x), written row-major over the term's
// model coordinates (all its parameters, nodes x dimension; for pair-difference
// terms the dimension components of d = x_1 - x_0). False if it cannot be
// evaluated at x. Used by the Newton models (core/term_hessian.h).
using ResidualCurvature =
    std::function<bool(const double* const* x, const double* c, double* curvature)>;

// A term's energy, gradient and Hessian in closed form, through reduced
// coordinates y = B x (an elastic element's deformation gradient): fills the
// UNWEIGHTED ReducedModel (core/term_hessian.h) at x; the eigensystem only
// when `hessian` is true. False if it cannot be evaluated at x.
struct ReducedModel;
using ReducedModelFunction =
    std::function<bool(const double* const* x, bool hessian, ReducedModel* model)>;

enum class TermKind {
  kInertia,      // 1/2 |x - x_tilde|_M^2, weight w_I
  kPotential,    // U(x), weight w_U (springs, external loads, barriers, ...)
  kDissipation,  // R(v(x)), weight w_R
};

// The largest term: nodes x dimension parameters (8 nodes in 3D). Newton
// models work on fixed-capacity matrices of this size.
constexpr int kMaxTermCoordinates = 24;

const char* TermKindName(TermKind kind);
double TermWeight(TermKind kind, const StepContext& context);

// Who a term belongs to: its family names it in reports ("contact"); its group
// (IncrementalPotential::NewTermGroup; 0: none) lets the owner that rebuilds
// terms (the contact state) remove and select exactly its own.
struct TermOwner {
  const char* family = "";
  int group = 0;
};

struct Term {
  TermKind kind = TermKind::kPotential;
  std::string family;  // effect that built it, e.g. "springs"
  int group = 0;       // TermOwner::group
  void SetOwner(const TermOwner& owner) {
    family = owner.family;
    group = owner.group;
  }
  std::vector<int> nodes;                     // one parameter block per node
  std::unique_ptr<ceres::CostFunction> cost;  // unweighted residual
  std::unique_ptr<ceres::LossFunction> loss;  // may be null
  // Impulsive (contact barrier, friction): integrators that keep an acceleration
  // history (Newmark) apply these forces as an impulse over the step instead
  // (VariationalIntegrator::Update, integrators/newmark.h).
  bool impulsive = false;
  // A dissipation measured relative to a moving surface (friction against a
  // moving obstacle): that surface's velocity u (zero: at rest). The force
  // F = -dR/dv such a term applies does the work h F . u of the surface's
  // motion over a step (IncrementalPotential::FrameDissipationRate; the
  // energy balance counts it, sim/energy_balance.h).
  Eigen::Vector3d frame_velocity = Eigen::Vector3d::Zero();
  // Optional: the same residual evaluated in extended precision (long double),
  // set for autodiff terms. Line searches compare energies whose differences near
  // convergence are far below double round-off of the energies themselves.
  std::function<bool(const double* const* x, long double* residuals)> precise_residual;
  // Optional: the loss rho(s) in extended precision, for the same energies
  // (a loss evaluated in double limits them to its own round-off).
  std::function<long double(long double s)> precise_loss;
  // Optional: the term's unweighted energy itself in extended precision,
  // used instead of the two above where a residual form loses digits (the
  // neo-Hookean element's r = sqrt(2 V Psi + c): V Psi - c cancels).
  std::function<bool(const double* const* x, long double* energy)> precise_energy;

  // Second-order information for the Newton models (core/term_hessian.h).
  // Gauss-Newton (rho' J^T J + 2 rho'' (J^T r)(J^T r)^T) is this term's model:
  // true where the residuals are affine in x, so that it is the exact Hessian
  // (inertia always, Rayleigh damping, plane gaps), or where the term chooses
  // it (the quasi-static gravity potential, energies/gravity_potential.h).
  bool gauss_newton_model = false;
  // The energy itself is affine in x (the quasi-static gravity potential,
  // written as a square for Ceres): its exact Hessian is zero, and the
  // Gauss-Newton curvature its residual form carries is a model artefact.
  // Newton models that ask for the exact Hessian (projected_newton's
  // when_indefinite and progressive) take zero.
  bool affine_energy = false;
  // The uniform-gravity potential of the quasi-static integrator
  // (energies/gravity_potential.h), whose value carries an offset: force and
  // energy reports (core/forces.h) leave these terms out and count M g and
  // -m g.x from the gravity vector instead.
  bool uniform_gravity = false;
  // Two nodes whose residuals depend on d = x_1 - x_0 only (springs): the
  // Hessian is [[K, -K], [-K, K]] and the model is built over d (K).
  bool pair_difference = false;
  // Analytic second derivatives; empty: central differences of the Jacobian.
  ResidualCurvature curvature;
  // Optional: the Newton model in closed form (then `curvature` is not used
  // for it): the energy is still defined by `cost` and `loss`, and the two
  // must agree (tested per term type).
  ReducedModelFunction reduced_model;
  int reduced_size = 0;  // k, the reduced coordinates of reduced_model
};

// Decorator that multiplies residuals and Jacobians by sqrt(weight), the weight
// read through a pointer at every evaluation. When `veto` is set and true, the
// evaluation fails (a step filter rejected the trial point).
class WeightedCostFunction : public ceres::CostFunction {
 public:
  WeightedCostFunction(const ceres::CostFunction* inner, const double* weight,
                       const bool* veto = nullptr);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const ceres::CostFunction* inner_;
  const double* weight_;
  const bool* veto_;
};

// Decorator for terms with a loss: rho_w(s) = weight * rho(s) (and rho_w'' = 0
// where rho_w' <= 0, which Ceres's corrector would abort on).
class WeightedLoss : public ceres::LossFunction {
 public:
  WeightedLoss(const ceres::LossFunction* inner, const double* weight);
  void Evaluate(double s, double rho[3]) const override;

 private:
  const ceres::LossFunction* inner_;
  const double* weight_;
};

}  // namespace ipstep
