#include "sim/simulation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>

#include <glog/logging.h>

#include "core/input_error.h"
#include "core/input_limits.h"
#include "sim/energy_balance.h"
#include "sim/prescribed_staging.h"

namespace ipstep {

void Simulation::ApplyBoundaryConditions(double t, Eigen::VectorXd* x) const {
  state_.PrescribedPositions(t, x);
}

bool Simulation::SolveStep(double h, Eigen::VectorXd* x, StepReport* report) {
  const double t_next = state_.time + h;
  std::unique_ptr<PrescribedStaging> staging;
  if (potential_->has_step_filters()) {
    // Start from a feasible point: free nodes move from x_n towards the guess only
    // as far as continuous collision detection allows (with a safety factor).
    Eigen::VectorXd start = state_.x;
    ApplyBoundaryConditions(t_next, &start);
    potential_->NotifyAccepted(state_.x.data());
    if (!potential_->IsStepValid(state_.x.data())) {
      // x_n itself is infeasible (at the filters' time, e.g. a moving obstacle's
      // first stage): only possible after a failed step was accepted.
      report->converged = false;
      report->status =
          "infeasible start: the state at the start of the step penetrates (after a "
          "failed step)";
      *x = state_.x;
      return false;
    }
    if (!potential_->IsStepValid(start.data())) {
      // The prescribed nodes cannot move to their targets at once: start from
      // the predictor when its path is free, else stage them
      // (sim/prescribed_staging.h).
      if (x->allFinite() && potential_->IsStepValid(x->data())) {
        start = *x;
      } else {
        staging = std::make_unique<PrescribedStaging>(state_, state_.x, start);
        *x = state_.x;
        if (!staging->Next(*potential_, x)) {
          report->converged = false;
          report->status =
              "moving boundary not reached: prescribed nodes touch at the start of their move";
          return false;
        }
      }
    }
    if (!staging) {
      const double t = potential_->MaxStepSize(start.data(), x->data());
      if (t < 1.0) *x = start + kFeasibleStartFraction * t * (*x - start);
    }
  }
  if (!x->allFinite()) {
    report->converged = false;
    report->status = "non-finite initial guess";
    return true;
  }
  for (int solve = 0;; ++solve) {
    const StepSolveResult result = solver_->Solve(x);
    report->converged = result.converged;
    report->status = result.status;
    report->iterations += result.iterations;
    report->evaluations += result.evaluations;
    report->residual = result.residual;
    if (!result.converged && options_.accept_residual > 0.0 &&
        result.residual <= options_.accept_residual &&
        (result.status.rfind("stalled", 0) == 0 ||
         result.status.rfind("iteration limit", 0) == 0)) {
      // Below the error budget (an adaptive run): accepted rather than making
      // the step smaller, which would not make the solve any more accurate.
      char text[120];
      std::snprintf(text, sizeof(text), "converged within the error budget: %.3g m/s (",
                    result.residual);
      report->converged = true;
      report->status = text + result.status + ")";
    }
    if (solve >= kMaxRefreshes) break;
    bool refreshed = false;
    for (const auto& filter : potential_->step_filters())
      refreshed |= filter->RefreshTerms(x->data());
    const Eigen::VectorXd solution = staging ? *x : Eigen::VectorXd();
    TakeProposedStart(x);
    if (staging && !staging->reached()) {
      if (!staging->Next(*potential_, x, &solution)) break;
      refreshed = true;
    }
    if (!refreshed) break;
  }
  if (staging && !staging->reached()) {
    char text[160];
    std::snprintf(text, sizeof(text),
                  "moving boundary not reached: prescribed nodes at %.3g %% of their move after "
                  "%d stages",
                  100.0 * staging->progress(), staging->stages());
    report->converged = false;
    report->status = text;
    return false;
  }
  return true;
}

void Simulation::TakeProposedStart(Eigen::VectorXd* x) {
  const auto& filters = potential_->step_filters();
  for (size_t k = 0; k < filters.size(); ++k) {
    Eigen::VectorXd proposal = *x;
    if (!filters[k]->ProposeStart(proposal.data())) continue;
    bool accepted = proposal.allFinite();
    for (size_t j = 0; j < filters.size() && accepted; ++j) {
      if (j == k) continue;
      filters[j]->OnAccepted(x->data());
      accepted = filters[j]->IsStepValid(proposal.data());
    }
    // The terms must be defined there too (a gap at the barrier's margin is not).
    double energy = 0.0;
    if (accepted) {
      potential_->NotifyAccepted(proposal.data());
      accepted = potential_->Evaluate(proposal.data(), &energy, nullptr);
    }
    if (accepted) {
      *x = proposal;
    } else {
      filters[k]->StartRejected();
    }
  }
}

bool Simulation::ImpulsiveForces(const Eigen::VectorXd& x, Eigen::VectorXd* forces) const {
  const StepContext& c = potential_->context();
  forces->setZero(x.size());
  bool any = false;
  Eigen::VectorXd gradient(x.size());
  for (TermKind kind : {TermKind::kPotential, TermKind::kDissipation}) {
    double energy = 0.0;
    int count = 0;
    const auto filter = [kind, &count](const Term& t) {
      const bool take = t.impulsive && t.kind == kind;
      count += take;
      return take;
    };
    if (!potential_->EvaluateUnweighted(filter, x.data(), &energy, gradient.data())) return false;
    if (count == 0) continue;
    *forces -= (TermWeight(kind, c) / c.potential_weight) * gradient;
    any = true;
  }
  return any;
}

std::vector<std::string> Simulation::DiagnosticNames() const {
  std::vector<std::string> names;
  for (const auto& filter : potential_->step_filters()) {
    for (const std::string& name : filter->DiagnosticNames()) names.push_back(name);
  }
  return names;
}

void Simulation::ReplaceStepSolver(const StepSolverFactory& factory) {
  if (!integrator_.variational) {
    throw std::logic_error(integrator().name() + " does not use a step solver");
  }
  solver_ = factory(potential_.get(), &state_);
}

const StepSolver& Simulation::step_solver() const {
  if (!solver_) throw std::logic_error(integrator().name() + " does not use a step solver");
  return *solver_;
}

void Simulation::set_iteration_sink(IterationSink sink) {
  if (solver_) solver_->set_iteration_sink(std::move(sink));
}

EnergyReport Simulation::Energies() const {
  EnergyReport report;
  if (!ComputeEnergies(*potential_, state_, gravity_, integrator().has_inertia(),
                       integrator().impulsive_energy_factor(), &report)) {
    report.kinetic = report.potential = std::nan("");
  }
  return report;
}

StepReport Simulation::Step() { return Step(time_step_); }

Simulation::Checkpoint Simulation::Save() const {
  return Checkpoint{state_, run_energy_, steps_taken_};
}

void Simulation::Restore(const Checkpoint& checkpoint) {
  state_ = checkpoint.state;
  run_energy_ = checkpoint.energy;
  steps_taken_ = checkpoint.steps_taken;
}

StepReport Simulation::Step(double h, bool retry_as_substeps) {
  const auto start = std::chrono::steady_clock::now();
  if (!(h >= limits::kMinTimeStep && h <= limits::kMaxTimeStep)) {
    throw InputError("options", "SimulationOptions.time_step",
                     "a step of " + limits::FormatLimit(h) + " s is outside " +
                         limits::RangeText(limits::kMinTimeStep, limits::kMaxTimeStep, "s"));
  }
  if (potential_->context().time_step != h) integrator().SetWeights(h, &potential_->context());
  StepReport report;
  report.step = ++steps_taken_;
  report.time_step = h;
  const Checkpoint saved = Save();
  Advance(h, &report);
  const int max_substeps = retry_as_substeps ? options_.max_substeps : 1;
  if (!report.converged && max_substeps > 1) report.retry_reason = report.status;
  // Retry a failed step as 2, 4, ... substeps from the same start.
  for (int substeps = 2; !report.converged && substeps <= max_substeps; substeps *= 2) {
    Restore(saved);
    const double h_sub = h / substeps;
    integrator().SetWeights(h_sub, &potential_->context());
    StepReport attempt;
    for (int k = 0; k < substeps && attempt.converged; ++k) {
      StepReport sub;
      Advance(h_sub, &sub);
      attempt.converged = sub.converged;
      attempt.status = sub.status;
      attempt.residual = sub.residual;
      attempt.iterations += sub.iterations;
      attempt.evaluations += sub.evaluations;
      attempt.energy_growth += sub.energy_growth;
      attempt.prescribed_work += sub.prescribed_work;
      attempt.energies = sub.energies;
    }
    integrator().SetWeights(h, &potential_->context());
    report.iterations += attempt.iterations;
    report.evaluations += attempt.evaluations;
    report.converged = attempt.converged;
    report.residual = attempt.residual;
    report.energy_growth = attempt.energy_growth;
    report.prescribed_work = attempt.prescribed_work;
    report.energies = attempt.energies;
    report.substeps = substeps;
    report.status = attempt.converged
                        ? "converged"
                        : attempt.status + " (also with " + std::to_string(substeps) + " substeps)";
  }
  // A step that failed in every attempt may end part-way (its last attempt
  // stopped after k of its substeps, or went back to a substep's start): the
  // time still advances by h, and the moving boundaries stay where that state
  // is free of them (a later step never starts inside an obstacle).
  const double t_end = saved.state.time + h;
  if (!report.converged) state_.boundary_lag += std::max(0.0, t_end - state_.time);
  state_.time = t_end;
  report.time = state_.time;
  report.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const auto& filter : potential_->step_filters()) {
    for (double value : filter->Diagnostics(state_.x.data())) report.diagnostics.push_back(value);
  }
  return report;
}

