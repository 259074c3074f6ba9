// RunIpstep (apps/programs.h), the ipstep program: runs one scene with one
// integrator and one optimiser.
//   ipstep --scene=cloth --integrator=newmark --optimizer=lbfgs --steps=60 --stats=cloth.csv
// Exit codes: 0 success, 2 bad input (scene file or flag, an output path that
// cannot be written), 3 a step failed (also as substeps, --max_substeps) or the
// run diverged (sim/divergence.h), with --on_failure=stop, or an output could
// not be written (io/output_file.h); 130 / 143 interrupted by SIGINT / SIGTERM
// (apps/run_signals.h: the step in progress finishes, the files are closed).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>

#include <gflags/gflags.h>
#include <glog/logging.h>

#include "apps/command_line.h"
#include "apps/contact_flags.h"
#include "apps/option_flags.h"
#include "apps/program_main.h"
#include "apps/programs.h"
#include "apps/run_signals.h"
#include "apps/setup_progress.h"
#include "apps/solver_flags.h"
#include "core/input_error.h"
#include "core/input_limits.h"
#include "io/frame_writer.h"
#include "io/positions_writer.h"
#include "io/stats_writer.h"
#include "io/vtk_unstructured_grid.h"
#include "problems/scene_loader.h"
#include "problems/solid.h"
#include "sim/run_trajectory.h"
#include "sim/simulation.h"
#include "sim/simulation_option_table.h"
#include "sim/step_size_controller.h"

DEFINE_string(on_failure, "stop",
              "When a step fails (not converged, energy growth, penetration, non-finite) even "
              "after its substeps: stop (exit code 3) or continue");
// Help text of the flags that set a library option (and, where the program's
// default is the library's, the default): its option row (apps/option_flags.h).
DEFINE_int32(max_substeps, ipstep::kProgramMaxSubsteps, ipstep::ProgramFlagHelp("max_substeps"));
DEFINE_string(stats, "", "CSV file: one row per step");
DEFINE_string(iterations_log, "", "CSV file: one row per optimizer iteration");
DEFINE_string(positions, "", "CSV file: final node positions (node,x,y[,z])");
DEFINE_string(frames, "",
              "Directory for a ParaView time series: DIR/run.pvd with one .vtu per frame (body: "
              "a 3D solid's tetrahedra with J, energy density, von Mises stress; obstacles; a 3D "
              "solid's surface) at its simulated time; docs/paraview.md; tools/animate.py DIR "
              "OUT.gif or tools/render_frames.py (ParaView) draws it");
DEFINE_string(frames_format, "zlib",
              "With --frames: zlib (binary, compressed: the smallest files), raw (binary) or "
              "ascii (text, for diffs); docs/paraview.md");
DEFINE_string(frames_precision, "float32",
              "With --frames: float32 (points and fields to ~7 digits, ParaView's own default; "
              "smaller files) or float64 (exact doubles, for post-processing); docs/paraview.md");
DEFINE_int32(frame_every, 1, "Write a frame every N steps (with --frames), in [1, 10000000]");
DEFINE_bool(progress, true,
            "Progress on stderr: a line for runs longer than 3 s and, when stderr is a terminal "
            "or --progress is given, the set-up's phases (loading and meshing the scene, building "
            "the simulation, the first step's analysis) with their size and time");
DEFINE_bool(adaptive, false,
            "Error-controlled time steps to the end time (--t_end, default the scene's "
            "time_step x steps): each step's local error estimate within --error_tolerance x "
            "h / t_end, rejected steps retried smaller; --dt is the first step");
DEFINE_double(error_tolerance, 1e-3, ipstep::ProgramFlagHelp("error_tolerance"));
DEFINE_bool(filter_stiff_modes, ipstep::FlagDefault<bool>("filter_stiff_modes"),
            ipstep::ProgramFlagHelp("filter_stiff_modes"));
DEFINE_double(min_dt, ipstep::FlagDefault<double>("min_dt"), ipstep::FlagHelp("min_dt"));
DEFINE_double(max_dt, ipstep::FlagDefault<double>("max_dt"), ipstep::FlagHelp("max_dt"));

