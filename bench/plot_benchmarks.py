#!/usr/bin/env python3
"""Plots and markdown tables from ipstep_bench CSV files (docs/benchmarks.md).

  plot_benchmarks.py work-precision RESULTS.csv --out docs/img
      work_precision.{png,svg}  error vs wall time per simulated second
      convergence.{png,svg}     error vs dt with fitted order
      iterations.{png,svg}      iterations per step by optimiser
      energy_drift.{png,svg}    max relative energy drift vs dt
  plot_benchmarks.py table RESULTS.csv [--baseline projected_newton] [--time min]
      markdown: iterations, ms per step (and per iteration), failed steps, error,
      time ratio to the baseline optimiser of the same scene/grid/integrator/dt
      (and tolerance, a column when there are several)
  plot_benchmarks.py scaling RESULTS.csv --out docs/img [--time min]
      scaling.{png,svg} and a markdown table with fitted exponents
  plot_benchmarks.py adaptive ADAPTIVE.csv... --out docs/img [--name adaptive_steps]
                    [--tune SCENE,TARGET,TUNE.csv]... [--cost wall|iterations]
      NAME.{png,svg}  error vs wall time, fixed h against --adaptive, one panel
                      per scene (bench/adaptive_steps.sh's CSV files); --tune draws
                      ipstep_tune's pick and the default for TARGET [m] on SCENE's panel;
                      --cost iterations: solver iterations (machine-independent) on x
  plot_benchmarks.py adaptive-table ADAPTIVE.csv...
      markdown: each --adaptive run against the cheapest fixed h (same integrator x
      optimiser, any solver tolerance) at most as far off, in iterations and wall time
  plot_benchmarks.py tune TUNE.csv --target E --out docs/img --name NAME
      NAME.{png,svg}  one ipstep_tune search (--tune_output): every run, the Pareto
                      front, the target, the pick and the default (bench/plot_accuracy.py)

--time: ms per step from the median of the timed runs (default) or from the
fastest one (min: on a shared machine, the run least disturbed by others).

Runs leave the plots when they diverged (status "diverged at step N": ipstep's
one rule, sim/divergence.h); the tables mark them.

Needs only matplotlib and the standard library: run it with the interpreter that
has matplotlib (Debian: /usr/bin/python3 with python3-matplotlib; a python3 from
pyenv or a virtualenv first on PATH may not have it).
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

try:
    import matplotlib
except ImportError:
    sys.exit(f"{sys.argv[0]}: matplotlib is not installed for {sys.executable}; install "
             "python3-matplotlib (tools/install_dependencies.sh) and run it with /usr/bin/python3")

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plot_accuracy  # noqa: E402

# CSV files written before ipstep_bench marked such runs "diverged" have status
# "ok" and a huge energy_drift (then |E - E0| / |E0|; now in the energy scales of
# sim/divergence.h, whose energy bound is the same 1e6).
DIVERGED_ENERGY_RATIO = 1e6


def number(text):
    try:
        value = float(text)
    except (TypeError, ValueError):
        return math.nan
    return value


def read(path, time="median"):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("dt", "tolerance", "wall_per_sim_s", "ms_per_step", "iterations_per_step",
                    "position_error", "energy_drift", "reference_error", "free_dofs",
                    "failed_steps", "grid_size", "steps", "steps_done", "wall_s_median",
                    "wall_s_min"):
            r[key] = number(r.get(key))
        if time == "min" and r["wall_s_median"] > 0:
            scale = r["wall_s_min"] / r["wall_s_median"]
            r["ms_per_step"] *= scale
            r["wall_per_sim_s"] *= scale
    return rows


def ok(r):
    return r["status"] == "ok" and r["steps_done"] == r["steps"]


def diverged(r):
    """The run diverged (sim/divergence.h; for old CSV files, the energy bound)."""
    if r["status"].startswith("diverged"):
        return True
    drift, error = r["energy_drift"], r["position_error"]
    return (drift == drift and not drift <= DIVERGED_ENERGY_RATIO) or error in (math.inf, -math.inf)


def usable(r):
    """Completed runs (possibly with failed steps) that have an error value and did not
    diverge."""
    if diverged(r):
        return False
    if r["optimizer"] == "none" and r["failed_steps"] > 0:
        return False  # explicit integrator blew up (forces not evaluable)
    return r["steps_done"] == r["steps"] and not r["status"].startswith(("error", "diverged",
                                                                          "timeout"))


def fit_slope(xs, ys):
    pts = [(math.log10(x), math.log10(y)) for x, y in zip(xs, ys) if x > 0 and y > 0]
    if len(pts) < 2:
        return math.nan
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    if sxx == 0:
        return math.nan
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def label_of(r):
    opt = r["optimizer"]
    return r["integrator"] if opt == "none" else f'{r["integrator"]} × {opt}'


def tightest_runs(sub):
    """The tightest tolerance among `sub` and its runs (plus explicit runs, which have
    no tolerance) grouped by integrator x optimiser label."""
    tight = min((r["tolerance"] for r in sub), default=math.nan)
    groups = defaultdict(list)
    for r in sub:
        if r["tolerance"] == tight or r["optimizer"] == "none":
            groups[label_of(r)].append(r)
    return tight, groups


# One way to write a figure (png and svg) for every plot.
save = plot_accuracy.save


def scene_name(r):
    g = int(r["grid_size"]) if r["grid_size"] == r["grid_size"] else 0
    return r["scene"] + (f" {g}²" if g > 0 else "")


def scene_grid(rows):
    scenes = []
    for r in rows:
        if scene_name(r) not in scenes:
            scenes.append(scene_name(r))
    cols = 2 if len(scenes) > 1 else 1
    nrows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(6.4 * cols, 4.6 * nrows), squeeze=False)
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    return scenes, fig, list(axes.flat)


STYLE = {}


def style(label):
    if label not in STYLE:
        colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        markers = "os^vDP*Xh<>"
        i = len(STYLE)
        STYLE[label] = (colors[i % len(colors)], markers[(i // len(colors) + i) % len(markers)])
    return STYLE[label]


def work_precision(rows, out):
    scenes, fig, axes = scene_grid(rows)
    for scene, ax in zip(scenes, axes):
        sub = [r for r in rows if scene_name(r) == scene and usable(r)
               and r["position_error"] > 0 and r["wall_per_sim_s"] > 0]
        tight = min((r["tolerance"] for r in sub), default=math.nan)
        groups = defaultdict(list)
        for r in sub:
            groups[label_of(r)].append(r)
        for label, runs in sorted(groups.items()):
            color, marker = style(label)
            line = sorted((r for r in runs if r["tolerance"] == tight or r["optimizer"] == "none"),
                          key=lambda r: r["dt"])
            ax.loglog([r["wall_per_sim_s"] for r in line], [r["position_error"] for r in line],
                      marker=marker, color=color, label=label)
            loose = [r for r in runs if r["tolerance"] != tight and r["optimizer"] != "none"]
            ax.loglog([r["wall_per_sim_s"] for r in loose], [r["position_error"] for r in loose],
                      marker=marker, color=color, linestyle="none", markerfacecolor="none")
        ax.set_title(f"{scene} (lines: tol {tight:g} m/s, hollow: looser)")
        ax.set_xlabel("wall time per simulated second [s]")
        ax.set_ylabel("final position error [m]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out, "work_precision")

    scenes, fig, axes = scene_grid(rows)
    for scene, ax in zip(scenes, axes):
        sub = [r for r in rows if scene_name(r) == scene and usable(r) and r["position_error"] > 0]
        tight, groups = tightest_runs(sub)
        for label, runs in sorted(groups.items()):
            runs.sort(key=lambda r: r["dt"])
            slope = fit_slope([r["dt"] for r in runs], [r["position_error"] for r in runs])
            color, marker = style(label)
            ax.loglog([r["dt"] for r in runs], [r["position_error"] for r in runs], marker=marker,
                      color=color, label=f"{label}: order {slope:.2f}")
        refs = [r["reference_error"] for r in sub if r["reference_error"] > 0]
        if refs:
            ax.axhline(max(refs), color="gray", linestyle=":", label="reference's own error")
        ax.set_title(f"{scene}: convergence (tol {tight:g} m/s)")
        ax.set_xlabel("time step dt [s]")
        ax.set_ylabel("final position error [m]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out, "convergence")

    scenes, fig, axes = scene_grid(rows)
    for scene, ax in zip(scenes, axes):
        sub = [r for r in rows if scene_name(r) == scene and r["optimizer"] != "none"
               and r["steps_done"] > 0]
        groups = defaultdict(list)
        for r in sub:
            groups[(r["optimizer"], r["tolerance"])].append(r["iterations_per_step"])
        keys = sorted(groups)
        values = [sum(groups[k]) / len(groups[k]) for k in keys]
        ax.bar(range(len(keys)), values, color=[style(k[0])[0] for k in keys])
        ax.set_xticks(range(len(keys)))
        ax.set_xticklabels([f"{k[0]}\ntol {k[1]:g}" for k in keys], fontsize=7)
        ax.set_yscale("log")
        ax.set_ylabel("iterations per step (mean over integrators, dt)")
        ax.set_title(scene)
        ax.grid(True, axis="y", which="both", alpha=0.3)
    save(fig, out, "iterations")

    scenes, fig, axes = scene_grid(rows)
    for scene, ax in zip(scenes, axes):
        sub = [r for r in rows if scene_name(r) == scene and usable(r) and r["energy_drift"] > 0]
        tight, groups = tightest_runs(sub)
        for label, runs in sorted(groups.items()):
            runs.sort(key=lambda r: r["dt"])
            color, marker = style(label)
            ax.loglog([r["dt"] for r in runs], [r["energy_drift"] for r in runs], marker=marker,
                      color=color, label=label)
        ax.set_title(f"{scene}: max |E - E0| / |E0|")
        ax.set_xlabel("time step dt [s]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    save(fig, out, "energy_drift")


def fmt(value, spec=".3g"):
    return "—" if value != value else format(value, spec)


def table(rows, baseline):
    base = {}
    for r in rows:
        if r["optimizer"] == baseline and r["steps_done"] == r["steps"]:
            base[(r["scene"], r["grid_size"], r["integrator"], r["dt"], r["tolerance"])] = r
    tolerances = len({r["tolerance"] for r in rows}) > 1
    print(f"| scene | DOFs | integrator | optimiser |" + (" tolerance |" if tolerances else "") +
          f" iterations/step | ms/step | ms/iteration "
          f"| × {baseline} (ms/step) | × {baseline} (iterations) | failed steps | worst residual "
          f"[m/s] | error [m] | status |")
    print("|---|---:|---|---|" + ("---:|" if tolerances else "") +
          "---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        b = base.get((r["scene"], r["grid_size"], r["integrator"], r["dt"], r["tolerance"]))
        done = r["steps_done"] == r["steps"]
        ratio = r["ms_per_step"] / b["ms_per_step"] if b and done else math.nan
        iratio = (r["iterations_per_step"] / b["iterations_per_step"]
                  if b and done and b["iterations_per_step"] > 0 else math.nan)
        per_it = (r["ms_per_step"] / r["iterations_per_step"]
                  if r["iterations_per_step"] > 0 else math.nan)
        status = r["status"] if len(r["status"]) < 60 else r["status"][:57] + "..."
        if diverged(r) and not status.startswith("diverged"):
            status = "diverged"
        print(f'| {scene_name(r)} | {int(r["free_dofs"])} | {r["integrator"]} | {r["optimizer"]} '
              + (f'| {fmt(r["tolerance"], "g")} ' if tolerances else '') +
              f'| {fmt(r["iterations_per_step"])} | {fmt(r["ms_per_step"])} | {fmt(per_it)} '
              f'| {fmt(ratio, ".2f")} | {fmt(iratio, ".2f")} | {int(r["failed_steps"])} '
              f'| {fmt(number(r["worst_residual"]), ".2g")} | {fmt(r["position_error"], ".2e")} '
              f'| {status} |')


def scaling(rows, out):
    groups = defaultdict(list)
    for r in rows:
        if r["steps_done"] > 0 and r["ms_per_step"] > 0:
            groups[r["optimizer"]].append(r)
    fig, ax = plt.subplots(figsize=(7, 5))
    print("| optimiser | " + " | ".join(["DOFs → ms/step (iterations/step)"]) +
          " | fitted exponent (ms/step ∝ DOFs^p) |")
    print("|---|---|---:|")
    for opt, runs in sorted(groups.items()):
        runs.sort(key=lambda r: r["free_dofs"])
        complete = [r for r in runs if r["steps_done"] == r["steps"]]
        slope = fit_slope([r["free_dofs"] for r in complete], [r["ms_per_step"] for r in complete])
        color, marker = style(opt)
        ax.loglog([r["free_dofs"] for r in complete], [r["ms_per_step"] for r in complete],
                  marker=marker, color=color, label=f"{opt}: p = {slope:.2f}")
        cells = ", ".join(f'{int(r["free_dofs"])} → {r["ms_per_step"]:.3g} '
                          f'({r["iterations_per_step"]:.3g})'
                          + ("" if r in complete else f' [{r["status"]}]') for r in runs)
        print(f"| {opt} | {cells} | {slope:.2f} |")
    ax.set_xlabel("free degrees of freedom (2D cloth)")
    ax.set_ylabel("ms per step")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out, "scaling")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mode", choices=["work-precision", "table", "scaling", "adaptive",
                                         "adaptive-table", "tune"])
    parser.add_argument("csv", nargs="+")
    parser.add_argument("--out", default="docs/img")
    parser.add_argument("--baseline", default="projected_newton")
    parser.add_argument("--time", choices=["median", "min"], default="median")
    parser.add_argument("--name", help="adaptive, tune: the plot's file name (no extension)")
    parser.add_argument("--tune", action="append", default=[], metavar="SCENE,TARGET,TUNE.csv",
                        help="adaptive: ipstep_tune's answer for TARGET [m] on SCENE's panel")
    parser.add_argument("--target", type=float, help="tune: the search's --target_error [m]")
    parser.add_argument("--cost", choices=["wall", "iterations"], default="wall",
                        help="adaptive: the x axis, wall time or solver iterations of a run")
    args = parser.parse_args()
    if args.mode == "adaptive":
        tunes = []
        for spec in args.tune:
            fields = spec.split(",")
            if len(fields) != 3 or not plot_accuracy.number(fields[1]) > 0:
                parser.error(f"--tune={spec}: give SCENE,TARGET,TUNE.csv with TARGET > 0")
            tunes.append((fields[0], float(fields[1]), fields[2]))
        plot_accuracy.adaptive(args.csv, args.out, args.name or "adaptive_steps", tunes,
                               args.cost)
        return
    if args.mode == "adaptive-table":
        plot_accuracy.adaptive_table(args.csv)
        return
    if args.mode == "tune":
        if len(args.csv) != 1 or not args.name or not (args.target and args.target > 0):
            parser.error("tune: give one TUNE.csv, --name and --target > 0")
        plot_accuracy.tune(args.csv[0], args.out, args.name, args.target)
        return
    rows = [r for path in args.csv for r in read(path, args.time)]
    if not rows:
        sys.exit(f"{args.csv}: no rows")
    if args.mode == "work-precision":
        work_precision(rows, args.out)
    elif args.mode == "table":
        table(rows, args.baseline)
    else:
        scaling(rows, args.out)


if __name__ == "__main__":
    main()
