#!/bin/bash
# The Hessian projections (--hessian_projection) of the Newton optimisers on
# the same runs: per run and optimiser, for each projection, failed and
# substepped steps, iterations and milliseconds per step, one markdown row per
# run and optimiser (docs/benchmarks.md, "Hessian projection"). Backward Euler
# unless a run says otherwise, tolerance 1e-5 m/s, --max_substeps=8
# --on_failure=continue. newton takes always, abs, trust_region and inertia;
# projected_newton all but inertia. PROJECTIONS="..." replaces the list.
#
#   bench/hessian_projection.sh BUILD_DIR [SOURCE_DIR]
#
# RUNS="..." in the environment replaces the default runs (one per line:
# the ipstep arguments after --optimizer); OPTIMIZERS="..." the optimisers
# (default: projected_newton newton).
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
optimizers=${OPTIMIZERS:-projected_newton newton}
projections=${PROJECTIONS:-always abs trust_region when_indefinite progressive inertia}
header="| run | optimiser |"
rule="|---|---|"
for projection in $projections; do
  header="$header $projection: failed, substepped | it/step | ms/step |"
  rule="$rule---|---:|---:|"
done
echo "$header"
echo "$rule"
while IFS= read -r run; do
  for optimizer in $optimizers; do
    row="| \`${run//$source\//}\` | $optimizer |"
    for projection in $projections; do
      if { [ "$optimizer" != projected_newton ] &&
        { [ "$projection" = when_indefinite ] || [ "$projection" = progressive ]; }; } ||
        { [ "$optimizer" = projected_newton ] && [ "$projection" = inertia ]; }; then
        row="$row — | — | — |"
        continue
      fi
      # shellcheck disable=SC2086
      line=$("$build/apps/ipstep" $run --optimizer=$optimizer --hessian_projection=$projection \
        --max_substeps=8 --on_failure=continue --progress=false 2>&1 | grep '^done:' || true)
      read -r f s it ms < <(echo "$line" | sed 's/done: [0-9]* steps, \([0-9]*\) failed, \([0-9]*\) substepped, \([0-9.]*\) iterations\/step, \([0-9.]*\) ms\/step.*/\1 \2 \3 \4/')
      row="$row $f, $s | $it | $ms |"
    done
    echo "$row"
  done
done <<< "$runs"
