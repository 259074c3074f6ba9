// The contact state's step (contact/contact_state.h, "Within a step"): the
// obstacle time, stiffness, candidate pairs, lags and terms set up at the
// step's start, and what changes after each solve.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "contact/contact_state.h"

namespace ipstep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Lagged closest points: re-lags per step, and the relative excess of the
// lagged gap over the true one that triggers one.
constexpr int kMaxLags = 3;
constexpr double kLagTolerance = 1e-2;

}  // namespace

void ContactState::BeginStep(const double* x_n) {
  time_.BeginStep(state_->time, context_->time_step, state_->boundary_lag);
  const double t_n = time_.t_n();
  // The barrier energy at x_n before and after this step's stiffness and pairs
  // (for the energy balance: PrescribedWork).
  double energy_before = 0.0;
  const bool before_ok = BarrierEnergy(x_n, t_n, &energy_before);
  UpdateKappa(x_n);

  // Candidate pairs for this step: reach from the predictor's displacement.
  for (const auto& set : sets_) set->Clear();
  stage_solutions_.clear();
  stage_times_.clear();
  stages_ = 0;
  has_proposal_ = false;
  lags_ = 0;
  const Eigen::VectorXd& x_tilde = context_->x_tilde;
  std::vector<double> reach(mesh_.nodes.size());
  double max_reach = 0.0;
  for (size_t s = 0; s < mesh_.nodes.size(); ++s) {
    const int node = mesh_.nodes[s];
    double r2 = 0.0;
    for (int k = 0; k < dim_; ++k) {
      const double d = x_tilde[dim_ * node + k] - x_n[dim_ * node + k];
      r2 += d * d;
    }
    reach[s] = 2.0 * std::sqrt(r2);
    max_reach = std::max(max_reach, reach[s]);
  }
  // Quasi-static steps have no predictor: the solution may be anywhere (a body
  // in the air falls onto an obstacle within one step), so every pair with an
  // obstacle is a candidate (terms out of reach are exactly zero).
  if (!(context_->inertia_weight > 0.0)) std::fill(reach.begin(), reach.end(), kInfinity);
  const std::vector<double> travel = time_.Travel(RotationRadii(x_n, x_tilde.data(), max_reach));
  ExtendPairs(CandidateRegion{x_n, x_tilde.data(), &reach, max_reach, &travel});

  LagFriction(x_n, t_n);
  friction_lags_ = 1;
  AdvanceObstacles(x_n);
  Lag(x_n);
  // Terms that read lags point into them, refilled above.
  bool rebuild = false;
  for (const auto& set : sets_) rebuild |= set->ChangedSinceClear() || set->TermsReadLags();
  if (rebuild) RebuildBarrierTerms();
  RebuildFrictionTerms();
  double energy_after = 0.0;
  begin_energy_input_ =
      before_ok && BarrierEnergy(x_n, t_n, &energy_after) ? energy_after - energy_before : 0.0;
}

bool ContactState::RefreshTerms(const double* x) {
  bool changed = false;
  double moved = 0.0;  // the proposed start's largest coordinate change
  has_proposal_ = false;
  if (!time_.reached_end()) {
    moved = AdvanceObstaclesAlongSecant(x);
    changed = true;
  }
  // Pairs within d_hat of the solution that the set missed (with margin d_hat).
  bool missing = false;
  for (const auto& set : sets_) {
    if (set->Missing(x)) {
      missing = true;
      break;
    }
  }
  if (missing || changed) {
    const std::vector<double> reach(mesh_.nodes.size(), options_.d_hat + 2.0 * moved);
    const std::vector<double> travel =
        time_.Travel(RotationRadii(x, x, options_.d_hat + 2.0 * moved));
    if (ExtendPairs(CandidateRegion{x, x, &reach, options_.d_hat + 2.0 * moved, &travel})) {
      RebuildBarrierTerms();
      changed = true;
    }
  }
  // Lagged closest points: re-lag and solve again while a lag is more than 1 %
  // farther than the true closest point for a pair in reach (at most kMaxLags).
  bool reads_lags = false;
  for (const auto& set : sets_) reads_lags |= set->TermsReadLags();
  if (!changed && reads_lags && lags_ < kMaxLags) {
    for (const auto& set : sets_) set->SaveLags();
    if (Lag(x) > kLagTolerance) {
      ++lags_;
      changed = true;
    } else {
      for (const auto& set : sets_) set->RestoreLags();
    }
  }
  if (!changed && friction_enabled_ && friction_lags_ < friction_.iterations) {
    LagFriction(x, time_.tau());
    RebuildFrictionTerms();
    ++friction_lags_;
    changed = true;
  }
  return changed;
}

}  // namespace ipstep
