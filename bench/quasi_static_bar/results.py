#!/usr/bin/python3
"""CSV rows, the summary table and the agreement check of the bar race
(run.sh calls it; Python standard library only).

  results.py ipstep-row MESH STATS LOG POSITIONS --config C --mode M --n N
                        --repeat R --wall-seconds S
      one CSV row from an ipstep run: its --stats file, its output (stdout and
      stderr: the scene line gives the free nodes, the `done:` line the
      ms/step) and its --positions file; setup_seconds = process wall time -
      step time.
  results.py fenicsx-row JSON --n N --repeat R
      one CSV row from fenicsx_bar.py --json output.
  results.py compare MESH A.csv B.csv
      two --positions files (node,x,y,z) of the same mesh: tip u_y of each, their
      relative difference, the largest node distance.
  results.py summary OUT.csv [--positions DIR]
      per mode, size and configuration: min-max over the repeats of iterations
      and solve seconds, the ratio of the minimum time to FEniCSx cholmod's, and
      the tip displacement's relative difference to FEniCSx cholmod (with
      --positions also the largest node distance, from DIR/n{n}_{mode}_{slug}.csv).
  results.py slug TEXT
      the file-name form of a configuration (runs of other characters than
      letters and digits become '_').
"""
import argparse
import csv
import json
import math
import os
import re
import sys

COLUMNS = ["code", "config", "mode", "n", "free_dofs", "repeat", "iterations",
           "solve_seconds", "setup_seconds", "converged", "residual", "tip_uy"]
LENGTH = 2.0  # the bar's free end is the face x = LENGTH


def slug(text):
    return re.sub(r"[^A-Za-z0-9]+", "_", text).strip("_")


def read_msh_nodes(path):
    """Node coordinates of an MSH 2.2 ASCII file in file order (ipstep's node order)."""
    with open(path) as f:
        for line in f:
            if line.strip() == "$Nodes":
                count = int(next(f))
                return [tuple(float(v) for v in next(f).split()[1:4]) for _ in range(count)]
    raise ValueError("%s: no $Nodes section" % path)


