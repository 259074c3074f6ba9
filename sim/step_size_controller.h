// Error-controlled time steps: the step-size controller of an adaptive run
// (RunOptions::adaptive, sim/run_trajectory.h).
//
// The user asks for a position error `error_tolerance` [m] at the end time T.
// Each step of h gets the budget tol h / T (error per unit step: a global
// error that is the sum of the local ones stays within tol), and the
// integrator's local error estimate e of the smooth motion
// (Integrator::LocalError: an embedded pair, no extra solve) is compared with
// it, filtered through the step's own matrix so that modes the step does not
// resolve count by their amplitude (AdaptiveOptions::filter_stiff_modes,
// sim/stiff_mode_filter.h).
// An impact is an event, not smooth motion: the velocity change that the
// change of the contact forces causes in a step, dv_c = h M^-1 (f_c(x_{n+1}) -
// f_c(x_n)), puts the impact's time within the step, a position error
// e_c = h/2 |dv_c| whatever the step count, and resolving the barrier's own
// stiffness in time would take the steps to nothing (a 1000 kg square at
// 3 m/s against kappa = 1e5: 1e-9 s). So an impact gets an absolute budget,
// tol / 8 per step: a step whose e_c, or the share of the contact forces
// themselves, h^2/2 |M^-1 f_c(x_{n+1})|, is half its estimate or more is judged
// against max(tol h / T, tol / 8), and e_c itself against tol / 8. With
//   r = max(e / budget, e_c / (tol / 8)):
//   r <= 1  the step is accepted and the next one is
//           h' = h s r^(-0.7/p) r_prev^(0.4/p)   (PI control, Gustafsson 1991;
//                                                 p: the integrator's order)
//   r > 1   the step is rejected and retried from its start with
//           h' = h max(shrink, s r^(-1/p)),
// with safety s = 0.9, h'/h in [shrink 0.2, growth 2] (no growth right after a
// rejection) and h in [min_time_step, max_time_step]. A step whose solve fails
// (not converged, energy growth, penetration) is retried at h/4: the same
// controller replaces the programs' substeps. At min_time_step the step is
// taken whatever the estimate says (counted: RunSummary::over_budget) or
// reported failed. The solver's tolerance follows the budget: a stopping
// measure (a velocity error over one step) of 0.1 tol / T puts the solve's
// own position error at a tenth of every step's budget, and a stall at
// 0.5 tol / T is accepted rather than refined (SolverTolerance, StallResidual).
#pragma once

namespace ipstep {

struct AdaptiveOptions {
  double error_tolerance = 0.0;    // [m] at the end time; > 0
  double t_end = 0.0;              // [s] the end time T, from the start; > 0
  double initial_time_step = 0.0;  // [s]; 0: the simulation's time_step()
  double min_time_step = 0.0;      // [s]; 0: max(1e-12, 1e-9 T)
  double max_time_step = 0.0;      // [s]; 0: T / 10
  double safety = 0.9;
  double max_growth = 2.0;
  double max_shrink = 0.2;  // the smallest factor of a rejection
  // The local error estimate through the step's own matrix (M + c K)^-1 M e
  // (sim/stiff_mode_filter.h): modes the step does not resolve are judged by
  // their amplitude, not their acceleration.
  bool filter_stiff_modes = true;
};

// Throws InputError naming the option (AdaptiveOptions.error_tolerance, ...).
void ValidateAdaptiveOptions(const AdaptiveOptions& options);

// The solver tolerance [m/s] for an adaptive run, 0.1 tol / T, and the
// stopping measure at which a stalled solve is accepted, 0.5 tol / T.
double AdaptiveSolverTolerance(const AdaptiveOptions& options);
double AdaptiveStallResidual(const AdaptiveOptions& options);

class StepSizeController {
 public:
  // `order`: the integrator's order p >= 1.
  StepSizeController(const AdaptiveOptions& options, int order);

  double min_time_step() const { return min_h_; }
  double max_time_step() const { return max_h_; }
  // The error budget of a step of h [m] for the smooth motion, and of an
  // impact (the contact forces' change) in any one step.
  double Budget(double h) const;
  double ImpactBudget() const;

  struct Decision {
    bool accept = false;
    double next_time_step = 0.0;
    bool over_budget = false;  // accepted at the smallest step with the error over budget
  };
  // A step of h whose local error estimate is `error` [m], `impact_error` the
  // share of the contact forces' change in it, h/2 |dv_c|, and
  // `contact_error` that of the contact forces, h^2/2 |M^-1 f_c(x_{n+1})|.
  Decision Judge(double h, double error, double impact_error = 0.0, double contact_error = 0.0);
  // A step of h whose solve failed: retry at h / 4 (accept = false), or, at
  // the smallest step already, accept = true (the caller reports the failure).
  Decision Failed(double h);

 private:
  double Clamp(double h) const;
  AdaptiveOptions options_;
  int order_;
  double min_h_, max_h_;
  double previous_ratio_ = 1.0;
  bool after_rejection_ = false;
};

}  // namespace ipstep
