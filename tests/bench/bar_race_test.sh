#!/usr/bin/env bash
# ctest bar_race: the harness of bench/quasi_static_bar/ (never timings): the
# mesh writer's Gmsh file loads in ipstep, the quasi-static and the
# backward-Euler step of a small bar converge, the CSV has their rows and the
# summary prints; with python3-dolfinx installed, FEniCSx's rows too and the
# two codes' tip displacements agree (exact Newton: to 1e-9 relative).
#   bar_race_test.sh IPSTEP SOURCE_DIR WORK_DIR
set -euo pipefail
ipstep=$1 source=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
IPSTEP_CONFIGS="projected_newton --num_threads=1" BE_SIZES=2 PYTHON=/usr/bin/python3 \
  bash "$source/bench/quasi_static_bar/run.sh" "$ipstep" "$work/race.csv" 2 1 > "$work/summary.txt"
/usr/bin/python3 - "$work/race.csv" << 'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
ipstep = [r for r in rows if r["code"] == "ipstep"]
assert sorted(r["mode"] for r in ipstep) == ["backward_euler", "quasi_static"], ipstep
assert all(r["converged"] == "1" and int(r["free_dofs"]) == 540 for r in ipstep), ipstep
fenicsx = [r for r in rows if r["code"] == "fenicsx" and r["config"] == "cholmod"]
for f in fenicsx:
    mine = next(r for r in ipstep if r["mode"] == f["mode"])
    difference = abs(float(mine["tip_uy"]) - float(f["tip_uy"])) / abs(float(f["tip_uy"]))
    assert difference < 1e-9, (f["mode"], difference)
print(f"{len(ipstep)} ipstep rows, {len(fenicsx)} FEniCSx cholmod rows checked")
PY
grep -q "^| quasi_static | 2 " "$work/summary.txt"
