// A step filter keeps every iterate an optimiser accepts inside the feasible
// set (e.g. contact: no penetration, no tunnelling). Ceres has no hook to cap a
// step, so infeasibility is reported by failing the evaluation: the line search
// backtracks, the trust region shrinks (../shared/design-notes.md).
//
// Protocol, driven by the step solvers and the simulation:
//   OnAccepted(x)      the start point of every solve and every accepted iterate;
//   IsStepValid(x)     a trial point: false if x, or the straight path from the
//                      last accepted iterate to x, is infeasible;
//   MaxStepSize(a, b)  largest t in [0, 1] with the path a -> a + t (b - a)
//                      feasible (continuous collision detection), used to pull
//                      the initial guess back to a feasible start;
//   IsFeasible(x)      the state check after every step.
#pragma once

namespace ipstep {

class StepFilter {
 public:
  virtual ~StepFilter() = default;
  virtual void OnAccepted(const double* x) = 0;
  virtual bool IsStepValid(const double* x) const = 0;
  virtual double MaxStepSize(const double* from, const double* to) const = 0;
  virtual bool IsFeasible(const double* x) const = 0;
};

}  // namespace ipstep