void Simulation::Advance(double h, StepReport* report) {
  const double t_next = state_.time + h;
  const int dim = state_.dimension;
  const VariationalIntegrator* variational = integrator_.variational.get();
  // The start, to go back to when the step ends inside an obstacle (only a
  // step filter can find one: no copy of the state without them).
  std::optional<State> start;
  if (potential_->has_step_filters()) start = state_;
  bool boundary_reached = true;  // the prescribed nodes reached their targets
  const bool prescribed_motion = state_.has_prescribed_motion();
  EnergyPoint energy_start;
  bool measured_start = false;  // variational steps with an energy tolerance
  if (variational) {
    Eigen::VectorXd x;
    variational->Predict(state_, gravity_, h, &potential_->context(), &x);
    // The energy balance starts before the filters' BeginStep, which report
    // what they change (PrescribedWork): sim/energy_balance.h.
    measured_start =
        options_.energy_tolerance > 0.0 &&
        MeasureEnergy(*potential_, state_, gravity_, integrator().has_inertia(),
                      integrator().impulsive_energy_factor(), prescribed_motion, &energy_start);
    ApplyBoundaryConditions(t_next, &x);
    for (const auto& filter : potential_->step_filters()) filter->BeginStep(state_.x.data());
    boundary_reached = SolveStep(h, &x, report);
    variational->Update(
        x, [this](const Eigen::VectorXd& at, Eigen::VectorXd* f) { return ImpulsiveForces(at, f); },
        h, &state_);
  } else {
    // The forces f(x_n, v_n), lagged terms (x_start) at x_n.
    potential_->context().x_start = state_.x;
    Eigen::VectorXd forces;
    if (!ComputeForces(potential_.get(), state_, gravity_, &forces)) {
      report->converged = false;
      report->status = "forces cannot be evaluated";
    } else {
      integrator_.explicit_integrator->Advance(forces, h, &state_);
    }
  }
  // Prescribed nodes whose staging ran out stay where it left them.
  if (boundary_reached) ApplyBoundaryConditions(t_next, &state_.x);
  state_.boundary_lag = 0.0;
  // One check of the new state for every integrator: explicit steps have no
  // step filter protecting them, and a variational step must also have
  // finished its filters' work (e.g. a moving obstacle's staged time).
  if (potential_->has_step_filters()) {
    potential_->NotifyAccepted(state_.x.data());
    const StepFilter::Infeasibility found = potential_->CheckState(state_.x.data());
    // A step that failed already keeps its own reason (e.g. "moving boundary
    // not reached: prescribed nodes ...").
    if (found == StepFilter::Infeasibility::kPenetration) {
      if (report->converged) report->status = "infeasible state after the step (penetration)";
      report->converged = false;
      // No later step may start inside an obstacle: back to the start (the
      // moving boundaries where they were then), time goes on.
      state_ = *start;
      state_.boundary_lag = start->boundary_lag + h;
      potential_->NotifyAccepted(state_.x.data());
    } else if (found == StepFilter::Infeasibility::kBoundaryNotReached && boundary_reached) {
      report->status =
          "moving boundary not reached: a moving obstacle's staging ran out" +
          (report->converged ? std::string() : " (last solve: " + report->status + ")");
      report->converged = false;
    }
    if (variational && found != StepFilter::Infeasibility::kPenetration) {
      // A state short of a moving obstacle's end time is free of it where it
      // got to: the next step starts the obstacles there.
      state_.boundary_lag = std::max(0.0, t_next - potential_->ReachedTime());
    }
  }
  state_.PrescribedVelocities(t_next, &state_.v);
  for (int i = 0; i < state_.num_nodes(); ++i) {
    if (!state_.is_free(i)) state_.a.segment(dim * i, dim).setZero();
  }
  state_.time = t_next;
  // The energies at the end, once: the report's and the balance's.
  EnergyPoint energy_end;
  const bool measured_end =
      measured_start &&
      MeasureEnergy(*potential_, state_, gravity_, integrator().has_inertia(),
                    integrator().impulsive_energy_factor(), prescribed_motion, &energy_end);
  report->energies = measured_end ? energy_end.energy : Energies();
  // The step that produces a non-finite number fails, whatever the integrator.
  if (report->converged && !(state_.x.allFinite() && state_.v.allFinite())) {
    report->converged = false;
    report->status = "non-finite state";
  } else if (report->converged && !std::isfinite(report->energies.total())) {
    report->converged = false;
    report->status = "non-finite energy";
  }
  if (!measured_end || !report->converged) return;
  double filter_work = 0.0;
  for (const auto& filter : potential_->step_filters()) {
    // Filters' terms are impulsive (contact): counted with the integrator's factor.
    filter_work += integrator().impulsive_energy_factor() *
                   filter->PrescribedWork(energy_start.x.data(), energy_end.x.data());
  }
  const EnergyBalance balance = BalanceOf(energy_start, energy_end, state_, gravity_, filter_work,
                                          options_.optimizer.tolerance / h);
  report->energy_growth = balance.growth();
  report->prescribed_work = balance.work;
  VLOG(2) << "energy balance: " << balance.Describe() << " start " << balance.start << " end "
          << balance.end << " work " << balance.work << " floor " << balance.floor;
  // Per step, and over the run: energy created a little at a time, each step
  // under the tolerance, adds up to the same.
  const RunEnergyBalance run = run_energy_.After(balance);
  if (balance.Exceeds(options_.energy_tolerance)) {
    report->converged = false;
    report->status = balance.Describe();
  } else if (run.Exceeds(options_.energy_tolerance)) {
    report->converged = false;
    report->status = run.Describe();
  }
  run_energy_ = run;
}

}  // namespace ipstep
