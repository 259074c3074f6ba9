#!/usr/bin/env python3
"""The hard-case suite (problems/hard/README.md): runs the ipstep program on
each hard scene x integrator x optimiser and prints a markdown table of failed
steps, substepped steps, the energy change, the largest energy growth of a
converged step and the smallest contact distance.

  bench/hard_cases.py --ipstep build/apps/ipstep [--subset ci|full] [--jobs 2]
                      [--flags=--hessian_projection=abs]

Exit code 1 if a target does not hold (listed after the table):
  * every run exits with 0 (done) or 3 (a step failed even as substeps);
  * no converged step holds a non-finite energy, and none creates energy
    beyond the program's energy balance (its status would say so; checked
    here: energy_growth of converged steps finite);
  * with newton (the default optimiser), the feasible scenes (FEASIBLE below)
    fail at most 5 % of their steps;
  * every reject scene (problems/hard/reject/*.json: what cannot be a body)
    exits with 2 and one error line naming its file (both subsets).
Needs only the Python standard library.
"""
import argparse
import concurrent.futures
import csv
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
HARD = os.path.join(os.path.dirname(HERE), "problems", "hard")

# (label, scene, extra flags, integrators)
BOTH = ("backward_euler", "newmark")
CASES = [
    ("gap", "gap.json", [], BOTH),
    ("offset", "offset.json", [], BOTH),
    ("wedge", "wedge.json", [], BOTH),
    ("squeeze_fast", "squeeze_fast.json", [], BOTH),
    ("thrown_stack", "thrown_stack.json", [], BOTH),
    ("mass_ratio", "mass_ratio.json", [], BOTH),
    ("chain_quasi_static", "chain_quasi_static.json", [], ("quasi_static",)),
    ("drop k=1e2", "drop_soft.json", [], BOTH),
    ("drop k=1e8", "drop_stiff.json", [], BOTH),
    ("drop h=1e-6", "drop", ["--dt=1e-6", "--steps=200"], BOTH),
    ("drop h=0.1", "drop", ["--dt=0.1", "--steps=20"], BOTH),
    ("impact 60 m/s", "impact", [], BOTH),
    ("impact 300 m/s", "impact_300.json", [], BOTH),
    ("impact 1000 m/s", "impact_1000.json", [], BOTH),
    ("impact 1000 m/s, d_hat 1e-4", "impact_1000_dhat1e-4.json", [], BOTH),
    ("slope 2000 steps", "slope", ["--steps=2000"], BOTH),
    ("drop 2000 steps", "drop", ["--steps=2000"], BOTH),
    ("node_ceiling", "node_ceiling.json", [], BOTH),
    ("textbook_squash", "textbook_squash.json", ["--tolerance=1e-6"], BOTH),
    ("impact h=1e-3", "impact", ["--dt=1e-3", "--steps=300"], ("newmark",)),
    ("paddle", "paddle.json", [], BOTH),
    ("paddle_heavy", "paddle_heavy.json", [], BOTH),
    ("tilting_floor", "tilting_floor.json", [], BOTH),
    ("swing_3d", "swing_3d.json", [], BOTH),
]
# Scenes that can run through with the default optimiser (newton): at most
# 5 % failed steps (with every integrator, or the one named).
FEASIBLE = {"gap", "offset", "wedge", "squeeze_fast/backward_euler", "thrown_stack/backward_euler",
            "mass_ratio", "chain_quasi_static", "drop k=1e2", "drop k=1e8", "drop h=1e-6",
            "drop h=0.1", "impact 60 m/s", "impact 300 m/s", "impact 1000 m/s",
            "impact 1000 m/s, d_hat 1e-4", "slope 2000 steps", "drop 2000 steps", "node_ceiling",
            "textbook_squash", "paddle", "paddle_heavy/backward_euler", "tilting_floor", "swing_3d"}
CI = {"gap", "offset", "thrown_stack", "drop h=0.1", "impact 300 m/s", "node_ceiling",
      "textbook_squash", "paddle", "tilting_floor"}


REJECT = os.path.join(HARD, "reject")


def reject_scenes():
    return sorted(f for f in os.listdir(REJECT) if f.endswith(".json"))


def run_reject(ipstep, name):
    done = subprocess.run([ipstep, "--scene=" + os.path.join(REJECT, name), "--noprogress"],
                          capture_output=True, text=True, timeout=120)
    lines = (done.stdout + done.stderr).strip().splitlines()
    return {"name": name, "exit": done.returncode, "lines": lines}


def scene_path(scene):
    return os.path.join(HARD, scene) if scene.endswith(".json") else scene


