"""Accuracy plots of plot_benchmarks.py (docs/benchmarks.md): fixed h against
--adaptive per scene (bench/adaptive_steps.sh's CSV files), with ipstep_tune's
answer drawn on its scene's panel, and one ipstep_tune search (--tune_output):
every run, the Pareto front, the target, the pick and the default.

Needs matplotlib (plot_benchmarks.py sets the Agg backend before importing this).
"""
import csv
import math
import os
from collections import defaultdict

import matplotlib.pyplot as plt


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def scene_label(scene):
    """problems/self_contact/two_cloths_box.json -> two_cloths_box"""
    base = os.path.basename(scene)
    return base[:-5] if base.endswith(".json") else base


def save(fig, out, name):
    os.makedirs(out, exist_ok=True)
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, f"{name}.{ext}"), dpi=110, bbox_inches="tight")
    plt.close(fig)
    print(f"wrote {out}/{name}.png and .svg")


def read_tune(path):
    """An ipstep_tune --tune_output CSV, numbers parsed."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for key in ("dt", "tolerance", "error_tolerance", "steps", "failed", "iterations",
                    "seconds", "error"):
            r[key] = number(r.get(key))
        r["adaptive"] = r.get("adaptive") == "1"
        r.setdefault("role", "search")
    return rows


def pareto(rows):
    """The runs of the search with an error and no failed step, by cost, each more accurate
    than every cheaper one (ipstep_tune's front: apps/tune_program.cc)."""
    measured = [r for r in rows if r["role"] in ("search", "pick") and r["error"] == r["error"]
                and r["failed"] == 0]
    measured.sort(key=lambda r: r["seconds"])
    front, best = [], math.inf
    for r in measured:
        if r["error"] < best:
            best = r["error"]
            front.append(r)
    return front


def tune_label(r):
    what = (f'adaptive E = {r["error_tolerance"]:.3g} m' if r["adaptive"] else
            f'h = {r["dt"]:.3g} s, tol {r["tolerance"]:.2g}')
    return f'{r["integrator"]} × {r["optimizer"]}, {what}'


TUNE_LABELS = ("ipstep_tune pick", "default:", "target ")


def draw_tune(ax, rows, target, cost="wall", per=1.0):
    """ipstep_tune's pick (star) and the default (cross) on a cost-error axis (`cost`: wall,
    the run loop's seconds in ipstep_tune divided by `per`, or iterations)."""
    x = "seconds" if cost == "wall" else "iterations"

    def cost_of(r):  # the faster of its two runs (role timing: the same configuration again)
        again = [t[x] for t in rows if t["role"] == "timing" and all(
            t[k] == r[k] for k in ("integrator", "optimizer", "adaptive", "dt", "tolerance",
                                   "error_tolerance"))]
        return min([r[x]] + again) / (per if cost == "wall" else 1.0)

    for r in rows:
        if r["role"] == "pick":
            ax.loglog([cost_of(r)], [r["error"]], "*", color="black", markersize=14,
                      label=f"ipstep_tune pick for {target:.3g} m: {tune_label(r)}")
        elif r["role"] == "default" and r["error"] == r["error"]:
            ax.loglog([cost_of(r)], [r["error"]], "X", color="gray", markersize=9,
                      label=f"default: {tune_label(r)}")
    ax.axhline(target, color="black", linestyle=":", linewidth=1, label=f"target {target:.3g} m")


COLORS = {}


def color(label):
    """One colour per integrator x optimiser, the same in every panel."""
    if label not in COLORS:
        cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        COLORS[label] = cycle[len(COLORS) % len(cycle)]
    return COLORS[label]


def adaptive(paths, out, name="adaptive_steps", tunes=(), cost="wall"):
    """Work-precision of fixed against adaptive steps (bench/adaptive_steps.sh), one panel per
    scene over all `paths`; `tunes`: (scene, target, TUNE.csv), drawn on that scene's panel.
    Colour: integrator x optimiser; solid circles: fixed h at ipstep's default solver tolerance,
    dotted hollow circles: fixed h at another one, dashed squares: --adaptive. `cost`: wall (the
    run's wall time, per simulated second when every row has its t_end) or iterations (the run's
    solver iterations). A tune drawn on a panel must have run to that scene's end time."""
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    scenes = []
    for r in rows:
        if r["scene"] not in scenes:
            scenes.append(r["scene"])
    cols = min(len(scenes), 2 if len(scenes) == 4 else 3)
    nrows = (len(scenes) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 4.4 * nrows), squeeze=False)
    for ax in list(axes.flat)[len(scenes):]:
        ax.set_visible(False)
    # Wall time per simulated second when every row has its end time.
    per_second = cost == "wall" and all(number(r.get("t_end")) > 0 for r in rows)
    for ax, scene in zip(axes.flat, scenes):
        groups = defaultdict(list)
        t_end = 1.0
        for r in rows:
            error = number(r["position_error"])
            x = number(r["wall_s"] if cost == "wall" else r.get("iterations"))
            if per_second and r["scene"] == scene:
                t_end = number(r["t_end"])
                x /= t_end
            if r["scene"] == scene and error > 0 and x > 0 and r["failed"] == "0":
                tolerance = r.get("solver_tolerance") or "1e-5"
                tolerance = "tied" if r["mode"] == "adaptive" else tolerance
                key = (r["integrator"], r.get("optimizer") or "newton", r["mode"], tolerance)
                groups[key].append((x, error))
        for (integrator, optimizer, mode, tolerance), points in sorted(groups.items()):  # as run
            label = f"{integrator} × {optimizer}"
            if mode == "adaptive":
                style = dict(marker="s", linestyle="--")
                label += ", adaptive"
            elif number(tolerance) == 1e-5:
                style = dict(marker="o", linestyle="-")
                label += ", fixed h"
            else:
                style = dict(marker="o", linestyle=":", markerfacecolor="none")
                label += f", fixed h, tol {tolerance} m/s"
            ax.loglog([p[0] for p in points], [p[1] for p in points], color=color(
                f"{integrator} × {optimizer}"), label=label, **style)
        for tune_scene, target, path in tunes:
            if scene_label(tune_scene) == scene_label(scene):
                draw_tune(ax, read_tune(path), target, cost, t_end)
        ax.set_title(scene_label(scene) + (f" to t = {t_end:g} s" if per_second else ""))
        ax.set_xlabel("solver iterations of the run" if cost != "wall" else
                      "wall time per simulated second [s]" if per_second else
                      "wall time of the run [s]")
        ax.set_ylabel("final position error [m]")
        ax.grid(True, which="both", alpha=0.3)
    # One legend for the styles (the same in every panel) below the panels; each panel's own
    # for its ipstep_tune answer.
    styles = {}
    for ax in axes.flat:
        handles, labels = ax.get_legend_handles_labels()
        tune_items = [(h, l) for h, l in zip(handles, labels) if l.startswith(TUNE_LABELS)]
        if tune_items:
            ax.legend(*zip(*tune_items), fontsize=6, loc="lower left")
        for h, l in zip(handles, labels):
            if not l.startswith(TUNE_LABELS):
                styles.setdefault(l, h)
    labels = sorted(styles)
    fig.legend([styles[l] for l in labels], labels, loc="upper center", fontsize=7, ncol=3,
               bbox_to_anchor=(0.5, 0.0))
    fig.tight_layout()
    save(fig, out, name)


