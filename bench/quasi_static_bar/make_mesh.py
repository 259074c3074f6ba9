#!/usr/bin/python3
"""Write the benchmark bar as a Gmsh MSH 2.2 ASCII file.

  make_mesh.py N OUT.msh

The bar is 2 m x 0.2 m x 0.2 m with its corner at (0, -0.1, -0.1), split into
(10N, N, N) cubes and each cube into 6 tetrahedra around its main diagonal
(the Kuhn split: conforming across cubes, every tetrahedron positively
oriented). Physical groups:
  3D "domain": every tetrahedron (dolfinx's gmshio takes its cells from it);
  2D "x_min":  the triangles of the x = 0 face (ipstep's clamp, by name).
Nodes are numbered i + (nx+1)(j + (ny+1)k) + 1 (i along x), as ipstep's own
structured box numbers them (0-based there). Python standard library only.
"""
import argparse
import itertools

LENGTH, WIDTH = 2.0, 0.2
ORIGIN = (0.0, -0.1, -0.1)


def volume6(p, q, r, s):
    """Six times the signed volume of the tetrahedron pqrs."""
    a, b, c = ([y - x for x, y in zip(p, t)] for t in (q, r, s))
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def bar_mesh(n):
    """Return (points, tetrahedra, x_min triangles) as lists, node indices 0-based."""
    nx, ny, nz = 10 * n, n, n
    points = [(ORIGIN[0] + LENGTH * i / nx, ORIGIN[1] + WIDTH * j / ny, ORIGIN[2] + WIDTH * k / nz)
              for k in range(nz + 1) for j in range(ny + 1) for i in range(nx + 1)]

    def node(i, j, k):
        return i + (nx + 1) * (j + (ny + 1) * k)

    # One tetrahedron per order in which the path from corner (0,0,0) to
    # (1,1,1) of a cube steps along the three axes.
    paths = []
    for order in itertools.permutations(range(3)):
        corner, path = [0, 0, 0], [(0, 0, 0)]
        for axis in order:
            corner[axis] = 1
            path.append(tuple(corner))
        paths.append(path)

    tets = []
    for k, j, i in itertools.product(range(nz), range(ny), range(nx)):
        for path in paths:
            t = [node(i + a, j + b, k + c) for a, b, c in path]
            if volume6(*(points[v] for v in t)) < 0:  # odd permutations: swap two nodes
                t[2], t[3] = t[3], t[2]
            tets.append(t)

    # x = 0 face: each square split along its (j, k)-(j+1, k+1) diagonal, the
    # faces the Kuhn tetrahedra have there; normals pointing to -x (outward).
    triangles = []
    for k, j in itertools.product(range(nz), range(ny)):
        a, b = node(0, j, k), node(0, j + 1, k)
        c, e = node(0, j + 1, k + 1), node(0, j, k + 1)
        triangles += [[a, c, b], [a, e, c]]
    return points, tets, triangles


def write_msh(path, points, tets, triangles):
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write('$PhysicalNames\n2\n2 1 "x_min"\n3 2 "domain"\n$EndPhysicalNames\n')
        f.write("$Nodes\n%d\n" % len(points))
        for tag, p in enumerate(points, start=1):
            f.write("%d %.17g %.17g %.17g\n" % (tag, p[0], p[1], p[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % (len(triangles) + len(tets)))
        tag = 1
        # elm-number elm-type(2 triangle, 4 tetrahedron) 2 tags: physical, elementary
        for t in triangles:
            f.write("%d 2 2 1 1 %d %d %d\n" % (tag, t[0] + 1, t[1] + 1, t[2] + 1))
            tag += 1
        for t in tets:
            f.write("%d 4 2 2 1 %d %d %d %d\n" % (tag, t[0] + 1, t[1] + 1, t[2] + 1, t[3] + 1))
            tag += 1
        f.write("$EndElements\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("n", type=int, help="cubes across the bar (10N along it)")
    parser.add_argument("out", help="output .msh file")
    args = parser.parse_args()
    if args.n < 1:
        parser.error("N must be >= 1")
    points, tets, triangles = bar_mesh(args.n)
    write_msh(args.out, points, tets, triangles)
    assert all(volume6(*(points[v] for v in t)) > 0 for t in tets)
    free_dofs = 3 * (len(points) - (args.n + 1) ** 2)
    print("%s: %d nodes, %d tetrahedra, %d x_min triangles, %d free DOFs"
          % (args.out, len(points), len(tets), len(triangles), free_dofs))


if __name__ == "__main__":
    main()
