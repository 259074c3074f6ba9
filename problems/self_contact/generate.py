#!/usr/bin/env python3
"""Writes the 3D self-contact scenes of problems/self_contact/ (not built in:
load them by path, tests/contact/self_contact_scenes_test.cc does).

Cloths are explicit node grids with structural springs and one shear
diagonal per quad (squared strain), plus Hookean bending springs across two
cells, and their declared contact surface ("surface": {"triangles": ...}: two
triangles per quad along the springs' diagonal; contact/collision_mesh.h). Parameters as problems/cloth_sphere.json: 0.2 kg per m^2, k = 2e3,
bending 50, d_hat 5 mm, adaptive kappa.

    python3 problems/self_contact/generate.py
"""
import json
import math
import os
import sys

SURFACE = True  # scenes listing nodes and springs declare their surface

HERE = os.path.dirname(os.path.abspath(__file__))


def cloth(n, size, place, first=0, rest=False, crease=None):
    """n x n nodes, spacing size / (n - 1); place(u, v) -> [x, y, z] with u, v
    in [0, size]. Returns positions, springs (node ids from `first`); with
    `rest`, every spring's rest length is that of the flat grid (else the
    loader takes the initial length). `crease`: a column index; bending
    springs across it are left out (BuildCollisionMesh decides from the
    initial positions which springs span a node, and a bending spring across
    a fold does not, so it would become a contact edge)."""
    a = size / (n - 1)
    positions = []
    for j in range(n):
        for i in range(n):
            positions.append([round(c, 12) for c in place(i * a, j * a)])
    springs = []

    def idx(i, j):
        return first + j * n + i

    def spring(p, q, model, k, length):
        entry = {"nodes": [p, q], "model": model, "stiffness": k}
        if rest:
            entry["rest_length"] = round(length, 12)
        springs.append(entry)

    for j in range(n):
        for i in range(n):
            if i + 1 < n:
                spring(idx(i, j), idx(i + 1, j), "squared_strain", 2000.0, a)
            if j + 1 < n:
                spring(idx(i, j), idx(i, j + 1), "squared_strain", 2000.0, a)
            if i + 1 < n and j + 1 < n:
                spring(idx(i, j), idx(i + 1, j + 1), "squared_strain", 2000.0, a * math.sqrt(2))
            if i + 2 < n and not (crease is not None and i < crease <= i + 2):
                spring(idx(i, j), idx(i + 2, j), "hookean", 50.0, 2 * a)
            if j + 2 < n:
                spring(idx(i, j), idx(i, j + 2), "hookean", 50.0, 2 * a)
    return positions, springs


def triangles(n, first=0):
    """The two triangles per quad of an n x n cloth (the diagonal (i, j) -
    (i + 1, j + 1) of its shear springs)."""
    def idx(i, j):
        return first + j * n + i

    out = []
    for j in range(n - 1):
        for i in range(n - 1):
            out.append([idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)])
            out.append([idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)])
    return out


def scene(name, description, positions, springs, masses, obstacles, steps, h=0.0025,
          moving=None, velocities=None, surface=None):
    s = {
        "name": name,
        "description": description,
        "dimension": 3,
        "time_step": h,
        "steps": steps,
        "effects": ["gravity", "springs", "contact"],
        "gravity": [0, -9.81, 0],
        "nodes": {"positions": positions, "masses": masses},
        "springs": springs,
    }
    if velocities:
        s["nodes"]["velocities"] = velocities
    if SURFACE and surface:
        s["surface"] = {"triangles": surface}
    if moving:
        s["moving"] = moving
    s["contact"] = {"dhat": 0.005, "self_contact": True, "obstacles": obstacles}
    with open(os.path.join(HERE, name + ".json"), "w") as f:
        json.dump(s, f, indent=1)
        f.write("\n")


