#!/bin/bash
# The bar race: ipstep against FEniCSx on the same mesh and stopping rule.
#
#   bench/quasi_static_bar/run.sh IPSTEP OUT.csv [SIZES] [REPEATS]
#
# IPSTEP   the ipstep binary, or a build directory holding apps/ipstep
#          ("" for the repository's build/apps/ipstep)
# OUT.csv  one row per run (README.md lists the columns); the meshes, scenes,
#          logs and final positions go to OUT_work/ next to it
# SIZES    values of n, the bar has (10n, n, n) cubes (default "3 7 10 14")
# REPEATS  runs of each configuration per size, interleaved (default 3)
#
# Environment:
#   IPSTEP_CONFIGS  ';'-separated ipstep configurations, each the flags after
#                   --optimizer= (default below)
#   BE_SIZES        sizes also run as one backward Euler step (default "10")
#   PYTHON          the interpreter with python3-dolfinx (default /usr/bin/python3)
#
# One process at a time, single-threaded: one MPI rank, OMP_NUM_THREADS=1 and
# OMP_THREAD_LIMIT=1 (Debian's CHOLMOD, under PETSc as under ipstep, runs
# OpenMP regions of a fixed 4 threads unless the limit caps them), ipstep
# with --num_threads=1 in the default configurations.
set -u

here=$(cd "$(dirname "$0")" && pwd)
ipstep=${1:-$here/../../build/apps/ipstep}
out=${2:?usage: run.sh IPSTEP OUT.csv [SIZES] [REPEATS]}
sizes=${3:-3 7 10 14}
repeats=${4:-3}
default_configs="newton --num_threads=1;projected_newton --num_threads=1"
default_configs="$default_configs;projected_newton --hessian_projection=when_indefinite --num_threads=1"
configs=${IPSTEP_CONFIGS:-$default_configs}
be_sizes=${BE_SIZES:-10}
python=${PYTHON:-/usr/bin/python3}
export OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 OPENBLAS_NUM_THREADS=1

if [ -d "$ipstep" ]; then
  if [ -x "$ipstep/apps/ipstep" ]; then ipstep=$ipstep/apps/ipstep; else ipstep=$ipstep/ipstep; fi
fi
if [ ! -x "$ipstep" ]; then
  echo "run.sh: no ipstep binary at $ipstep" >&2
  exit 2
fi
work=${out%.csv}_work
mkdir -p "$work/logs" "$work/positions"
results() { "$python" "$here/results.py" "$@"; }

have_fenicsx=1
if ! "$python" -c "import dolfinx" 2>/dev/null; then
  have_fenicsx=0
  echo "run.sh: python3-dolfinx is not importable with $python: NO FEniCSx rows," \
       "only ipstep's (install Debian's python3-dolfinx or set PYTHON)" >&2
fi

IFS=';' read -r -a config_list <<< "$configs"
columns=code,config,mode,n,free_dofs,repeat,iterations,solve_seconds,setup_seconds,converged
echo "$columns,residual,tip_uy" > "$out"

fenicsx_run() {  # n mode solver repeat
  local n=$1 mode=$2 solver=$3 r=$4
  local base=$work/logs/n${n}_${mode}_fenicsx_${solver}_r$r
  echo "  fenicsx $solver ($mode)" >&2
  if "$python" "$here/fenicsx_bar.py" "$work/bar_$n.msh" --mode "$mode" --solver "$solver" \
       --json --positions "$work/positions/n${n}_${mode}_fenicsx_${solver}.csv" \
       > "$base.json" 2> "$base.err"; then
    results fenicsx-row "$base.json" --n "$n" --repeat "$r" >> "$out"
  else
    echo "run.sh: FEniCSx $solver $mode n=$n failed, see $base.err" >&2
  fi
}

ipstep_run() {  # n mode config repeat
  local n=$1 mode=$2 config=$3 r=$4
  local tag
  tag=$(results slug "ipstep $config")
  local base=$work/logs/n${n}_${mode}_${tag}_r$r
  local positions=$work/positions/n${n}_${mode}_${tag}.csv
  echo "  ipstep $config ($mode)" >&2
  rm -f "$base.stats.csv" "$positions"
  local start end
  start=$(date +%s.%N)
  # $config unquoted on purpose: it is the optimiser and its flags.
  # shellcheck disable=SC2086
  "$ipstep" --scene="$work/bar_$n.json" --integrator="$mode" --optimizer=$config \
    --max_substeps=1 --noprogress --stats="$base.stats.csv" --positions="$positions" \
    > "$base.log" 2>&1
  local status=$?
  end=$(date +%s.%N)
  if [ -s "$base.stats.csv" ]; then
    results ipstep-row "$work/bar_$n.msh" "$base.stats.csv" "$base.log" "$positions" \
      --config "$config" --mode "$mode" --n "$n" --repeat "$r" \
      --wall-seconds "$(awk "BEGIN { print $end - $start }")" >> "$out"
  fi
  [ $status -eq 0 ] || echo "run.sh: ipstep exited $status ($config $mode n=$n), see $base.log" >&2
}

for n in $sizes; do
  "$python" "$here/make_mesh.py" "$n" "$work/bar_$n.msh" >&2 || exit 1
  "$python" "$here/bar_scene.py" "$work/bar_$n.msh" "$work/bar_$n.json" || exit 1
  modes=quasi_static
  for b in $be_sizes; do [ "$b" = "$n" ] && modes="quasi_static backward_euler"; done
  for r in $(seq 1 "$repeats"); do
    for mode in $modes; do
      echo "n=$n repeat $r/$repeats $mode" >&2
      if [ $have_fenicsx = 1 ]; then
        fenicsx_run "$n" "$mode" cholmod "$r"
        fenicsx_run "$n" "$mode" gamg "$r"
      fi
      for config in "${config_list[@]}"; do
        ipstep_run "$n" "$mode" "$config" "$r"
      done
    done
  done
done

echo
echo "$out. Ratio: the minimum solve time over FEniCSx cholmod's; tip: relative difference"
echo "of tip u_y to FEniCSx cholmod's; max node distance: to FEniCSx cholmod's final"
echo "positions (in brackets relative to its max |u|)."
results summary "$out" --positions "$work/positions"
