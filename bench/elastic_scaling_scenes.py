#!/usr/bin/env python3
"""Refined copies of the built-in elastic scenes for the cost-per-step tables
of docs/benchmarks.md ("Elastic solids").

  bench/elastic_scaling_scenes.py OUT_DIR

writes
  OUT_DIR/bar_N.json     twisted_bar_3d with 10N x N x N cubes (6 tetrahedra
                         each), the end face's nodes moving with the tangential
                         velocity of a rotation at 2 rad/s about the bar's
                         axis (a linearised twist, as the built-in scene was
                         when these tables were measured);
  OUT_DIR/squash_N.json  squash_square with N x N cells;
  OUT_DIR/twisted_bar_linear.json  the built-in twisted_bar_3d as it was
                         before moving nodes could rotate (its end face moved
                         with the constant velocities omega x r, 40 steps):
                         the twisted_bar_3d rows of docs/benchmarks.md;
for the sizes below (3D: 10^3 to 10^5 DOFs, 2D: 10^3 to 10^5 DOFs), and
  OUT_DIR/cantilever_raised.json  cantilever_2d moved up by 1 m, as the
                         table of docs/benchmarks.md was measured: the
                         divergence test of the time, |E_n - E_0| > 1e6 |E_0|,
                         called every run of the built-in beam (about y = 0,
                         E_0 = 0) diverged at its first step; the rule of
                         sim/divergence.h does not. Moving it changes nothing
                         else (uniform gravity, the clamp moves with it).
"""
import copy
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PROBLEMS = os.path.join(HERE, "..", "problems")

BAR_SIZES = [3, 5, 7, 10, 14]          # (10N+1)(N+1)^2 nodes: 1488 ... 95175 DOFs
SQUASH_SIZES = [22, 40, 80, 160, 220]  # (N+1)^2 nodes: 1058 ... 97682 DOFs


def bar(n):
    with open(os.path.join(PROBLEMS, "twisted_bar_3d.json")) as f:
        scene = json.load(f)
    mesh = scene["solid"]["mesh"]
    size, origin = mesh["size"], mesh["origin"]
    nx, ny, nz = 10 * n, n, n
    mesh["cells"] = [nx, ny, nz]
    # The end face moves with the constant velocities omega x r (a linearised
    # twist), as the built-in twisted_bar_3d did before moving nodes could
    # rotate; bar(2) is that earlier built-in scene, which docs/benchmarks.md's
    # twisted_bar_3d rows measured.
    omega = 2.0  # rad/s about the x axis through (y, z) = (0, 0)
    moving = []
    for k in range(nz + 1):
        for j in range(ny + 1):
            # mesh/structured_mesh.h: node i + (nx+1)(j + (ny+1)k), i along x.
            node = nx + (nx + 1) * (j + (ny + 1) * k)
            y = origin[1] + size[1] * j / ny
            z = origin[2] + size[2] * k / nz
            moving.append({"node": node, "velocity": [0.0, -omega * z, omega * y]})
    scene["moving"] = moving
    scene["name"] = "bar_%d" % n
    scene["description"] = "twisted_bar_3d refined to %d x %d x %d cubes" % (nx, ny, nz)
    return scene


def squash(n):
    with open(os.path.join(PROBLEMS, "squash_square.json")) as f:
        scene = json.load(f)
    scene["solid"]["mesh"]["cells"] = [n, n]
    scene["name"] = "squash_%d" % n
    scene["description"] = "squash_square refined to %d x %d cells" % (n, n)
    return scene


def cantilever_raised():
    with open(os.path.join(PROBLEMS, "cantilever_2d.json")) as f:
        scene = json.load(f)
    origin = scene["solid"]["mesh"]["origin"]
    scene["solid"]["mesh"]["origin"] = [origin[0], origin[1] + 1.0]
    scene["name"] = "cantilever_raised"
    scene["description"] = "cantilever_2d moved up by 1 m (nonzero initial energy)"
    return scene


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for n in BAR_SIZES:
        with open(os.path.join(out, "bar_%d.json" % n), "w") as f:
            json.dump(bar(n), f, indent=1)
    for n in SQUASH_SIZES:
        with open(os.path.join(out, "squash_%d.json" % n), "w") as f:
            json.dump(squash(n), f, indent=1)
    # The earlier built-in twisted_bar_3d (linearised twist, 40 steps).
    linear = bar(2)
    linear["steps"] = 40
    linear["name"] = "twisted_bar_linear"
    linear["description"] = "twisted_bar_3d before rotating moving nodes: end face at omega x r"
    with open(os.path.join(out, "twisted_bar_linear.json"), "w") as f:
        json.dump(linear, f, indent=1)
    with open(os.path.join(out, "cantilever_raised.json"), "w") as f:
        json.dump(cantilever_raised(), f, indent=1)


if __name__ == "__main__":
    main()
