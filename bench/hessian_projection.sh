#!/bin/bash
# projected_newton with --hessian_projection=always (every term's Hessian
# projected to PSD) against when_indefinite (the exact Hessian's step when the
# assembled sum is positive definite): failed and substepped steps,
# iterations and milliseconds per step, one markdown row per run
# (docs/benchmarks.md, "Hessian projection"). Backward Euler unless a run
# says otherwise, tolerance 1e-5 m/s, --max_substeps=8 --on_failure=continue.
#
#   bench/hessian_projection.sh BUILD_DIR [SOURCE_DIR]
#
# RUNS="..." in the environment replaces the default runs (one per line:
# the ipstep arguments after --optimizer).
set -euo pipefail
build=$1
source=${2:-$(cd "$(dirname "$0")/.." && pwd)}
default_runs="--scene=cloth
--scene=cloth --grid_size=40
--scene=hanging_square
--scene=hanging_square --grid_size=40
--scene=hanging_square --grid_size=80
--scene=squash_square
--scene=cantilever_2d
--scene=twisted_bar_3d
--scene=ball_impact_3d
--scene=squeeze
--scene=two_squares
--scene=cloth_box
--scene=cloth_sphere
--scene=$source/problems/self_contact/cloth_twist.json --steps=200
--scene=$source/problems/self_contact/cloth_twist.json --integrator=newmark --dt=0.001 --steps=790"
runs=${RUNS:-$default_runs}
echo "| run | always: failed, substepped | iterations/step | ms/step | when_indefinite: failed, substepped | iterations/step | ms/step |"
echo "|---|---|---:|---:|---|---:|---:|"
while IFS= read -r run; do
  row="| \`${run//$source\//}\` |"
  for projection in always when_indefinite; do
    # shellcheck disable=SC2086
    line=$("$build/apps/ipstep" $run --optimizer=projected_newton --hessian_projection=$projection \
      --max_substeps=8 --on_failure=continue --progress=false 2>&1 | grep '^done:' || true)
    read -r f s it ms < <(echo "$line" | sed 's/done: [0-9]* steps, \([0-9]*\) failed, \([0-9]*\) substepped, \([0-9.]*\) iterations\/step, \([0-9.]*\) ms\/step.*/\1 \2 \3 \4/')
    row="$row $f, $s | $it | $ms |"
  done
  echo "$row"
done <<< "$runs"
