// A step filter keeps every iterate an optimiser accepts inside the feasible
// set (e.g. contact: no penetration, no tunnelling). Ceres has no hook to cap a
// step, so infeasibility is reported by failing the evaluation: the line search
// backtracks, the trust region shrinks (tests/contact/contact_scenes_test.cc
// checks every accepted iterate).
//
// Protocol, driven by the step solvers and the simulation:
//   OnAccepted(x)      the start point of every solve and every accepted iterate;
//   IsStepValid(x)     a trial point: false if x, or the straight path from the
//                      last accepted iterate to x, is infeasible;
//   MaxStepSize(a, b)  largest t in [0, 1] with the path a -> a + t (b - a)
//                      feasible (continuous collision detection), used to pull
//                      the initial guess back to a feasible start;
//   IsFeasible(x)      the state check after every step.
// Optional hooks (defaults do nothing):
//   CheckState(x)      the state check with its reason (Infeasibility; default
//                      from IsFeasible: penetration);
//   ReachedTime()      the time the filter's moving boundaries (e.g. a staged
//                      moving obstacle) reached in the step (infinity: none
//                      lags behind); a step whose state is kept short of the
//                      step's end time starts the next step from there
//                      (State::boundary_lag);
//   BeginStep(x_n)     before the predictor is pulled back, once per step
//                      (e.g. lag friction normal forces at the step start);
//   RefreshTerms(x)    after each solve of a step; return true if the filter
//                      changed the potential's terms (e.g. the contact set grew
//                      or friction was re-lagged): the step is solved again from x;
//   Diagnostics        named per-step values for the --stats CSV (NaN: empty);
//   ProposeStart(x)    after RefreshTerms: a start for the next solve that the
//                      filter's staging moved the free nodes to (written to x;
//                      true if proposed); the simulation takes it when every
//                      other filter accepts the path from the solution to it,
//                      else calls StartRejected (the filter stages without it);
//   PrescribedWork     energy the filter's own prescribed motions (e.g. moving
//                      obstacles) put into the potential over the step from
//                      x_start at the step's start time to x_end at its end,
//                      for the step's energy balance (sim/energy_balance.h),
//                      in units of its (impulsive, Term::impulsive) terms'
//                      energy, which the balance scales like those terms.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace ipstep {

class StepFilter {
 public:
  virtual ~StepFilter() = default;
  virtual void OnAccepted(const double* x) = 0;
  virtual bool IsStepValid(const double* x) const = 0;
  virtual double MaxStepSize(const double* from, const double* to) const = 0;
  virtual bool IsFeasible(const double* x) const = 0;

  // Why a state fails the check after a step.
  enum class Infeasibility {
    kNone,
    kPenetration,         // the state penetrates (or inverts, or tunnels)
    kBoundaryNotReached,  // free of it, but a moving boundary's staging ran out
  };
  virtual Infeasibility CheckState(const double* x) const {
    return IsFeasible(x) ? Infeasibility::kNone : Infeasibility::kPenetration;
  }
  virtual double ReachedTime() const { return std::numeric_limits<double>::infinity(); }

  virtual void BeginStep(const double* /*x_n*/) {}
  virtual bool RefreshTerms(const double* /*x*/) { return false; }
  virtual bool ProposeStart(double* /*x*/) { return false; }
  virtual void StartRejected() {}
  virtual std::vector<std::string> DiagnosticNames() const { return {}; }
  // Values in the order of DiagnosticNames(), at state positions x.
  virtual std::vector<double> Diagnostics(const double* /*x*/) const { return {}; }
  virtual double PrescribedWork(const double* /*x_start*/, const double* /*x_end*/) { return 0.0; }
};

}  // namespace ipstep
