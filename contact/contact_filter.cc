#include "contact/contact_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "contact/pair_kinds.h"

namespace ipstep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Obstacles advance to this fraction of the way to their first impact.
constexpr double kObstacleAdvanceFraction = 0.8;
// Lagged closest points: re-lags per step, and the relative excess of the
// lagged gap over the true one that triggers one.
constexpr int kMaxLags = 3;
constexpr double kLagTolerance = 1e-2;

std::vector<bool> FreeNodes(const CollisionMesh& mesh, const State& state) {
  std::vector<bool> free;
  for (int node : mesh.nodes) free.push_back(state.is_free(node));
  return free;
}

// kappa_min's scale: a free contact node's inertia per unit weight in E / w_U.
AdaptiveKappa MakeKappa(const CollisionMesh& mesh, const std::vector<bool>& node_free,
                        const State& state, const StepContext& context,
                        const ContactOptions& options) {
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
  return AdaptiveKappa(options.kappa, stiffness, weight, options.d_hat);
}

}  // namespace

constexpr char ContactFilter::kContactFamily[];
constexpr char ContactFilter::kFrictionFamily[];

ContactFilter::ContactFilter(IncrementalPotential* potential, const State* state,
                             CollisionMesh mesh, ContactOptions options)
    : potential_(potential),
      state_(state),
      context_(&potential->context()),
      dim_(state->dimension),
      mesh_(std::move(mesh)),
      options_(std::move(options)),
      node_free_(FreeNodes(mesh_, *state)),
      margin_(1e-8 * options_.d_hat),
      kappa_(MakeKappa(mesh_, node_free_, *state, potential->context(), options_)),
      accepted_(state->x) {
  for (const Obstacle& o : options_.obstacles) has_moving_obstacles_ |= o.is_moving();
  PairSetContext c;
  c.dimension = dim_;
  c.num_coordinates = static_cast<int>(state->x.size());
  c.mesh = &mesh_;
  c.obstacles = &options_.obstacles;
  c.node_free = &node_free_;
  c.d_hat = options_.d_hat;
  c.margin = margin_;
  c.time = &tau_;
  c.kappa = kappa_.pointer();
  c.step = context_;
  c.barrier_family = kContactFamily;
  c.friction_family = kFrictionFamily;
  sets_ = MakePairSets(c, options_.self_contact, state->x.data());
  t_n_ = t_next_ = tau_ = state_->time;
}

void ContactFilter::EnableFriction(const FrictionOptions& options) {
  friction_enabled_ = true;
  friction_ = options;
}

int ContactFilter::num_barrier_pairs() const {
  size_t n = 0;
  for (const auto& set : sets_) n += set->size();
  return static_cast<int>(n);
}

std::string ContactFilter::Summary() const {
  std::ostringstream out;
  out << "contact: " << mesh_.nodes.size() << " contact nodes, " << options_.obstacles.size()
      << " obstacles";
  if (options_.self_contact) out << ", self-contact on " << mesh_.edges.size() << " edges";
  out << ", d_hat " << options_.d_hat << ", kappa ";
  if (kappa_.adaptive()) {
    out << "adaptive from " << kappa_.min();
  } else {
    out << kappa_.value();
  }
  return out.str();
}

std::vector<double> ContactFilter::ObstacleTravel() const {
  std::vector<double> travel;
  for (const Obstacle& o : options_.obstacles) {
    travel.push_back(o.velocity.norm() * std::max(0.0, t_next_ - tau_));
  }
  return travel;
}

double ContactFilter::Sweep(const double* a, const double* b, double t_a, double t_b) const {
  double first = PairSet::kNoImpact;
  for (const auto& set : sets_) {
    first = std::min(first, set->TimeOfImpact(a, b, t_a, t_b));
    if (first == 0.0) break;
  }
  return first;
}

