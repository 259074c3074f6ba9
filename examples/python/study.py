#!/usr/bin/env python3
"""A study in Python (docs/python.md): which integrator and optimiser for the
built-in cloth, and what accuracy costs.

1. The comparison ipstep_compare prints (every integrator x optimiser at the
   scene's step, errors against a fine Newmark reference), from
   ipstep.compare: at --steps=20 it is `ipstep_compare --scene=cloth
   --steps=20`'s table, the same iterations and errors.
2. A work-precision sweep from ipstep.bench: 3 integrators x 3 optimisers x
   3 time steps to the same end time, errors against one reference, drawn as
   position error against wall time per simulated second (diverged runs left
   out) into OUTPUT (a .png; matplotlib's Agg backend).

Usage (from the repository root, after the build):
  PYTHONPATH=build/python /usr/bin/python3 examples/python/study.py study.png
  ... study.py --grid_size=6 --steps=3 small.png      (what ctest runs, < 20 s)
"""
import argparse
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import ipstep  # noqa: E402

INTEGRATORS = ["backward_euler", "newmark", "symplectic_euler"]
OPTIMIZERS = ["newton", "projected_newton", "lbfgs"]
DT_FACTORS = [1.0, 0.5, 0.25]


def table(records):
    """ipstep_compare's table, from compare's records."""
    lines = ["| integrator | optimizer | dt [s] | failed steps | iterations/step | ms/step | "
             "position error [m] | max energy drift [energy scales] |",
             "|---|---|---|---|---|---|---|---|"]
    for r in records:
        label = {"": "(explicit)", "projected_newton": "projected_newton (not Ceres)"}.get(
            r["optimizer"], r["optimizer"])
        if r["diverged_at"] > 0:
            error, drift = "diverged (step %d)" % r["diverged_at"], "diverged"
        else:
            error, drift = "%.3e" % r["position_error"], "%.3e" % r["max_energy_drift"]
        lines.append("| %s | %s | %g | %d | %.1f | %.3f | %s | %s |" % (
            r["integrator"], label, r["dt"], r["failed_steps"], r["iterations_per_step"],
            r["ms_per_step"], error, drift))
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("output", help="the work-precision plot (.png)")
    parser.add_argument("--grid_size", type=int, default=None, help="cloth nodes per side")
    parser.add_argument("--steps", type=int, default=20, help="steps at the scene's dt")
    args = parser.parse_args()

    scene = ipstep.load_scene("cloth", grid_size=args.grid_size)
    records = ipstep.compare(scene, steps=args.steps)
    print("scene %s: %d nodes, dt %g s, %d steps" % (scene.name, scene.num_nodes,
                                                     scene.time_step, args.steps))
    print("reference: %s\n" % records[0]["reference"])
    print(table(records))

    t_end = scene.time_step * args.steps
    sweep = ipstep.bench("cloth", integrators=INTEGRATORS, optimizers=OPTIMIZERS,
                         dts=[scene.time_step * f for f in DT_FACTORS], t_end=t_end,
                         grid_size=args.grid_size or 0, tolerance=1e-5)
    figure, axes = plt.subplots(figsize=(7, 5))
    for integrator in INTEGRATORS:
        for optimizer in OPTIMIZERS + ["none"]:
            rows = [r for r in sweep if r["integrator"] == integrator and
                    r["optimizer"] == optimizer and math.isfinite(r["position_error"]) and
                    r["status"] == "ok"]
            if not rows:
                continue
            rows.sort(key=lambda r: r["dt"])
            axes.loglog([r["wall_per_sim_s"] for r in rows], [r["position_error"] for r in rows],
                        "o-", label="%s + %s" % (integrator, optimizer))
    left_out = sum(1 for r in sweep if r["status"] != "ok")
    axes.set_xlabel("wall time per simulated second [s]")
    axes.set_ylabel("position error at t = %g s [m]" % t_end)
    axes.set_title("cloth (%d nodes): work-precision, dt x %s%s" % (
        scene.num_nodes, ", ".join("%g" % f for f in DT_FACTORS),
        "; %d runs left out (not ok)" % left_out if left_out else ""))
    axes.grid(True, which="both", alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(args.output, dpi=100)
    print("\n%d runs, %d drawn; plot: %s" % (len(sweep), len(sweep) - left_out, args.output))


if __name__ == "__main__":
    main()
