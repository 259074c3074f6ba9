#!/bin/bash
# Cost per step of elastic solids at growing mesh sizes (docs/benchmarks.md,
# "Elastic solids"): refined copies of twisted_bar_3d (3D) and squash_square
# (2D) from bench/elastic_scaling_scenes.py, backward Euler, tolerance 1e-5 m/s,
# one run per size and optimiser, one CSV row each.
#
#   bench/elastic_scaling.sh BUILD_DIR OUT.csv 3d|2d [STEPS] [LBFGS_LIMIT_S]
#
# lbfgs runs with --time_limit=LBFGS_LIMIT_S per step (default 120) and no
# substeps: a step that hits the limit counts as failed, and the row says so.
# SIZES="..." in the environment replaces the default sizes (N below).
set -euo pipefail
build=$1 out=$2 which=$3 steps=${4:-3} limit=${5:-120}
here=$(cd "$(dirname "$0")" && pwd)
scenes=$(mktemp -d)
/usr/bin/env python3 "$here/elastic_scaling_scenes.py" "$scenes"
if [ "$which" = 3d ]; then sizes="3 5 7 10 14"; prefix=bar; else sizes="22 40 80 160 220"; prefix=squash; fi
sizes=${SIZES:-$sizes}
echo "scene,cells,nodes,free_dofs,optimizer,steps,failed,iterations_per_step,ms_per_step,note" > "$out"
for n in $sizes; do
  for opt in newton projected_newton lbfgs; do
    extra=""
    note=""
    if [ "$opt" = lbfgs ]; then extra="--time_limit=$limit --max_substeps=1 --on_failure=continue"; note="time limit ${limit} s per step"; fi
    log=$("$build/apps/ipstep" --scene="$scenes/${prefix}_$n.json" --optimizer=$opt --steps=$steps $extra 2>&1 || true)
    nodes=$(echo "$log" | sed -n 's/.*: \([0-9]*\) nodes, \([0-9]*\) free, dimension \([23]\).*/\1/p' | head -1)
    free=$(echo "$log" | sed -n 's/.*: \([0-9]*\) nodes, \([0-9]*\) free, dimension \([23]\).*/\2 \3/p' | head -1)
    dofs=$(( ${free% *} * ${free#* } ))
    done_line=$(echo "$log" | grep '^done:' || echo "done: ? steps, ? failed, ? substepped, ? iterations/step, ? ms/step")
    read -r s f it ms < <(echo "$done_line" | sed 's/done: \([0-9?]*\) steps, \([0-9?]*\) failed, [0-9?]* substepped, \([0-9.?]*\) iterations\/step, \([0-9.?]*\) ms\/step.*/\1 \2 \3 \4/')
    echo "${prefix}_$n,$n,$nodes,$dofs,$opt,$s,$f,$it,$ms,$note" | tee -a "$out"
  done
done
rm -rf "$scenes"
