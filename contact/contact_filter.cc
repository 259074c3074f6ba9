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
// Lagged closest points: re-lags per step, and the relative excess of the
// lagged gap over the true one that triggers one.
constexpr int kMaxLags = 3;
constexpr double kLagTolerance = 1e-2;

std::vector<bool> FreeNodes(const CollisionMesh& mesh, const State& state) {
  std::vector<bool> free;
  for (int node : mesh.nodes) free.push_back(state.is_free(node));
  return free;
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
      kappa_(AdaptiveKappa::ForMesh(mesh_, node_free_, *state, potential->context(), options_.kappa,
                                    options_.d_hat)),
      time_(&options_.obstacles, state->time),
      accepted_(state->x) {
  IndexNodeSlots(&mesh_);  // a mesh not from BuildCollisionMesh too
  PairSetContext c;
  c.dimension = dim_;
  c.num_coordinates = static_cast<int>(state->x.size());
  c.mesh = &mesh_;
  c.obstacles = &options_.obstacles;
  c.node_free = &node_free_;
  c.d_hat = options_.d_hat;
  c.margin = margin_;
  c.time = time_.pointer();
  c.kappa = kappa_.pointer();
  c.step = context_;
  barrier_group_ = potential_->NewTermGroup();
  friction_group_ = potential_->NewTermGroup();
  c.barrier = TermOwner{kContactFamily, barrier_group_};
  c.friction = TermOwner{kFrictionFamily, friction_group_};
  sets_ = MakePairSets(c, options_.self_contact, state->x.data(),
                       options_.self_contact_kappa > 0.0 ? &options_.self_contact_kappa : nullptr);
  // The pairs already within d_hat at x_0 and their barrier terms: the
  // initial energy (and Newmark's initial acceleration) include them. Every
  // step rebuilds its own pairs (BeginStep).
  const std::vector<double> no_reach(mesh_.nodes.size(), 0.0);
  const std::vector<double> no_travel(options_.obstacles.size(), 0.0);
  ExtendPairs(CandidateRegion{state->x.data(), state->x.data(), &no_reach, 0.0, &no_travel});
  Lag(state->x.data());
  RebuildBarrierTerms();
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
  out << (kappa_.adaptive() ? "adaptive from " : "")
      << (kappa_.adaptive() ? kappa_.min() : kappa_.value());
  if (options_.self_contact && options_.self_contact_kappa > 0.0) {
    out << ", self-contact kappa " << options_.self_contact_kappa;
  }
  return out.str();
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
  return Sweep(accepted_.data(), x, time_.tau(), time_.tau()) > 1.0;
}

double ContactFilter::MaxStepSize(const double* from, const double* to) const {
  double t = std::clamp(Sweep(from, to, time_.tau(), time_.tau()), 0.0, 1.0);
  for (const auto& set : sets_) t = set->ShrinkToClear(from, to, t);
  return t;
}

bool ContactFilter::IsFeasible(const double* x) const {
  return CheckState(x) == Infeasibility::kNone;
}

StepFilter::Infeasibility ContactFilter::CheckState(const double* x) const {
  if (!FindPenetration(x, time_.tau()).empty()) return Infeasibility::kPenetration;
  // A moving obstacle that did not reach its position leaves the step infeasible.
  if (!time_.reached_end()) return Infeasibility::kBoundaryNotReached;
  return Infeasibility::kNone;
}

double ContactFilter::ReachedTime() const {
  return time_.has_moving_obstacles() ? time_.tau() : kInfinity;
}

void ContactFilter::Near(const double* x, double reach, double* min_distance, int* count) const {
  *min_distance = kInfinity;
  *count = 0;
  for (const auto& set : sets_) set->Near(x, time_.tau(), reach, min_distance, count);
}

std::vector<std::string> ContactFilter::DiagnosticNames() const {
  return {"min_distance", "active_contacts", "broad_phase_ms"};
}

double ContactFilter::BroadPhaseSeconds() const {
  double total = 0.0;
  for (const auto& set : sets_) total += set->BroadPhaseSeconds();
  return total;
}

std::vector<double> ContactFilter::Diagnostics(const double* x) const {
  // The broad phase's time since the (last sub)step began, before Near adds its own.
  const double broad_phase_ms = 1e3 * (BroadPhaseSeconds() - broad_phase_at_begin_);
  double best = kInfinity;
  int count = 0;
  Near(x, options_.d_hat, &best, &count);
  return {std::isfinite(best) ? best : std::nan(""), static_cast<double>(count), broad_phase_ms};
}

bool ContactFilter::ExtendPairs(const CandidateRegion& region) {
  bool added = false;
  for (const auto& set : sets_) added |= set->Extend(region);
  return added;
}

void ContactFilter::RebuildBarrierTerms() {
  potential_->RemoveTerms(barrier_group_);
  for (const auto& set : sets_) set->AddBarrierTerms(potential_);
}

double ContactFilter::Lag(const double* x) {
  double excess = 0.0;
  for (const auto& set : sets_) excess = std::max(excess, set->Lag(x));
  return excess;
}

FrictionSettings ContactFilter::Friction() const {
  return FrictionSettings{friction_.mu, friction_.epsilon_v, options_.self_contact_mu};
}

bool ContactFilter::AnyFriction() const {
  if (!friction_enabled_) return false;
  const FrictionSettings settings = Friction();
  bool any = options_.self_contact && settings.ForSelf() > 0.0;
  for (const ObstaclePtr& o : options_.obstacles) any |= settings.ForObstacle(*o) > 0.0;
  return any;
}

void ContactFilter::LagFriction(const double* x, double t) {
  if (!AnyFriction()) return;
  for (const auto& set : sets_) set->LagFriction(x, t);
}

void ContactFilter::RebuildFrictionTerms() {
  if (!friction_enabled_) return;
  potential_->RemoveTerms(friction_group_);
  num_friction_contacts_ = 0;
  if (!AnyFriction()) return;
  const FrictionSettings settings = Friction();
  for (const auto& set : sets_)
    num_friction_contacts_ += set->AddFrictionTerms(settings, potential_);
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
    for (const auto& set : sets_)
      set->AddBarrierGradient(x_n, time_.tau(), context_->potential_weight, g);
    zero_fixed(g);
  };
  const auto rest_gradient = [&](Eigen::VectorXd* g) {
    const bool ok = GradientWithout(*potential_, {barrier_group_, friction_group_}, x_n, g);
    zero_fixed(g);
    return ok;
  };
  kappa_.Update(MinDistance(x_n, options_.d_hat), barrier_gradient, rest_gradient);
}