def tune(path, out, name, target):
    """One ipstep_tune search: every run with an error (hollow: with failed steps), the front,
    the target, the pick and the default."""
    rows = read_tune(path)
    fig, ax = plt.subplots(figsize=(7, 4.6))
    groups = defaultdict(list)
    for r in rows:
        if r["role"] in ("search", "pick") and r["error"] > 0 and r["seconds"] > 0:
            groups[(r["integrator"], r["optimizer"], r["adaptive"])].append(r)
    for (integrator, optimizer, is_adaptive), runs in sorted(groups.items()):
        ok = [r for r in runs if r["failed"] == 0]
        failed = [r for r in runs if r["failed"] != 0]
        line = ax.loglog([r["seconds"] for r in ok], [r["error"] for r in ok],
                         "s" if is_adaptive else "o", linestyle="none", alpha=0.7,
                         label=f'{integrator} × {optimizer}, {"adaptive" if is_adaptive else "fixed h"}')
        ax.loglog([r["seconds"] for r in failed], [r["error"] for r in failed],
                  "s" if is_adaptive else "o", linestyle="none", markerfacecolor="none",
                  color=line[0].get_color())
    front = pareto(rows)
    ax.step([r["seconds"] for r in front], [r["error"] for r in front], where="post",
            color="black", linewidth=1, label="Pareto front")
    draw_tune(ax, rows, target)
    ax.set_xlabel("wall time of the run [s] (pick and default: the faster of two runs)")
    ax.set_ylabel("final position error [m]")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    save(fig, out, name)
    return front