def read_positions(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    rows.sort(key=lambda r: int(r["node"]))
    return [(float(r["x"]), float(r["y"]), float(r["z"])) for r in rows]


def displacements(rest, positions):
    if len(rest) != len(positions):
        raise ValueError("%d nodes in the mesh, %d in the positions" % (len(rest), len(positions)))
    return [tuple(p - q for p, q in zip(a, b)) for a, b in zip(positions, rest)]


def tip_uy(rest, disp):
    """Mean y-displacement of the nodes on the face x = LENGTH."""
    tip = [d[1] for r, d in zip(rest, disp) if abs(r[0] - LENGTH) < 1e-9]
    return sum(tip) / len(tip)


def compare(mesh, a, b):
    rest = read_msh_nodes(mesh)
    da, db = displacements(rest, read_positions(a)), displacements(rest, read_positions(b))
    ta, tb = tip_uy(rest, da), tip_uy(rest, db)
    largest = max(math.dist(p, q) for p, q in zip(da, db))
    max_u = max(math.hypot(*p) for p in da)
    return {"tip_uy_a": ta, "tip_uy_b": tb, "tip_relative": abs(ta - tb) / abs(ta),
            "max_node_distance": largest, "max_node_relative": largest / max_u}


def write_row(row):
    csv.writer(sys.stdout, lineterminator="\n").writerow([row[c] for c in COLUMNS])


def ipstep_row(args):
    with open(args.stats) as f:
        step = list(csv.DictReader(f))[-1]
    with open(args.log) as f:
        log = f.read()
    free = re.search(r"(\d+) free, dimension", log)
    done = re.search(r"done: .*?, ([0-9.]+) ms/step", log)
    solve_seconds = float(done.group(1)) / 1000.0 if done else float(step["wall_seconds"])
    rest = read_msh_nodes(args.mesh)
    try:
        tip = "%.15e" % tip_uy(rest, displacements(rest, read_positions(args.positions)))
    except (OSError, ValueError):
        tip = "nan"
    write_row({
        "code": "ipstep", "config": args.config, "mode": args.mode, "n": args.n,
        "free_dofs": 3 * int(free.group(1)) if free else "",
        "repeat": args.repeat, "iterations": step["iterations"],
        "solve_seconds": "%.6f" % solve_seconds,
        "setup_seconds": "%.6f" % (args.wall_seconds - solve_seconds),
        "converged": step["converged"], "residual": step["residual"], "tip_uy": tip,
    })


def fenicsx_row(args):
    with open(args.json) as f:
        r = json.load(f)
    write_row({
        "code": "fenicsx", "config": r["config"], "mode": r["mode"], "n": args.n,
        "free_dofs": r["free_dofs"], "repeat": args.repeat, "iterations": r["iterations"],
        "solve_seconds": "%.6f" % r["solve_seconds"], "setup_seconds": "%.6f" % r["setup_seconds"],
        "converged": int(r["converged"]), "residual": "%.6e" % r["residual"],
        "tip_uy": "%.15e" % r["tip_uy"],
    })


def span(values, fmt):
    lo, hi = min(values), max(values)
    return fmt % lo if fmt % lo == fmt % hi else (fmt + "-" + fmt) % (lo, hi)


def summary(args):
    with open(args.csv) as f:
        rows = [r for r in csv.DictReader(f)]
    groups = {}
    for r in rows:
        groups.setdefault((r["mode"], int(r["n"]), r["code"], r["config"]), []).append(r)
    print("| mode | n | free DOFs | code | config | converged | iterations | solve s (min-max) "
          "| setup s | / FEniCSx cholmod | tip u_y [m] | tip vs cholmod | max node distance |")
    print("|---|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for key in sorted(groups, key=lambda k: (k[0], k[1], k[2] != "fenicsx", k[2], k[3])):
        mode, n, code, config = key
        g = groups[key]
        times = [float(r["solve_seconds"]) for r in g]
        ref = groups.get((mode, n, "fenicsx", "cholmod"))
        ratio = tip_rel = distance = ""
        tip = [float(r["tip_uy"]) for r in g]
        if ref and not (code == "fenicsx" and config == "cholmod"):
            ratio = "%.2f" % (min(times) / min(float(r["solve_seconds"]) for r in ref))
            ref_tip = float(ref[0]["tip_uy"])
            tip_rel = "%.1e" % max(abs(t - ref_tip) / abs(ref_tip) for t in tip)
            if args.positions:
                distance = node_distance(args.positions, n, mode, code, config)
        converged = sum(int(r["converged"]) for r in g)
        print("| %s | %d | %s | %s | %s | %d/%d | %s | %s | %s | %s | %.9e | %s | %s |" % (
            mode, n, g[0]["free_dofs"], code, config, converged, len(g),
            span([int(r["iterations"]) for r in g], "%d"), span(times, "%.3f"),
            span([float(r["setup_seconds"]) for r in g], "%.2f"), ratio, tip[0], tip_rel, distance))


def node_distance(directory, n, mode, code, config):
    mesh = os.path.join(directory, "..", "bar_%d.msh" % n)
    a = os.path.join(directory, "n%d_%s_fenicsx_cholmod.csv" % (n, mode))
    b = os.path.join(directory, "n%d_%s_%s_%s.csv" % (n, mode, code, slug(config)))
    if not (os.path.exists(mesh) and os.path.exists(a) and os.path.exists(b)):
        return ""
    c = compare(mesh, a, b)
    return "%.1e m (%.1e)" % (c["max_node_distance"], c["max_node_relative"])


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("ipstep-row")
    for name in ("mesh", "stats", "log", "positions"):
        p.add_argument(name)
    p.add_argument("--config", required=True)
    p.add_argument("--mode", required=True)
    p.add_argument("--n", type=int, required=True)
    p.add_argument("--repeat", type=int, required=True)
    p.add_argument("--wall-seconds", type=float, required=True)
    p = sub.add_parser("fenicsx-row")
    p.add_argument("json")
    p.add_argument("--n", type=int, required=True)
    p.add_argument("--repeat", type=int, required=True)
    p = sub.add_parser("compare")
    for name in ("mesh", "a", "b"):
        p.add_argument(name)
    p = sub.add_parser("summary")
    p.add_argument("csv")
    p.add_argument("--positions", help="directory of the runs' --positions files")
    p = sub.add_parser("slug")
    p.add_argument("text")
    args = parser.parse_args()

    if args.command == "ipstep-row":
        ipstep_row(args)
    elif args.command == "fenicsx-row":
        fenicsx_row(args)
    elif args.command == "compare":
        c = compare(args.mesh, args.a, args.b)
        print("tip u_y: %.12e m (%s), %.12e m (%s); relative difference %.2e"
              % (c["tip_uy_a"], args.a, c["tip_uy_b"], args.b, c["tip_relative"]))
        print("largest node distance: %.3e m (%.2e of the largest |u|)"
              % (c["max_node_distance"], c["max_node_relative"]))
    elif args.command == "summary":
        summary(args)
    else:
        print(slug(args.text))


if __name__ == "__main__":
    main()