namespace ipstep {
namespace {

// The set-up lines (apps/setup_progress.h): every phase with an explicit
// --progress, phases longer than half a second when stderr is a terminal,
// none with --noprogress or otherwise.
double SetupDelay() {
  if (!FLAGS_progress) return -1.0;
  if (!FlagIsDefault("progress")) return 0.0;
  return isatty(STDERR_FILENO) ? 0.5 : -1.0;
}

std::string SceneSize(const Scene& scene) {
  std::string text = Thousands(scene.num_nodes()) + " nodes";
  if (scene.solid) {
    text +=
        ", " + Thousands(static_cast<long long>(scene.solid->mesh.elements.size())) + " elements";
  } else if (!scene.springs.empty()) {
    text += ", " + Thousands(static_cast<long long>(scene.springs.size())) + " springs";
  }
  return text;
}

int Run(const EffectRegistry& registry) {
  SimulationOptions options = SimulationOptionsFromFlags(registry);
  if (FLAGS_on_failure != "stop" && FLAGS_on_failure != "continue") {
    throw InputError("flag", "--on_failure",
                     "must be 'stop' or 'continue', got '" + ClipInput(FLAGS_on_failure) + "'");
  }
  options.max_substeps =
      CheckFlagRange("max_substeps", FLAGS_max_substeps, 1, limits::kMaxSubsteps,
                     std::to_string(kProgramMaxSubsteps) + " substeps; 1 is no retry");
  CheckFlagRange("frame_every", FLAGS_frame_every, 1, limits::kMaxSteps, "");
  VtkEncoding frames_format;
  if (!ParseVtkEncoding(FLAGS_frames_format, &frames_format)) {
    throw InputError(
        "flag", "--frames_format",
        "must be 'zlib', 'raw' or 'ascii', got '" + ClipInput(FLAGS_frames_format) + "'");
  }
  VtkPrecision frames_precision;
  if (!ParseVtkPrecision(FLAGS_frames_precision, &frames_precision)) {
    throw InputError(
        "flag", "--frames_precision",
        "must be 'float32' or 'float64', got '" + ClipInput(FLAGS_frames_precision) + "'");
  }
  SetupProgress setup("ipstep", SetupDelay());
  setup.Begin("loading scene " + ClipInput(FLAGS_scene));
  const Scene scene = LoadScene(FLAGS_scene, SceneLoadOptionsFromFlags(registry));
  setup.End(SceneSize(scene));
  CheckContactFlagsApply(scene);
  RunOptions run_options;
  if (FLAGS_adaptive) {
    AdaptiveOptions& adaptive = run_options.adaptive_options;
    run_options.adaptive = true;
    if (!FlagIsDefault("steps")) {
      throw InputError("flag", "--steps",
                       "an --adaptive run's steps follow from the error; "
                       "give the end time with --t_end");
    }
    const double dt = options.time_step > 0.0 ? options.time_step : scene.time_step;
    adaptive.t_end = options.t_end > 0.0 ? options.t_end : dt * scene.steps;
    if (!(adaptive.t_end > 0.0)) {
      throw InputError("flag", "--t_end", "an --adaptive run needs an end time > 0");
    }
    options.t_end = 0.0;  // the steps follow from the error, not from dt
    adaptive.initial_time_step = dt;
    // The ranges of AdaptiveOptionTable (sim/simulation_option_table.h).
    const auto checked = [](const char* name, double value) {
      const OptionRow<AdaptiveOptions>& row = *FindOption(AdaptiveOptionTable(), name);
      return CheckFlagRange(row.flag.c_str(), value, row.min, row.max, row.unit.c_str(), "",
                            row.min_open);
    };
    adaptive.error_tolerance = checked("error_tolerance", FLAGS_error_tolerance);
    if (!FlagIsDefault("min_dt")) adaptive.min_time_step = checked("min_time_step", FLAGS_min_dt);
    if (!FlagIsDefault("max_dt")) adaptive.max_time_step = checked("max_time_step", FLAGS_max_dt);
    adaptive.filter_stiff_modes = FLAGS_filter_stiff_modes;
    if (!FlagIsDefault("max_substeps")) {
      throw InputError("flag", "--max_substeps",
                       "an --adaptive run retries failed steps smaller itself");
    }
    // The solve's tolerance follows the error budget unless --tolerance says.
    ConfigureAdaptiveSimulation(adaptive, /*keep_tolerance=*/!FlagIsDefault("tolerance"), &options);
  } else {
    for (const char* flag : {"error_tolerance", "min_dt", "max_dt", "filter_stiff_modes"}) {
      if (!FlagIsDefault(flag)) {
        throw InputError("flag", std::string("--") + flag, "applies with --adaptive only");
      }
    }
  }
  setup.Begin("building the simulation");
  Simulation sim(scene, options);
  setup.End(Thousands(static_cast<long long>(sim.potential().terms().size())) + " terms, " +
            Thousands(static_cast<long long>(sim.state().num_free_nodes()) * scene.dimension) +
            " free DOFs");
  ValidateRunOptions(sim, run_options);  // before any output: one error line

  std::unique_ptr<StatsWriter> stats;
  std::unique_ptr<IterationLogWriter> iterations;
  std::unique_ptr<FrameWriter> frames;
  std::unique_ptr<PositionsFile> positions;
  if (!FLAGS_positions.empty()) {
    positions = std::make_unique<PositionsFile>(FLAGS_positions, "positions");
  }
  if (!FLAGS_stats.empty()) {
    stats = std::make_unique<StatsWriter>(FLAGS_stats, "stats", sim.DiagnosticNames());
  }
  if (!FLAGS_iterations_log.empty()) {
    iterations = std::make_unique<IterationLogWriter>(FLAGS_iterations_log, "iterations_log");
    sim.set_iteration_sink([&](const IterationRecord& r) { iterations->Write(r); });
  }
  if (!FLAGS_frames.empty()) {
    frames =
        std::make_unique<FrameWriter>(FLAGS_frames, sim, "frames", frames_format, frames_precision);
    frames->Write(0);
  }

  std::printf("scene %s (%s): %d nodes, %d free, dimension %d\n", scene.name.c_str(),
              scene.source.c_str(), sim.state().num_nodes(), sim.state().num_free_nodes(),
              scene.dimension);
  if (run_options.adaptive) {
    const AdaptiveOptions& adaptive = run_options.adaptive_options;
    std::printf(
        "integrator %s, optimizer %s, adaptive steps to t = %g s for an error of %g m "
        "(first dt %g s), tolerance %g m/s\n",
        sim.integrator().name().c_str(), OptimizerName(options.optimizer.optimizer), adaptive.t_end,
        adaptive.error_tolerance, adaptive.initial_time_step, options.optimizer.tolerance);
  } else {
    std::printf("integrator %s, optimizer %s, dt %g s, %d steps, tolerance %g m/s\n",
                sim.integrator().name().c_str(), OptimizerName(options.optimizer.optimizer),
                sim.time_step(), sim.steps(), options.optimizer.tolerance);
  }
  const bool variational = sim.variational_integrator() != nullptr;  // else explicit: no solver
  if (variational) {
    std::string solver = sim.step_solver().LinearSolverDescription();
    if (solver.empty()) solver = "no linear solver";
    if (UsesNewtonModel(options.optimizer.optimizer)) {
      solver = std::string("Hessian projection ") +
               HessianProjectionName(ResolveHessianProjection(options.optimizer)) + ", " + solver;
    }
    std::printf("solver: %s, %d threads\n", solver.c_str(), ThreadCount(options.optimizer));
  }
  std::printf("active effects:\n");
  if (sim.potential().context().inertia_weight > 0.0) {  // inertia terms (sim/simulation.h)
    std::printf("  inertia: %d terms\n", sim.potential().CountTerms(TermKind::kInertia));
  }
  for (const std::string& line : sim.effect_summaries()) std::printf("  %s\n", line.c_str());
  CheckStdout();  // a lost stdout stops the run before it starts

  const auto start = std::chrono::steady_clock::now();
  auto last_progress = start;
  bool progress_shown = false;
  run_options.stop_on_failure = FLAGS_on_failure == "stop";
  // With --on_failure=continue a diverged run goes on (its steps are "diverged").
  run_options.stop_on_divergence = run_options.stop_on_failure;
  run_options.before_step = [&](int step) {
    if (iterations) iterations->set_step(step);
    // The first step pays for the solver's analysis (the sparsity pattern's
    // ordering, Ceres's preprocessing).
    if (step == 1 && variational) {
      setup.Begin("step 1 (with the solver's first analysis)");
    }
  };
  // A failed write (OutputError) stops the run from here: exit code 3.
  run_options.after_step = [&](const StepReport& r) {
    if (r.step == 1) setup.End(std::to_string(r.iterations) + " iterations");
    if (stats) stats->Write(r);
    if (iterations) iterations->Flush();
    if (frames && r.step % FLAGS_frame_every == 0) frames->Write(r.step);
    VLOG(1) << "step " << r.step << " t=" << r.time << " iterations=" << r.iterations
            << " residual=" << r.residual << " E=" << r.energies.total() << " " << r.status;
    if (r.converged && r.substeps > 1) {
      std::fprintf(stderr, "%sstep %d (t = %g): %s; converged as %d substeps\n",
                   progress_shown ? "\n" : "", r.step, r.time, r.retry_reason.c_str(), r.substeps);
      progress_shown = false;
    }
    if (!r.converged) {
      const bool diverged = r.status.rfind("diverged", 0) == 0;
      if (diverged && r.status.find("after the divergence") != std::string::npos) {
        // Every later step of a diverged run (--on_failure=continue): in the stats only.
      } else if (diverged || !variational) {
        std::fprintf(stderr, "%sstep %d (t = %g): %s\n", progress_shown ? "\n" : "", r.step, r.time,
                     r.status.c_str());
      } else {
        std::fprintf(stderr, "%sstep %d (t = %g): %s after %d iterations, residual %.3g m/s\n",
                     progress_shown ? "\n" : "", r.step, r.time, r.status.c_str(), r.iterations,
                     r.residual);
      }
      progress_shown = false;
    }
    const auto now = std::chrono::steady_clock::now();
    if (FLAGS_progress && std::chrono::duration<double>(now - start).count() > 3.0 &&
        std::chrono::duration<double>(now - last_progress).count() > 1.0) {
      if (run_options.adaptive) {
        std::fprintf(stderr, "\rstep %d  t = %.4g/%.4g s  dt %.3g s  iterations %d   ", r.step,
                     r.time, run_options.adaptive_options.t_end, r.time_step, r.iterations);
      } else {
        std::fprintf(stderr, "\rstep %d/%d  t = %.4g s  iterations %d  residual %.2e   ", r.step,
                     sim.steps(), r.time, r.iterations, r.residual);
      }
      last_progress = now;
      progress_shown = true;
    }
  };
  RunSignals signals;
  run_options.interrupt = signals.flag();
  const RunSummary run = RunTrajectory(sim, run_options);
  if (progress_shown) std::fprintf(stderr, "\n");
  // The last finished step's positions; every file complete before the summary.
  if (positions) positions->Write(sim.state());
  if (stats) stats->Close();
  if (iterations) iterations->Close();
  if (run.termination == RunTermination::kInterrupted) {
    std::fprintf(stderr, "%s (%s)\n", run.message.c_str(), signals.name());
  } else if (run.termination != RunTermination::kCompleted) {
    std::fprintf(stderr, "stopping (--on_failure=stop): %s\n", run.message.c_str());
  }
  // "done: N steps" counts the steps taken; per step means per step taken.
  std::string ending;
  if (run.steps_done < run.steps_planned) {
    ending += ", stopped after " + std::to_string(run.steps_done) + " of " +
              std::to_string(run.steps_planned) + " steps";
  }
  if (run.diverged()) ending += ", diverged at step " + std::to_string(run.diverged_at);
  if (run.adaptive) {
    char text[160];
    std::snprintf(
        text, sizeof(text), "; adaptive: %d rejected, dt %.3g to %.3g s%s", run.rejected,
        run.min_time_step, run.max_time_step,
        run.over_budget > 0
            ? (", " + std::to_string(run.over_budget) + " over budget at the smallest dt").c_str()
            : "");
    ending += text;
  }
  std::printf("done: %d steps, %d failed, %d substepped, %.2f iterations/step, %.3f ms/step%s\n",
              run.steps_done, run.failed, run.substepped, run.iterations_per_step(),
              run.ms_per_step(), ending.c_str());
  std::printf(
      "energy: initial %.10g J, final %.10g J (kinetic %.6g, potential %.6g); largest "
      "drift %.3g energy scales (%.3g J)\n",
      run.initial_energies.total(), run.final_energies.total(), run.final_energies.kinetic,
      run.final_energies.potential, run.max_energy_drift, run.energy_scale);
  if (run.adaptive && run.contact_kappa_adaptive) {
    // The error tolerance holds for the barrier this run settled on; other
    // tolerances settle on others (docs/benchmarks.md "Contact accuracy").
    std::printf(
        "note: the contact stiffness adapted to kappa = %.3g; it follows the step, so runs at "
        "other error tolerances simulate other barriers: give --contact_kappa to compare them\n",
        run.contact_kappa);
  }
  if (run.termination == RunTermination::kInterrupted) return signals.exit_code();
  if (run.termination != RunTermination::kCompleted) return kStepFailureExitCode;
  return 0;
}

}  // namespace

int RunIpstep(int argc, char** argv, const EffectRegistry& registry) {
  return ProgramMain(
      argc, argv, ProgramName(argc, argv, "ipstep").c_str(),
      "ipstep --scene=NAME|FILE --integrator=... --optimizer=... [--dt --steps --stats ...]",
      [&registry] { return Run(registry); });
}

int RunIpstep(int argc, char** argv) { return RunIpstep(argc, argv, DefaultEffects()); }

}  // namespace ipstep
