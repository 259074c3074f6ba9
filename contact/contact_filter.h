// The contact step filter (core/step_filter.h): keeps every iterate free of
// penetration and tunnelling, and reports min_distance / active_contacts /
// broad_phase_ms. It filters with the contact state's geometry
// (contact/contact_state.h, which the contact effect owns: the pairs, their
// terms, kappa, friction and the obstacles' time): IsStepValid and
// MaxStepSize are one time-of-impact sweep over every pair kind from the last
// accepted iterate at the current obstacle time, and the state check asks for
// no penetration and the obstacles at t_{n+1}. The step's other events
// (BeginStep, RefreshTerms, ProposeStart, StartRejected, PrescribedWork) are
// the state's, which the filter passes them to.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "contact/collision_mesh.h"
#include "contact/contact_state.h"
#include "contact/obstacle.h"
#include "core/step_filter.h"

namespace ipstep {

class ContactFilter : public StepFilter {
 public:
  static constexpr const char* kContactFamily = ContactState::kContactFamily;

  // `contact` must outlive the filter (the simulation owns both); `x0`: the
  // first accepted iterate (the initial positions).
  ContactFilter(ContactState* contact, Eigen::VectorXd x0);

  // StepFilter.
  void OnAccepted(const double* x) override;
  bool IsStepValid(const double* x) const override;
  double MaxStepSize(const double* from, const double* to) const override;
  bool IsFeasible(const double* x) const override;
  // Penetration at the obstacles' time, else a moving obstacle short of t_{n+1}.
  Infeasibility CheckState(const double* x) const override;
  // The staged obstacles' time (infinity without moving obstacles).
  double ReachedTime() const override;
  void BeginStep(const double* x_n) override;
  bool RefreshTerms(const double* x) override;
  bool ProposeStart(double* x) override;
  void StartRejected() override;
  std::vector<std::string> DiagnosticNames() const override;
  // min_distance [m], active_contacts, broad_phase_ms (the pair kinds' broad
  // phase since the step, or its last substep, began: PairSet::BroadPhaseSeconds).
  std::vector<double> Diagnostics(const double* x) const override;
  double PrescribedWork(const double* x_start, const double* x_end) override;

 private:
  ContactState* contact_;
  Eigen::VectorXd accepted_;
  double broad_phase_at_begin_ = 0.0;  // ContactState::BroadPhaseSeconds() at BeginStep [s]
};

}  // namespace ipstep
