#!/usr/bin/env bash
# Adaptive against fixed steps (docs/benchmarks.md "Adaptive steps"): for each
# scene x integrator, fixed-h runs over a range of h and --adaptive runs over a
# range of --error_tolerance, each to the same end time; the final-position
# error (max over nodes) against a fixed-step run at h_ref, and the wall time
# of the run (the ipstep process). One CSV row per run. The reference is the
# exact solution for the oscillator, otherwise the trapezoidal rule (Newmark
# 1/4, 1/2; second order) at REF_DT with a tight tolerance for every
# integrator. Fixed runs keep the default --tolerance (1e-5 m/s), as a user
# who only changes --dt would; adaptive runs tie it to the error budget.
#   bench/adaptive_steps.sh BUILD_DIR OUT.csv
# Environment: SCENES ("oscillator:10 spring_pendulum:2 drop:1", scene:t_end),
# INTEGRATORS ("newmark backward_euler"), OPTIMIZERS ("newton"), DTS (the
# fixed steps, "0.1 0.03 0.01 0.003 0.001 0.0003" s), REF_DT (1e-5),
# REF_TOLERANCE (1e-9 m/s), FIXED_TOLERANCES (the solver tolerances of the
# fixed runs, "default": ipstep's 1e-5 m/s; e.g. "default 1e-8"), TOLERANCES
# ("1e-2 1e-3 1e-4 1e-5"; backward Euler stops at 1e-4: first order, 1e-5
# takes ~10^6-10^7 steps), MAX_SECONDS per run (120; a run cut there is a row
# with failed = timeout), ADAPTIVE_FLAGS (more flags for the adaptive runs,
# e.g. "--filter_stiff_modes=false"; none by default). Cost: the process's
# wall time and, independent of the machine, the solver iterations of the run
# (rejected attempts included).
set -euo pipefail
build=${1:?build directory}
out=${2:?output CSV}
ipstep="$build/apps/ipstep"
scenes=${SCENES:-"oscillator:10 spring_pendulum:2 drop:1"}
integrators=${INTEGRATORS:-"newmark backward_euler"}
optimizers=${OPTIMIZERS:-newton}
dts=${DTS:-"0.1 0.03 0.01 0.003 0.001 0.0003"}
ref_dt=${REF_DT:-1e-5}
ref_tolerance=${REF_TOLERANCE:-1e-9}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$(dirname "$out")"
fixed_tolerances=${FIXED_TOLERANCES:-default}
echo "scene,t_end,integrator,optimizer,mode,dt_or_tolerance,solver_tolerance,steps,failed,rejected,iterations,wall_s,position_error" > "$out"
error_of() {  # max node distance between two --positions files
  /usr/bin/python3 - "$1" "$2" <<'PY'
import sys
def load(path):
    rows = [line.strip().split(",") for line in open(path) if line[:1].isdigit()]
    return {int(r[0]): [float(v) for v in r[1:]] for r in rows}
a, b = load(sys.argv[1]), load(sys.argv[2])
print("%.6g" % max(sum((p - q) ** 2 for p, q in zip(a[k], b[k])) ** 0.5 for k in a))
PY
}
run() {  # scene integrator optimizer mode value solver_tolerance args...: appends a row
  local scene=$1 integrator=$2 optimizer=$3 mode=$4 value=$5 solver_tolerance=$6; shift 6
  local start end log
  start=$(date +%s.%N)
  local code=0
  log=$(timeout "${MAX_SECONDS:-120}" "$ipstep" --scene="$scene" --integrator="$integrator" --optimizer="$optimizer" --num_threads=1 --progress=false \
        --on_failure=continue --positions="$work/run.csv" "$@" 2>&1) || code=$?
  end=$(date +%s.%N)
  local done_line steps failed rejected per_step
  done_line=$(echo "$log" | grep '^done:' || echo "done: 0 steps, timeout failed")
  # ipstep stops at timeout's SIGTERM after its step and reports the steps
  # done (and writes the positions there): a row with failed = timeout.
  if [ "$code" = 124 ]; then done_line=$(echo "$done_line" | sed 's/[0-9]* failed/timeout failed/'); fi
  steps=$(echo "$done_line" | sed 's/done: \([0-9]*\) steps.*/\1/')
  failed=$(echo "$done_line" | sed 's/.* \([0-9a-z]*\) failed.*/\1/')
  rejected=$(echo "$done_line" | grep -o '[0-9]* rejected' | cut -d' ' -f1 || true)
  per_step=$(echo "$done_line" | grep -o '[0-9.]* iterations/step' | cut -d' ' -f1 || true)
  echo "$scene,$t_end,$integrator,$optimizer,$mode,$value,$solver_tolerance,$steps,$failed,${rejected:-0}," \
       "$(printf '%.0f' "$(echo "${per_step:-0} * $steps" | bc)"),$(echo "$end - $start" | bc)," \
       "$(error_of "$work/run.csv" "$work/ref_${scene//\//_}.csv")" | tr -d ' ' >> "$out"
  rm -f "$work/run.csv"
}
for entry in $scenes; do
  scene=${entry%%:*}; t_end=${entry##*:}
  if [ "$scene" = oscillator ]; then  # the exact solution x = 1 + 0.1 cos t
    /usr/bin/python3 -c "import math; print('node,x,y'); print('0,0,0'); \
print('1,%.17g,0' % (1 + 0.1 * math.cos($t_end)))" > "$work/ref_${scene//\//_}.csv"
  else
    ref_log=$("$ipstep" --scene="$scene" --integrator=newmark --dt="$ref_dt" --t_end="$t_end" \
      --tolerance="$ref_tolerance" --num_threads=1 --progress=false --on_failure=continue \
      --positions="$work/ref_${scene//\//_}.csv" 2>&1) || true
    # (a reference whose steps fail still has its positions; one that did not run has none)
    [ -s "$work/ref_${scene//\//_}.csv" ] || { echo "adaptive_steps: no reference for $scene" >&2; exit 1; }
    # Failed steps (a solve stalled below its tolerance, kept) make it a worse
    # reference: say so (drop at the default 1e-9 m/s: 5 of 100,000).
    ref_failed=$(echo "$ref_log" | grep '^done:' | sed 's/.* \([0-9]*\) failed.*/\1/')
    if [ "${ref_failed:-0}" != 0 ]; then
      echo "adaptive_steps: warning: the reference for $scene has $ref_failed failed steps" \
           "(REF_TOLERANCE=$ref_tolerance may be below the scene's precision floor)" >&2
    fi
  fi
  for integrator in $integrators; do
   for optimizer in $optimizers; do
    for fixed_tolerance in $fixed_tolerances; do
     tolerance_flag=()
     [ "$fixed_tolerance" = default ] || tolerance_flag=(--tolerance="$fixed_tolerance")
     for dt in $dts; do
      steps=$(echo "$t_end / $dt" | bc)
      [ "$steps" -ge 1 ] || continue
      run "$scene" "$integrator" "$optimizer" fixed "$dt" "${fixed_tolerance/default/1e-5}" \
        --dt="$(echo "scale=12; $t_end / $steps" | bc)" --t_end="$t_end" "${tolerance_flag[@]}"
     done
    done
    for tolerance in ${TOLERANCES:-1e-2 1e-3 1e-4 1e-5}; do
      if [ "$integrator" = backward_euler ] && [ "$tolerance" = 1e-5 ]; then continue; fi
      # shellcheck disable=SC2086 # ADAPTIVE_FLAGS: words
      run "$scene" "$integrator" "$optimizer" adaptive "$tolerance" tied --adaptive --error_tolerance="$tolerance" \
        --t_end="$t_end" ${ADAPTIVE_FLAGS:-}
    done
    echo "adaptive_steps: $scene $integrator $optimizer done" >&2
   done
  done
done
echo "wrote $out" >&2
