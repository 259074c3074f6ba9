#!/usr/bin/env bash
# ctest plot_benchmarks: bench/plot_benchmarks.py on a sweep with diverged runs
# (symplectic Euler on the cloth: status "diverged at step N", and a row as
# CSV files from before that status have it: status ok, error 6e72, drift
# 1e300) leaves them out of the plots, marks them in its table and draws every
# plot. Exit code 77 (skipped) without an interpreter that has matplotlib.
#   plot_benchmarks_test.sh IPSTEP_BENCH SOURCE_DIR WORK_DIR
set -euo pipefail
bench=$1 source=$2 work=$3
python=""
for candidate in python3 /usr/bin/python3; do
  if "$candidate" -c 'import matplotlib' 2> /dev/null; then
    python=$candidate
    break
  fi
done
if [ -z "$python" ]; then
  echo "no python3 with matplotlib: skipped"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
"$bench" --scenes=cloth --grid_sizes=6 --integrators=newmark,symplectic_euler --optimizers=newton \
  --dt_factors=1,0.5 --steps=20 --repeats=1 --warmup=0 --output="$work/sweep.csv" 2> /dev/null
"$python" - "$source/bench" "$work" << 'PY'
import csv, os, sys
sys.path.insert(0, sys.argv[1])
work = sys.argv[2]
import plot_benchmarks as pb
rows = list(csv.DictReader(open(f"{work}/sweep.csv")))
legacy = dict(rows[-1], id="99", status="ok", position_error="6.4e+72", energy_drift="1e+300")
legacy["steps_done"] = legacy["steps"]
with open(f"{work}/with_legacy.csv", "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows + [legacy])
rows = pb.read(f"{work}/with_legacy.csv")
verdicts = [(r["integrator"], pb.diverged(r), pb.usable(r)) for r in rows]
assert verdicts == [("newmark", False, True)] * 2 + [("symplectic_euler", True, False)] * 3, verdicts
assert all(r["status"].startswith("diverged") for r in rows[2:4]), [r["status"] for r in rows]
pb.work_precision(rows, f"{work}/plots")
for name in ("work_precision", "convergence", "iterations", "energy_drift"):
    assert os.path.getsize(f"{work}/plots/{name}.png") > 0, name
print("diverged runs left out; every plot drawn")
PY
"$python" "$source/bench/plot_benchmarks.py" adaptive "$source/bench/results/adaptive_steps.csv" \
  --out "$work/plots" > /dev/null
test -s "$work/plots/adaptive_steps.png" || { echo "no adaptive_steps.png"; exit 1; }
# ipstep_tune's CSV (--tune_output): the front is the runs with an error and no
# failed step, by time, each more accurate than every cheaper one; the default
# and the validation are not runs of the search.
cat > "$work/tune.csv" << 'CSV'
integrator,optimizer,adaptive,dt,tolerance,error_tolerance,steps,failed,iterations,seconds,error,role
newmark,newton,0,0.2,1e-05,0,50,0,50,0.5,2e-3,search
newmark,newton,0,0.1,1e-05,0,100,0,99,1.0,4e-4,search
newmark,newton,0,0.05,1e-05,0,200,0,199,2.0,5e-4,search
newmark,newton,1,0.1,1e-06,1e-4,97,0,98,1.5,8e-5,pick
backward_euler,newton,0,0.1,1e-05,0,100,3,100,0.2,1e-5,search
backward_euler,newton,0,0.1,1e-05,0,100,0,100,0.1,nan,search
backward_euler,newton,0,0.1,1e-05,0,100,0,100,0.3,3e-2,default
newmark,newton,1,0.1,1e-06,1e-4,97,0,98,1.5,9e-5,validation
CSV
"$python" - "$source/bench" "$work" << 'PY'
import sys
sys.path.insert(0, sys.argv[1])
import plot_accuracy as pa
front = pa.pareto(pa.read_tune(f"{sys.argv[2]}/tune.csv"))
got = [(r["seconds"], r["error"], r["role"]) for r in front]
assert got == [(0.5, 2e-3, "search"), (1.0, 4e-4, "search"), (1.5, 8e-5, "pick")], got
print("the tune front")
PY
"$python" "$source/bench/plot_benchmarks.py" tune "$work/tune.csv" --target=1e-4 --name=tune \
  --out "$work/plots" > /dev/null
test -s "$work/plots/tune.png" || { echo "no tune.png"; exit 1; }
"$python" "$source/bench/plot_benchmarks.py" adaptive "$source/bench/results/adaptive_steps.csv" \
  --name=with_tune --tune="oscillator,1e-4,$work/tune.csv" --out "$work/plots" > /dev/null
test -s "$work/plots/with_tune.png" || { echo "no with_tune.png"; exit 1; }
# adaptive-table: each adaptive run against the cheapest fixed h of its
# integrator x optimiser that is at least as accurate (a failed run and another
# optimiser's cheaper one do not count).
cat > "$work/adaptive.csv" << 'CSV'
scene,integrator,optimizer,mode,dt_or_tolerance,solver_tolerance,steps,failed,rejected,iterations,wall_s,position_error
s,newmark,newton,fixed,0.01,1e-5,10,0,0,20,2.0,1e-3
s,newmark,newton,fixed,0.005,1e-7,20,0,0,40,1.0,2e-4
s,newmark,newton,fixed,0.001,1e-5,100,0,0,100,3.0,1e-4
s,newmark,newton,fixed,0.002,1e-5,50,2,0,10,0.1,1e-5
s,newmark,lbfgs,fixed,0.01,1e-5,10,0,0,5,0.1,1e-6
s,newmark,newton,adaptive,1e-3,tied,30,0,1,30,1.5,3e-4
s,newmark,newton,adaptive,1e-5,tied,300,0,1,300,9.0,5e-6
CSV
"$python" "$source/bench/plot_benchmarks.py" adaptive-table "$work/adaptive.csv" > "$work/adaptive.md"
grep -q '| s | newmark × newton | 1e-3 | 0.0003 (0.3) | 30 | 30 | 1.5 | 0.005, 1e-7, 40, 1 | 0.75, 1.50 |' \
  "$work/adaptive.md" || { cat "$work/adaptive.md"; exit 1; }
grep -q '| s | newmark × newton | 1e-5 | 5e-06 (0.5) | 300 | 300 | 9 | none reaches it | — |' \
  "$work/adaptive.md" || { cat "$work/adaptive.md"; exit 1; }
if "$python" "$source/bench/plot_benchmarks.py" adaptive "$source/bench/results/adaptive_steps.csv" \
  --tune="oscillator,0,$work/tune.csv" --out "$work/plots" 2> "$work/bad.txt"; then
  echo "--tune with target 0 should be an error"; exit 1
fi
grep -q -- "--tune=oscillator,0" "$work/bad.txt" || { cat "$work/bad.txt"; exit 1; }
"$python" "$source/bench/plot_benchmarks.py" table "$work/with_legacy.csv" > "$work/table.md"
if [ "$(grep -c '| diverged' "$work/table.md")" -ne 3 ]; then
  echo "the table should mark three runs diverged:"
  cat "$work/table.md"
  exit 1
fi