def run(ipstep, label, scene, flags, integrator, optimizer, extra):
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.csv")
        command = [ipstep, "--scene=" + scene_path(scene), "--integrator=" + integrator,
                   "--optimizer=" + optimizer, "--on_failure=continue", "--noprogress",
                   "--stats=" + stats] + flags + extra
        done = subprocess.run(command, capture_output=True, text=True, timeout=1800)
        rows = []
        if os.path.exists(stats):
            with open(stats, newline="") as f:
                rows = list(csv.DictReader(f))
    return {"label": label, "integrator": integrator, "optimizer": optimizer,
            "exit": done.returncode, "rows": rows, "stderr": done.stderr.strip().splitlines()}


def number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def summarize(result):
    rows = result["rows"]
    steps = len(rows)
    failed = sum(r["converged"] != "1" for r in rows)
    substepped = sum(r["substeps"] != "1" for r in rows)
    energies = [number(r["total_energy"]) for r in rows]
    bad_converged = [r["step"] for r in rows if r["converged"] == "1" and not (
        math.isfinite(number(r["total_energy"])) and math.isfinite(number(r["energy_growth"])))]
    growth = max((number(r["energy_growth"]) for r in rows if r["converged"] == "1"),
                 default=math.nan)
    distances = [number(r.get("min_distance")) for r in rows]
    distances = [d for d in distances if math.isfinite(d)]
    return {"steps": steps, "failed": failed, "substepped": substepped,
            "energy_change": energies[-1] - energies[0] if energies else math.nan,
            "growth": growth, "min_distance": min(distances) if distances else math.nan,
            "bad_converged": bad_converged}


def fmt(value):
    return "—" if value != value else "%.3g" % value


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ipstep", default="build/apps/ipstep")
    parser.add_argument("--subset", choices=["ci", "full"], default="full")
    parser.add_argument("--optimizers", default=None,
                        help="comma-separated (default: newton,lbfgs,projected_newton; ci: newton)")
    parser.add_argument("--jobs", type=int, default=1)
    parser.add_argument("--flags", default="",
                        help="extra ipstep flags for every run, e.g. --hessian_projection=abs")
    args = parser.parse_args()
    extra = args.flags.split()
    optimizers = (args.optimizers or ("newton" if args.subset == "ci" else
                                      "newton,lbfgs,projected_newton")).split(",")
    jobs = []
    for label, scene, flags, integrators in CASES:
        if args.subset == "ci" and label not in CI:
            continue
        for integrator in integrators:
            for optimizer in optimizers:
                jobs.append((args.ipstep, label, scene, flags, integrator, optimizer, extra))
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        results = list(pool.map(lambda job: run(*job), jobs))
    problems = []
    print("| scene | integrator | optimiser | exit | steps | failed | substepped | energy change [J] "
          "| largest growth of a converged step [J] | smallest distance [m] |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for result in results:
        s = summarize(result)
        print(f'| {result["label"]} | {result["integrator"]} | {result["optimizer"]} '
              f'| {result["exit"]} | {s["steps"]} | {s["failed"]} | {s["substepped"]} '
              f'| {fmt(s["energy_change"])} | {fmt(s["growth"])} | {fmt(s["min_distance"])} |')
        name = f'{result["label"]} / {result["integrator"]} / {result["optimizer"]}'
        if result["exit"] not in (0, 3):
            problems.append(f'{name}: exit code {result["exit"]}: '
                            + " ".join(result["stderr"][-1:]))
        if s["bad_converged"]:
            problems.append(f'{name}: converged steps with non-finite energy: '
                            f'{s["bad_converged"][:5]}')
        feasible = result["optimizer"] == "newton" and (
            result["label"] in FEASIBLE or f'{result["label"]}/{result["integrator"]}' in FEASIBLE)
        if feasible and s["failed"] > 0.05 * max(1, s["steps"]):
            problems.append(f'{name}: {s["failed"]} of {s["steps"]} steps failed (feasible scene)')
    print("\n| reject scene | exit | error |")
    print("|---|---:|---|")
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        rejects = list(pool.map(lambda name: run_reject(args.ipstep, name), reject_scenes()))
    for r in rejects:
        line = r["lines"][-1] if r["lines"] else ""
        print(f'| {r["name"]} | {r["exit"]} | `{line}` |')
        if r["exit"] != 2 or len(r["lines"]) != 1 or r["name"] + ": " not in line:
            problems.append(f'reject/{r["name"]}: exit {r["exit"]}, not one error line naming '
                            f'the file: {r["lines"][-3:]}')
    if problems:
        print("\nTargets not met:")
        for p in problems:
            print("  " + p)
        sys.exit(1)
    print(f"\nAll targets met ({len(results)} runs, {len(rejects)} reject scenes).")


if __name__ == "__main__":
    main()