void ContactFilter::BeginStep(const double* x_n) {
  broad_phase_at_begin_ = BroadPhaseSeconds();
  time_.BeginStep(state_->time, context_->time_step, state_->boundary_lag);
  const double t_n = time_.t_n();
  // The barrier energy at x_n before and after this step's stiffness and pairs
  // (for the energy balance: PrescribedWork).
  double energy_before = 0.0;
  const bool before_ok = BarrierEnergy(x_n, t_n, &energy_before);
  OnAccepted(x_n);
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

bool ContactFilter::BarrierEnergy(const double* x, double t, double* energy) {
  double* tau = time_.pointer();
  const double saved_tau = *tau;
  *tau = t;
  const bool ok = potential_->EvaluateUnweighted(
      [this](const Term& term) { return term.group == barrier_group_; }, x, energy, nullptr);
  *tau = saved_tau;
  return ok;
}

bool ContactFilter::BarrierForces(const double* x, Eigen::VectorXd* forces) const {
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(state_->x.size());
  double energy = 0.0;
  if (!potential_->EvaluateUnweighted(
          [this](const Term& term) { return term.group == barrier_group_; }, x, &energy,
          gradient.data())) {
    return false;
  }
  *forces = -gradient;
  return true;
}

double ContactFilter::PrescribedWork(const double* x_start, const double* x_end) {
  // Friction against moving obstacles: the force F = -dR/dv = -(1/slope)
  // dR/dx at the step's end (its implicit value) does the work h F . u.
  double friction_work = 0.0, rate = 0.0;
  if (friction_enabled_ && context_->velocity_slope > 0.0 &&
      potential_->FrameDissipationRate(x_end, &rate)) {
    friction_work = -context_->time_step / context_->velocity_slope * rate;
  }
  return begin_energy_input_ + friction_work +
         time_.Work(x_start, x_end, static_cast<int>(accepted_.size()),
                    [this](const double* x, double t, double* energy) {
                      return BarrierEnergy(x, t, energy);
                    });
}

bool ContactFilter::RefreshTerms(const double* x) {
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
