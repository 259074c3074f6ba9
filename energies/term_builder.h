// The interface an effect uses to add its energy terms to the incremental
// potential. A new energy is one templated functor (Ceres autodiff, templated on
// the dimension) plus one registration (energies/effect_registry.h); see
// docs/new_energy.md for a worked example.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <ceres/autodiff_cost_function.h>

#include "core/incremental_potential.h"
#include "core/state.h"
#include "problems/scene.h"

namespace ipstep {

// Pass as kNumResiduals for terms with one residual per coordinate (kDim of them).
constexpr int kOneResidualPerCoordinate = -1;

class TermBuilder {
 public:
  TermBuilder(const Scene& scene, const State& state, bool has_inertia,
              IncrementalPotential* potential)
      : scene_(scene), state_(state), has_inertia_(has_inertia), potential_(potential) {}

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
    std::unique_ptr<ceres::CostFunction> cost;
    if (dimension() == 2) {
      cost = MakeAutoDiff<Functor<2>, kNumResiduals, 2>(std::make_index_sequence<kNumNodes>(),
                                                        std::forward<Args>(args)...);
    } else {
      cost = MakeAutoDiff<Functor<3>, kNumResiduals, 3>(std::make_index_sequence<kNumNodes>(),
                                                        std::forward<Args>(args)...);
    }
    Add(kind, std::vector<int>(nodes.begin(), nodes.end()), std::move(cost));
  }

  // Adds any cost function (analytic, numeric, autodiff) with optional loss.
  void Add(TermKind kind, std::vector<int> nodes, std::unique_ptr<ceres::CostFunction> cost,
           std::unique_ptr<ceres::LossFunction> loss = nullptr);

  // Family name recorded on the terms added from now on (the effect's name).
  void set_family(std::string family) { family_ = std::move(family); }

 private:
  template <class F, int kNumResiduals, int kDim, size_t... Is, typename... Args>
  static std::unique_ptr<ceres::CostFunction> MakeAutoDiff(std::index_sequence<Is...>,
                                                           Args&&... args) {
    constexpr int kResiduals = kNumResiduals == kOneResidualPerCoordinate ? kDim : kNumResiduals;
    return std::make_unique<ceres::AutoDiffCostFunction<F, kResiduals, ((void)Is, kDim)...>>(
        new F(std::forward<Args>(args)...));
  }

  const Scene& scene_;
  const State& state_;
  bool has_inertia_;
  IncrementalPotential* potential_;
  std::string family_;
};

}  // namespace ipstep
