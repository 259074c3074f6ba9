// The interface an effect uses to add its energy terms to the incremental
// potential. A new energy is one templated functor (Ceres autodiff, templated on
// the dimension) plus one registration (energies/effect_registry.h); see
// docs/new_energy.md for a worked example.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <ceres/autodiff_cost_function.h>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "energies/effect.h"
#include "problems/scene.h"

namespace ipstep {

// Pass as kNumResiduals for terms with one residual per coordinate (kDim of them).
constexpr int kOneResidualPerCoordinate = -1;

// Optional declarations of a functor, read by AddAutoDiff (core/term.h):
//   static constexpr bool kGaussNewtonModel = true;  residuals affine in x: J^T J
//       is the exact Hessian (Term::gauss_newton_model);
//   static constexpr bool kPairDifference = true;   two nodes, residuals of
//       x_1 - x_0 only (Term::pair_difference);
//   static constexpr bool kAffineEnergy = true;     the energy itself is affine
//       in x: its exact Hessian is zero (Term::affine_energy);
//   static constexpr bool kUniformGravity = true;   the uniform-gravity
//       potential, which reports count from the gravity vector instead
//       (Term::uniform_gravity);
//   bool ResidualCurvature(const double* const* x, const double* c,
//                          double* curvature) const;
//       analytic sum_k c_k Hess(r_k) (Term::curvature); without it Newton
//       methods take central differences of the autodiff Jacobian.
template <class F, class = void>
struct DeclaresGaussNewtonModel : std::false_type {};
template <class F>
struct DeclaresGaussNewtonModel<F, std::void_t<decltype(F::kGaussNewtonModel)>>
    : std::bool_constant<F::kGaussNewtonModel> {};
template <class F, class = void>
struct DeclaresPairDifference : std::false_type {};
template <class F>
struct DeclaresPairDifference<F, std::void_t<decltype(F::kPairDifference)>>
    : std::bool_constant<F::kPairDifference> {};
template <class F, class = void>
struct DeclaresAffineEnergy : std::false_type {};
template <class F>
struct DeclaresAffineEnergy<F, std::void_t<decltype(F::kAffineEnergy)>>
    : std::bool_constant<F::kAffineEnergy> {};
template <class F, class = void>
struct DeclaresUniformGravity : std::false_type {};
template <class F>
struct DeclaresUniformGravity<F, std::void_t<decltype(F::kUniformGravity)>>
    : std::bool_constant<F::kUniformGravity> {};
template <class F, class = void>
struct HasResidualCurvature : std::false_type {};
template <class F>
struct HasResidualCurvature<F, std::void_t<decltype(std::declval<const F&>().ResidualCurvature(
                                   std::declval<const double* const*>(),
                                   std::declval<const double*>(), std::declval<double*>()))>>
    : std::true_type {};

class TermBuilder {
 public:
  // `effects`: those built so far (may be null: none).
  TermBuilder(const Scene& scene, const State& state, bool has_inertia,
              IncrementalPotential* potential, const EffectList* effects = nullptr)
      : scene_(scene),
        state_(state),
        has_inertia_(has_inertia),
        potential_(potential),
        effects_(effects) {}

  const Scene& scene() const { return scene_; }
  const State& state() const { return state_; }
  int dimension() const { return potential_->dimension(); }
  // False for the quasi-static integrator (no inertia term, no predictor).
  bool has_inertia() const { return has_inertia_; }
  // Stable pointer for functors that read per-step data (predictor, velocities).
  const StepContext* context() const { return &potential_->context(); }

  // Adds an autodiff term: Functor<D>(args...) with operator()(const T* x_node0,
  // ..., const T* x_nodeK, T* residual) and kNumResiduals residuals (or D of them
  // with kOneResidualPerCoordinate).
  template <template <int> class Functor, int kNumResiduals, size_t kNumNodes, typename... Args>
  void AddAutoDiff(TermKind kind, const std::array<int, kNumNodes>& nodes, Args&&... args) {
    Term term;
    if (dimension() == 2) {
      MakeAutoDiff<Functor<2>, kNumResiduals, 2>(std::make_index_sequence<kNumNodes>(), &term,
                                                 std::forward<Args>(args)...);
    } else {
      MakeAutoDiff<Functor<3>, kNumResiduals, 3>(std::make_index_sequence<kNumNodes>(), &term,
                                                 std::forward<Args>(args)...);
    }
    term.kind = kind;
    term.nodes.assign(nodes.begin(), nodes.end());
    Add(std::move(term));
  }

  // Adds any cost function (analytic, numeric, autodiff) with optional loss.
  void Add(TermKind kind, std::vector<int> nodes, std::unique_ptr<ceres::CostFunction> cost,
           std::unique_ptr<ceres::LossFunction> loss = nullptr);
  // Adds a fully built term (its family is set here).
  void Add(Term term);

  // Hands a step filter (core/step_filter.h) to the potential, which owns it.
  void AddStepFilter(std::unique_ptr<StepFilter> filter) {
    potential_->AddStepFilter(std::move(filter));
  }
  IncrementalPotential* potential() const { return potential_; }

  // An effect built before this one, of exactly type T, or null. Declare it in
  // EffectInfo::needs so that it is built first.
  template <class T>
  T* FindEffect() const {
    return effects_ == nullptr ? nullptr : effects_->Find<T>();
  }

  // Family name recorded on the terms added from now on (the effect's name).
  void set_family(std::string family) { family_ = std::move(family); }

 private:
  // The autodiff cost function, and the same functor in extended precision.
  template <class F, int kNumResiduals, int kDim, size_t... Is, typename... Args>
  static void MakeAutoDiff(std::index_sequence<Is...>, Term* term, Args&&... args) {
    constexpr int kResiduals = kNumResiduals == kOneResidualPerCoordinate ? kDim : kNumResiduals;
    F functor(std::forward<Args>(args)...);
    term->cost = std::make_unique<ceres::AutoDiffCostFunction<F, kResiduals, ((void)Is, kDim)...>>(
        new F(functor));
    term->gauss_newton_model = DeclaresGaussNewtonModel<F>::value;
    term->pair_difference = DeclaresPairDifference<F>::value;
    term->affine_energy = DeclaresAffineEnergy<F>::value;
    term->uniform_gravity = DeclaresUniformGravity<F>::value;
    if constexpr (HasResidualCurvature<F>::value) {
      term->curvature = [functor](const double* const* x, const double* c, double* curvature) {
        return functor.ResidualCurvature(x, c, curvature);
      };
    }
    term->precise_residual = [functor](const double* const* x, long double* residuals) {
      long double xl[sizeof...(Is)][kDim];
      for (size_t b = 0; b < sizeof...(Is); ++b) {
        for (int k = 0; k < kDim; ++k) xl[b][k] = x[b][k];
      }
      return functor(static_cast<const long double*>(xl[Is])..., residuals);
    };
  }

  const Scene& scene_;
  const State& state_;
  bool has_inertia_;
  IncrementalPotential* potential_;
  const EffectList* effects_;
  std::string family_;
};

}  // namespace ipstep
