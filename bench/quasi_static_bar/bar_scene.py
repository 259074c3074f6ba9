#!/usr/bin/python3
"""Write the ipstep scene of the benchmark bar.

  bar_scene.py MESH.msh OUT.json

A neo-Hookean bar (E = 1e8 Pa, nu = 0.3, rho = 1000 kg/m^3) under gravity
(0, -9.81, 0), clamped on the mesh's "x_min" physical group; one step of
0.01 s. The mesh path is written relative to the scene file (ipstep reads it
so).
"""
import argparse
import json
import os

YOUNGS_MODULUS = 1e8
POISSON_RATIO = 0.3
DENSITY = 1000.0
GRAVITY = [0.0, -9.81, 0.0]
TIME_STEP = 0.01


def scene(mesh_file):
    return {
        "name": "quasi_static_bar",
        "description": "2 m x 0.2 m x 0.2 m neo-Hookean bar (E = 1e8 Pa, nu = 0.3, "
                       "rho = 1000 kg/m^3) clamped at x = 0, under its weight; "
                       "mesh " + os.path.basename(mesh_file),
        "dimension": 3,
        "time_step": TIME_STEP,
        "steps": 1,
        "effects": ["gravity", "elasticity"],
        "gravity": GRAVITY,
        "solid": {
            "mesh": {"file": mesh_file},
            "model": "neo_hookean",
            "youngs_modulus": YOUNGS_MODULUS,
            "poisson_ratio": POISSON_RATIO,
            "density": DENSITY,
        },
        "pinned": ["x_min"],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("mesh", help="Gmsh .msh file from make_mesh.py")
    parser.add_argument("out", help="output scene .json")
    args = parser.parse_args()
    out_dir = os.path.dirname(os.path.abspath(args.out))
    mesh_file = os.path.relpath(os.path.abspath(args.mesh), out_dir)
    with open(args.out, "w") as f:
        json.dump(scene(mesh_file), f, indent=2)
        f.write("\n")


if __name__ == "__main__":
    main()