std::string ContactFilter::FindPenetration(const double* x, double t) const {
  for (const auto& set : sets_) {
    std::string conflict = set->FindPenetration(x, t);
    if (!conflict.empty()) return conflict;
  }
  return "";
}

void ContactFilter::OnAccepted(const double* x) {
  std::copy(x, x + accepted_.size(), accepted_.data());
}

bool ContactFilter::IsStepValid(const double* x) const {
  return Sweep(accepted_.data(), x, tau_, tau_) > 1.0;
}

double ContactFilter::MaxStepSize(const double* from, const double* to) const {
  double t = std::clamp(Sweep(from, to, tau_, tau_), 0.0, 1.0);
  for (const auto& set : sets_) t = set->ShrinkToClear(from, to, t);
  return t;
}

bool ContactFilter::IsFeasible(const double* x) const {
  if (tau_ < t_next_) return false;  // a moving obstacle did not reach its position
  return FindPenetration(x, tau_).empty();
}

double ContactFilter::MinDistance(const double* x, double reach) const {
  double best = kInfinity;
  int count = 0;
  for (const auto& set : sets_) set->Near(x, tau_, reach, &best, &count);
  return best;
}

int ContactFilter::CountPairsWithin(const double* x, double reach) const {
  double best = kInfinity;
  int count = 0;
  for (const auto& set : sets_) set->Near(x, tau_, reach, &best, &count);
  return count;
}

std::vector<std::string> ContactFilter::DiagnosticNames() const {
  return {"min_distance", "active_contacts"};
}

std::vector<double> ContactFilter::Diagnostics(const double* x) const {
  double best = kInfinity;
  int count = 0;
  for (const auto& set : sets_) set->Near(x, tau_, options_.d_hat, &best, &count);
  return {std::isfinite(best) ? best : std::nan(""), static_cast<double>(count)};
}

bool ContactFilter::ExtendPairs(const CandidateRegion& region) {
  bool added = false;
  for (const auto& set : sets_) added |= set->Extend(region);
  return added;
}

void ContactFilter::RebuildBarrierTerms() {
  potential_->RemoveTerms(kContactFamily);
  for (const auto& set : sets_) set->AddBarrierTerms(potential_);
}

double ContactFilter::Lag(const double* x) {
  double excess = 0.0;
  for (const auto& set : sets_) excess = std::max(excess, set->Lag(x));
  return excess;
}

void ContactFilter::LagFriction(const double* x, double t) {
  if (!friction_enabled_ || !(friction_.mu > 0.0)) return;
  for (const auto& set : sets_) set->LagFriction(x, t);
}

void ContactFilter::RebuildFrictionTerms() {
  if (!friction_enabled_) return;
  potential_->RemoveTerms(kFrictionFamily);
  num_friction_contacts_ = 0;
  if (!(friction_.mu > 0.0)) return;
  const FrictionSettings settings{friction_.mu, friction_.epsilon_v};
  for (const auto& set : sets_)
    num_friction_contacts_ += set->AddFrictionTerms(settings, potential_);
}

void ContactFilter::AdvanceObstacles(const double* x) {
  if (!has_moving_obstacles_) {
    tau_ = t_next_;
    return;
  }
  const double first = Sweep(x, x, tau_, t_next_);
  if (first > 1.0) {
    tau_ = t_next_;
  } else {
    tau_ += kObstacleAdvanceFraction * first * (t_next_ - tau_);
  }
}