def main():
    n = 12
    ground = lambda y: {"type": "plane", "point": [0, y, 0], "normal": [0, 1, 0]}

    # 1. A cloth folded in half falls onto a sphere: the lower half drapes
    # over the sphere and the upper half lands on it. The crease is one cell
    # wide and unstrained: the upper half is shifted by half a cell, at height
    # sqrt(3)/2 a, so the crease's structural springs have length a and its
    # diagonals a sqrt(2) (rest lengths those of the flat cloth).
    m = 16
    size = 1.2
    a = size / (m - 1)
    half = m // 2
    gap = math.sqrt(3.0) / 2.0 * a

    def folded(u, v):
        i = round(u / a)
        if i < half:
            return [u - 0.45, 0.3, v - 0.6]
        return [(m - 1 - i) * a + 0.5 * a - 0.45, 0.3 + gap, v - 0.6]

    pos, spr = cloth(m, size, folded, rest=True, crease=half)
    scene("cloth_sphere_fold",
          "3D self-contact: a 1.2 m x 1.2 m cloth (16 x 16 nodes, one triangulation, 0.29 kg) "
          "folded in half (upper half 6.9 cm above the lower one, shifted half a cell: an "
          "unstrained one-cell crease; no bending springs across it) falls from y = 0.3 onto a sphere of radius 0.2 at "
          "the origin, ground y = -0.3: the lower half drapes over the sphere and the upper "
          "half lands on it. problems/self_contact/generate.py.",
          pos, spr, [0.2 * 1.44 / len(pos)] * len(pos),
          [{"type": "sphere", "center": [0, 0, 0], "radius": 0.2}, ground(-0.3)], 300,
          surface=triangles(m))

    # 2. Two cloths dropped onto a box: the upper one turned by 30 degrees
    # about y, 4 cm above the lower one.
    c, s30 = math.cos(math.pi / 6), math.sin(math.pi / 6)
    pos_a, spr_a = cloth(n, 0.8, lambda u, v: [u - 0.4, 0.05, v - 0.4])
    pos_b, spr_b = cloth(n, 0.8, lambda u, v: [c * (u - 0.4) - s30 * (v - 0.4), 0.09,
                                               s30 * (u - 0.4) + c * (v - 0.4)], first=n * n)
    masses = [0.2 * 0.64 / (n * n)] * (2 * n * n)
    scene("two_cloths_box",
          "3D self-contact: two 0.8 m x 0.8 m cloths (12 x 12 nodes each, one triangulation) "
          "dropped onto a 0.4 m x 0.3 m x 0.4 m box (top at y = 0) on the ground y = -0.3; the "
          "upper cloth, turned by 30 degrees, starts 4 cm above the lower one and lands on it. "
          "problems/self_contact/generate.py.",
          pos_a + pos_b, spr_a + spr_b, masses,
          [{"type": "box", "min": [-0.2, -0.3, -0.2], "max": [0.2, 0, 0.2]}, ground(-0.3)], 200,
          surface=triangles(n) + triangles(n, first=n * n))

    # 3. A cloth held at two opposite edges that move towards each other,
    # its middle thrown upwards: it buckles up into a tall loop, which the
    # approaching edges narrow until it falls over onto itself.
    pos, spr = cloth(n, 1.0, lambda u, v: [u - 0.5, 0.0, v - 0.5])
    moving = []
    for j in range(n):
        moving.append({"node": j * n, "velocity": [0.4, 0, 0]})
        moving.append({"node": j * n + n - 1, "velocity": [-0.4, 0, 0]})
    velocities = [[round(-1.5 * math.sin(math.pi * (p[0] + 0.5)), 12),
                   round(2.0 * math.sin(math.pi * (p[0] + 0.5)), 12), 0.0] for p in pos]
    for entry in moving:  # held nodes start at their prescribed velocity
        velocities[entry["node"]] = list(entry["velocity"])
    scene("cloth_pinch",
          "3D self-contact: a 1 m x 1 m cloth (12 x 12 nodes, one triangulation, 0.2 kg) held "
          "at its two edges x = -0.5 and x = 0.5, which move towards each other at 0.4 m/s "
          "for 1 s (constant velocities: scenes have no rotating nodes for a twist), its "
          "middle thrown up and to the side (2 m/s up, 1.5 m/s towards -x, sine profile): it "
          "buckles up into a leaning loop that the edges narrow to 0.2 m, and the loop falls "
          "over onto the cloth. "
          "problems/self_contact/generate.py.",
          pos, spr, [0.2 / len(pos)] * len(pos), [ground(-1.0)], 400, moving=moving,
          velocities=velocities, surface=triangles(n))


if __name__ == "__main__":
    main()
