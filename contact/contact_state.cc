#include "contact/contact_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include "contact/pair_kinds.h"

namespace ipstep {

namespace {

std::vector<bool> FreeNodes(const CollisionMesh& mesh, const State& state) {
  std::vector<bool> free;
  for (int node : mesh.nodes) free.push_back(state.is_free(node));
  return free;
}

}  // namespace

constexpr char ContactState::kContactFamily[];
constexpr char ContactState::kFrictionFamily[];

ContactState::ContactState(IncrementalPotential* potential, const State* state, CollisionMesh mesh,
                           ContactOptions options)
    : potential_(potential),
      state_(state),
      context_(&potential->context()),
      dim_(state->dimension),
      num_coordinates_(static_cast<int>(state->x.size())),
      mesh_(std::move(mesh)),
      options_(std::move(options)),
      node_free_(FreeNodes(mesh_, *state)),
      margin_(1e-8 * options_.d_hat),
      kappa_(AdaptiveKappa::ForMesh(mesh_, node_free_, *state, potential->context(), options_.kappa,
                                    options_.d_hat)),
      time_(&options_.obstacles, state->time) {
  IndexNodeSlots(&mesh_);  // a mesh not from BuildCollisionMesh too
  PairSetContext c;
  c.dimension = dim_;
  c.num_coordinates = num_coordinates_;
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

void ContactState::EnableFriction(const FrictionOptions& options) {
  friction_enabled_ = true;
  friction_ = options;
}

std::string ContactState::Summary() const {
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

double ContactState::Sweep(const double* a, const double* b, double t_a, double t_b) const {
  double first = PairSet::kNoImpact;
  for (const auto& set : sets_) {
    first = std::min(first, set->TimeOfImpact(a, b, t_a, t_b));
    if (first == 0.0) break;
  }
  return first;
}

double ContactState::ShrinkToClear(const double* from, const double* to, double t) const {
  for (const auto& set : sets_) t = set->ShrinkToClear(from, to, t);
  return t;
}

std::string ContactState::FindPenetration(const double* x, double t) const {
  for (const auto& set : sets_) {
    std::string conflict = set->FindPenetration(x, t);
    if (!conflict.empty()) return conflict;
  }
  return "";
}

void ContactState::Near(const double* x, double reach, double* min_distance, int* count) const {
  *min_distance = std::numeric_limits<double>::infinity();
  *count = 0;
  for (const auto& set : sets_) set->Near(x, time_.tau(), reach, min_distance, count);
}

double ContactState::BroadPhaseSeconds() const {
  double total = 0.0;
  for (const auto& set : sets_) total += set->BroadPhaseSeconds();
  return total;
}

bool ContactState::ExtendPairs(const CandidateRegion& region) {
  bool added = false;
  for (const auto& set : sets_) added |= set->Extend(region);
  return added;
}

void ContactState::RebuildBarrierTerms() {
  potential_->RemoveTerms(barrier_group_);
  for (const auto& set : sets_) set->AddBarrierTerms(potential_);
}

double ContactState::Lag(const double* x) {
  double excess = 0.0;
  for (const auto& set : sets_) excess = std::max(excess, set->Lag(x));
  return excess;
}

FrictionSettings ContactState::Friction() const {
  return FrictionSettings{friction_.mu, friction_.epsilon_v, options_.self_contact_mu};
}

bool ContactState::AnyFriction() const {
  if (!friction_enabled_) return false;
  const FrictionSettings settings = Friction();
  bool any = options_.self_contact && settings.ForSelf() > 0.0;
  for (const ObstaclePtr& o : options_.obstacles) any |= settings.ForObstacle(*o) > 0.0;
  return any;
}

void ContactState::LagFriction(const double* x, double t) {
  if (!AnyFriction()) return;
  for (const auto& set : sets_) set->LagFriction(x, t);
}

void ContactState::RebuildFrictionTerms() {
  if (!friction_enabled_) return;
  potential_->RemoveTerms(friction_group_);
  if (!AnyFriction()) return;
  const FrictionSettings settings = Friction();
  for (const auto& set : sets_) set->AddFrictionTerms(settings, potential_);
}

void ContactState::UpdateKappa(const double* x_n) {
  if (!kappa_.adaptive()) return;
  const auto zero_fixed = [&](Eigen::VectorXd* g) {
    for (int i = 0; i < state_->num_nodes(); ++i) {
      if (!state_->is_free(i)) g->segment(dim_ * i, dim_).setZero();
    }
  };
  // g_B: gradient of sum_pairs w_U w_i B(d) (kappa = 1); g_E: of the rest of E.
  const auto barrier_gradient = [&](Eigen::VectorXd* g) {
    *g = Eigen::VectorXd::Zero(num_coordinates_);
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

bool ContactState::BarrierEnergy(const double* x, double t, double* energy) {
  double* tau = time_.pointer();
  const double saved_tau = *tau;
  *tau = t;
  const bool ok = potential_->EvaluateUnweighted(
      [this](const Term& term) { return term.group == barrier_group_; }, x, energy, nullptr);
  *tau = saved_tau;
  return ok;
}

bool ContactState::BarrierForces(const double* x, Eigen::VectorXd* forces) const {
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

double ContactState::PrescribedWork(const double* x_start, const double* x_end) {
  // Friction against moving obstacles: the force F = -dR/dv = -(1/slope)
  // dR/dx at the step's end (its implicit value) does the work h F . u.
  double friction_work = 0.0, rate = 0.0;
  if (friction_enabled_ && context_->velocity_slope > 0.0 &&
      potential_->FrameDissipationRate(x_end, &rate)) {
    friction_work = -context_->time_step / context_->velocity_slope * rate;
  }
  return begin_energy_input_ + friction_work +
         time_.Work(x_start, x_end, num_coordinates_,
                    [this](const double* x, double t, double* energy) {
                      return BarrierEnergy(x, t, energy);
                    });
}

}  // namespace ipstep
