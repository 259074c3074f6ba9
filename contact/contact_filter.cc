#include "contact/contact_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ipstep {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

}  // namespace

constexpr const char* ContactFilter::kContactFamily;

ContactFilter::ContactFilter(ContactState* contact, Eigen::VectorXd x0)
    : contact_(contact), accepted_(std::move(x0)) {}

void ContactFilter::OnAccepted(const double* x) {
  std::copy(x, x + accepted_.size(), accepted_.data());
}

bool ContactFilter::IsStepValid(const double* x) const {
  return contact_->Sweep(accepted_.data(), x, contact_->obstacle_time(),
                         contact_->obstacle_time()) > 1.0;
}

double ContactFilter::MaxStepSize(const double* from, const double* to) const {
  double t = std::clamp(
      contact_->Sweep(from, to, contact_->obstacle_time(), contact_->obstacle_time()), 0.0, 1.0);
  return contact_->ShrinkToClear(from, to, t);
}

bool ContactFilter::IsFeasible(const double* x) const {
  return CheckState(x) == Infeasibility::kNone;
}

StepFilter::Infeasibility ContactFilter::CheckState(const double* x) const {
  if (!contact_->FindPenetration(x, contact_->obstacle_time()).empty())
    return Infeasibility::kPenetration;
  // A moving obstacle that did not reach its position leaves the step infeasible.
  if (!contact_->obstacles_reached_end()) return Infeasibility::kBoundaryNotReached;
  return Infeasibility::kNone;
}

double ContactFilter::ReachedTime() const {
  return contact_->has_moving_obstacles() ? contact_->obstacle_time() : kInfinity;
}

void ContactFilter::BeginStep(const double* x_n) {
  broad_phase_at_begin_ = contact_->BroadPhaseSeconds();
  OnAccepted(x_n);
  contact_->BeginStep(x_n);
}

bool ContactFilter::RefreshTerms(const double* x) { return contact_->RefreshTerms(x); }

bool ContactFilter::ProposeStart(double* x) { return contact_->ProposeStart(x); }

void ContactFilter::StartRejected() { contact_->StartRejected(); }

double ContactFilter::PrescribedWork(const double* x_start, const double* x_end) {
  return contact_->PrescribedWork(x_start, x_end);
}

std::vector<std::string> ContactFilter::DiagnosticNames() const {
  return {"min_distance", "active_contacts", "broad_phase_ms"};
}

std::vector<double> ContactFilter::Diagnostics(const double* x) const {
  // The broad phase's time since the (last sub)step began, before Near adds its own.
  const double broad_phase_ms = 1e3 * (contact_->BroadPhaseSeconds() - broad_phase_at_begin_);
  double best = kInfinity;
  int count = 0;
  contact_->Near(x, contact_->d_hat(), &best, &count);
  return {std::isfinite(best) ? best : std::nan(""), static_cast<double>(count), broad_phase_ms};
}

}  // namespace ipstep