def read_adaptive(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows += list(csv.DictReader(f))
    for r in rows:
        r["optimizer"] = r.get("optimizer") or "newton"
        r["solver_tolerance"] = r.get("solver_tolerance") or ("tied" if r["mode"] == "adaptive"
                                                              else "1e-5")
        for key in ("position_error", "wall_s", "iterations", "steps"):
            r[key] = number(r.get(key))
    return [r for r in rows if r["failed"] == "0" and r["position_error"] > 0]


def cheapest_fixed(rows, run, cost):
    """The fixed-h run of `run`'s scene, integrator and optimiser (any solver tolerance) with the
    least `cost` (iterations or wall_s) among those at most as far off as `run`; None if none."""
    fixed = [r for r in rows if r["mode"] == "fixed" and r["position_error"] <= run["position_error"]
             and all(r[k] == run[k] for k in ("scene", "integrator", "optimizer"))]
    return min(fixed, key=lambda r: r[cost], default=None)


def adaptive_table(paths):
    """Markdown: each --adaptive run against the cheapest fixed h (same integrator x optimiser,
    any solver tolerance) that is at least as accurate, in iterations and in wall time."""
    rows = read_adaptive(paths)
    print("| scene | integrator × optimiser | E [m] | error [m] (÷ E) | steps | iterations | "
          "wall [s] | cheapest fixed h at ≤ that error: h [s], tol [m/s], iterations, wall [s] | "
          "adaptive ÷ fixed: iterations, wall |")
    print("|---|---|---:|---:|---:|---:|---:|---|---|")
    for run in rows:
        if run["mode"] != "adaptive":
            continue
        by_iterations = cheapest_fixed(rows, run, "iterations")
        by_wall = cheapest_fixed(rows, run, "wall_s")
        if by_iterations is None:
            fixed, ratio = "none reaches it", "—"
        else:
            fixed = (f'{by_iterations["dt_or_tolerance"]}, {by_iterations["solver_tolerance"]}, '
                     f'{by_iterations["iterations"]:.0f}, {by_wall["wall_s"]:.3g}')
            ratio = (f'{run["iterations"] / by_iterations["iterations"]:.2f}, '
                     f'{run["wall_s"] / by_wall["wall_s"]:.2f}')
        error, tolerance = run["position_error"], number(run["dt_or_tolerance"])
        print(f'| {scene_label(run["scene"])} | {run["integrator"]} × {run["optimizer"]} '
              f'| {run["dt_or_tolerance"]} | {error:.2g} ({error / tolerance:.2g}) '
              f'| {run["steps"]:.0f} | {run["iterations"]:.0f} | {run["wall_s"]:.3g} | {fixed} '
              f'| {ratio} |')