void ContactFilter::UpdateKappa(const double* x_n) {
  if (!kappa_.adaptive()) return;
  const int n = static_cast<int>(accepted_.size());
  const auto zero_fixed = [&](Eigen::VectorXd* g) {
    for (int i = 0; i < state_->num_nodes(); ++i) {
      if (!state_->is_free(i)) g->segment(dim_ * i, dim_).setZero();
    }
  };
  // g_B: gradient of sum_pairs w_U w_i B(d) (kappa = 1); g_E: of the rest of E.
  const auto barrier_gradient = [&](Eigen::VectorXd* g) {
    *g = Eigen::VectorXd::Zero(n);
    for (const auto& set : sets_) set->AddBarrierGradient(x_n, tau_, context_->potential_weight, g);
    zero_fixed(g);
  };
  const auto rest_gradient = [&](Eigen::VectorXd* g) {
    *g = Eigen::VectorXd::Zero(n);
    Eigen::VectorXd gradient(n);
    bool ok = true;
    for (TermKind kind : {TermKind::kInertia, TermKind::kPotential, TermKind::kDissipation}) {
      double energy = 0.0;
      ok &= potential_->EvaluateUnweighted(
          [kind](const Term& t) {
            return t.kind == kind && t.family != kContactFamily && t.family != kFrictionFamily;
          },
          x_n, &energy, gradient.data());
      if (ok) *g += TermWeight(kind, *context_) * gradient;
    }
    zero_fixed(g);
    return ok;
  };
  kappa_.Update(MinDistance(x_n, options_.d_hat), barrier_gradient, rest_gradient);
}

void ContactFilter::BeginStep(const double* x_n) {
  t_n_ = state_->time;
  t_next_ = t_n_ + context_->time_step;
  tau_ = t_n_;
  // The barrier energy at x_n before and after this step's stiffness and pairs
  // (for the energy balance: PrescribedWork).
  double energy_before = 0.0;
  const bool before_ok = BarrierEnergy(x_n, t_n_, &energy_before);
  OnAccepted(x_n);
  UpdateKappa(x_n);

  // Candidate pairs for this step: reach from the predictor's displacement.
  for (const auto& set : sets_) set->Clear();
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
  const std::vector<double> travel = ObstacleTravel();
  ExtendPairs(CandidateRegion{x_n, x_tilde.data(), &reach, max_reach, &travel});

  LagFriction(x_n, t_n_);
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
      before_ok && BarrierEnergy(x_n, t_n_, &energy_after) ? energy_after - energy_before : 0.0;
}

bool ContactFilter::BarrierEnergy(const double* x, double t, double* energy) {
  const double saved_tau = tau_;
  tau_ = t;
  const bool ok = potential_->EvaluateUnweighted(
      [](const Term& term) { return term.family == kContactFamily; }, x, energy, nullptr);
  tau_ = saved_tau;
  return ok;
}

double ContactFilter::PrescribedWork(const double* x_start, const double* x_end) {
  if (!has_moving_obstacles_ || !(t_next_ > t_n_)) return begin_energy_input_;
  const double h = t_next_ - t_n_, delta = 1e-6 * h;
  // dU_b/dt at fixed positions by central differences in the obstacle time.
  const auto rate = [&](const double* x, double t, double* value) {
    double up = 0.0, down = 0.0;
    if (!BarrierEnergy(x, t + delta, &up) || !BarrierEnergy(x, t - delta, &down)) return false;
    *value = (up - down) / (2.0 * delta);
    return true;
  };
  double at_start = 0.0, at_end = 0.0;
  const bool start_ok = rate(x_start, t_n_, &at_start);
  const bool end_ok = rate(x_end, t_next_, &at_end);
  double work = 0.0;
  if (start_ok && end_ok) {
    work = 0.5 * h * (at_start + at_end);
  } else if (start_ok || end_ok) {
    work = h * (start_ok ? at_start : at_end);
  }
  return begin_energy_input_ + work;
}

bool ContactFilter::RefreshTerms(const double* x) {
  bool changed = false;
  if (tau_ < t_next_) {
    AdvanceObstacles(x);
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
    const std::vector<double> reach(mesh_.nodes.size(), options_.d_hat);
    const std::vector<double> travel = ObstacleTravel();
    if (ExtendPairs(CandidateRegion{x, x, &reach, options_.d_hat, &travel})) {
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
    LagFriction(x, tau_);
    RebuildFrictionTerms();
    ++friction_lags_;
    changed = true;
  }
  return changed;
}

}  // namespace ipstep
