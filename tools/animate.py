#!/usr/bin/env python3
"""Draws the frames of an ipstep run (ipstep --frames=DIR) as an animation.

  tools/animate.py DIR OUT.gif [--max-frames 60] [--fps 15] [--size 4] [--dpi 80]
  tools/animate.py DIR OUT.mp4            (needs ffmpeg)

DIR/run.pvd lists the frames (io/frame_writer.h): the body (part 0: springs as
lines, triangles, particles), the contact obstacles (part 1) and a 3D solid's
boundary triangles (part 2, drawn instead of its tetrahedra), each with its
simulated time; ASCII or binary (raw or zlib) .vtu files. 2D scenes are drawn as lines and filled cells; 3D scenes as
shaded triangles from a fixed camera (--elev, --azim; y is up, as in the
built-in scenes). Obstacles are grey, the time is in the corner. At most
--max-frames frames are drawn, evenly spaced over the run, so that a GIF
stays small.

Needs matplotlib and, for GIFs, Pillow: run it with the interpreter that has
them (Debian: /usr/bin/python3 with python3-matplotlib and python3-pil,
tools/install_dependencies.sh; a python3 from pyenv or a virtualenv first on
PATH may not have them). Exit code 2 for bad input (a missing or malformed
DIR/run.pvd, an unknown output format), 3 when a module is missing.
"""
import argparse
import math
import os
import shutil
import sys
import xml.etree.ElementTree as ET

VTK_VERTEX, VTK_LINE, VTK_TRIANGLE, VTK_POLYGON, VTK_QUAD = 1, 3, 5, 7, 9


def fail(message, code=2):
    print(f"animate.py: error: {message}", file=sys.stderr)
    sys.exit(code)


FORMATS = {"Float64": "d", "Float32": "f", "Int64": "q", "Int32": "i", "UInt8": "B",
           "UInt32": "I", "UInt64": "Q"}


class Arrays:
    """The DataArrays of one .vtu: inline ASCII, or binary appended data (raw,
    or zlib-compressed in VTK's blocks: io/vtk_unstructured_grid.h)."""

    def __init__(self, path):
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as e:
            fail(f"{path}: {e}")
        self.path, self.appended = path, b""
        at = data.find(b"<AppendedData")
        if at >= 0:  # binary after '_': not XML
            self.appended = data[data.index(b"_", at) + 1:]
            data = data[:at] + b"</VTKFile>"
        try:
            self.root = ET.fromstring(data)
        except ET.ParseError as e:
            fail(f"{path}: {e}")
        self.header = "<" + FORMATS[self.root.get("header_type", "UInt32")]
        self.zlib = self.root.get("compressor") == "vtkZLibDataCompressor"

    def numbers(self, element, kind=float):
        if element.get("format") != "appended":
            return [kind(v) for v in (element.text or "").split()]
        import struct
        import zlib
        size = struct.calcsize(self.header)
        at = int(element.get("offset"))

        def header(count):
            nonlocal at
            values = struct.unpack_from(self.header[0] + self.header[1] * count, self.appended, at)
            at += count * size
            return values

        if self.zlib:
            blocks = header(3)[0]
            lengths = header(blocks)
            raw = b""
            for length in lengths:
                raw += zlib.decompress(self.appended[at:at + length])
                at += length
        else:
            length = header(1)[0]
            raw = self.appended[at:at + length]
        code = FORMATS[element.get("type")]
        return [kind(v) for v in struct.unpack(f"<{len(raw) // struct.calcsize(code)}{code}", raw)]


class Mesh:
    """One .vtu file: points, cells (point index lists) and their VTK types."""

    def __init__(self, path):
        arrays = Arrays(path)
        numbers = arrays.numbers
        piece = arrays.root.find("UnstructuredGrid/Piece")
        if piece is None:
            fail(f"{path}: not a VTK unstructured grid (.vtu)")
        flat = numbers(piece.find("Points/DataArray"))
        self.points = [tuple(flat[i:i + 3]) for i in range(0, len(flat), 3)]
        cells = {a.get("Name"): a for a in piece.findall("Cells/DataArray")}
        connectivity = numbers(cells["connectivity"], int)
        offsets = numbers(cells["offsets"], int)
        self.types = numbers(cells["types"], int)
        self.cells, start = [], 0
        for end in offsets:
            self.cells.append(connectivity[start:end])
            start = end
        if len(self.points) != int(piece.get("NumberOfPoints")):
            fail(f"{path}: NumberOfPoints does not match the points")
        owner = piece.find("CellData/DataArray[@Name='obstacle']")
        self.owner = numbers(owner, int) if owner is not None else [0] * len(self.cells)

    def is_plane(self, obstacle):
        """A plane is drawn as one segment (2D) or one quad (3D)."""
        kinds = [t for t, o in zip(self.types, self.owner) if o == obstacle]
        return len(kinds) == 1 and kinds[0] in (VTK_LINE, VTK_QUAD)

    def cells_of(self, *types):
        return [c for c, t in zip(self.cells, self.types) if t in types]


def read_series(directory):
    pvd = os.path.join(directory, "run.pvd")
    try:
        root = ET.parse(pvd).getroot()
    except (OSError, ET.ParseError) as e:
        fail(f"{pvd}: {e} (write frames with ipstep --frames={directory})")
    frames = {}
    for dataset in root.iter("DataSet"):
        time = float(dataset.get("timestep"))
        part = int(dataset.get("part", "0"))
        frames.setdefault(time, {})[part] = os.path.join(directory, dataset.get("file"))
    if not frames:
        fail(f"{pvd}: lists no frames")
    return [(t, frames[t]) for t in sorted(frames)]


def pick(series, max_frames):
    if len(series) <= max_frames:
        return series
    step = (len(series) - 1) / (max_frames - 1)
    return [series[round(i * step)] for i in range(max_frames)]


def is_3d(meshes):
    return any(abs(p[2]) > 0 for mesh in meshes for p in mesh.points)


def bounds(meshes, skip_planes):
    """Bounding box of the bodies and of the obstacles other than planes."""
    points = []
    for mesh, is_obstacle in meshes:
        if not is_obstacle:
            points += mesh.points
        else:
            for cell, owner in zip(mesh.cells, mesh.owner):
                if not (skip_planes and mesh.is_plane(owner)):
                    points += [mesh.points[i] for i in cell]
    lo = [min(p[k] for p in points) for k in range(3)]
    hi = [max(p[k] for p in points) for k in range(3)]
    return lo, hi


def draw_2d(ax, body, obstacles):
    from matplotlib.collections import LineCollection, PolyCollection
    if obstacles is not None:
        polygons = [[obstacles.points[i][:2] for i in c]
                    for c in obstacles.cells_of(VTK_POLYGON, VTK_QUAD, VTK_TRIANGLE)]
        ax.add_collection(PolyCollection(polygons, facecolors="0.75", edgecolors="0.45"))
        lines = [[obstacles.points[i][:2] for i in c] for c in obstacles.cells_of(VTK_LINE)]
        ax.add_collection(LineCollection(lines, colors="0.35", linewidths=3))
    triangles = [[body.points[i][:2] for i in c] for c in body.cells_of(VTK_TRIANGLE)]
    ax.add_collection(PolyCollection(triangles, facecolors="#9ecae1", edgecolors="none"))
    springs = [[body.points[i][:2] for i in c] for c in body.cells_of(VTK_LINE)]
    ax.add_collection(LineCollection(springs, colors="#08519c", linewidths=0.8))
    particles = [body.points[c[0]] for c in body.cells_of(VTK_VERTEX)]
    if particles:
        ax.plot([p[0] for p in particles], [p[1] for p in particles], "o", color="#08519c")


def shaded(polygons, base, light=(-0.5, -0.6, 0.65)):
    """Face colours from a base RGB colour and the faces' normals (two-sided)."""
    norm = math.sqrt(sum(c * c for c in light))
    colors = []
    for poly in polygons:
        a, b, c = poly[0], poly[1], poly[2]
        u = [b[k] - a[k] for k in range(3)]
        v = [c[k] - a[k] for k in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        intensity = abs(sum(n[k] * light[k] for k in range(3))) / (length * norm)
        shade = 0.3 + 0.75 * intensity
        colors.append(tuple(min(1.0, ch * shade) for ch in base) + (1.0,))
    return colors


def draw_3d(ax, body, obstacles, lo, hi):
    """Planes first, clamped to the drawn box; then the other obstacles' faces
    and the body's triangles in one collection, so that matplotlib sorts them
    by depth together."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    def view(p):  # y up: plot (x, z, y)
        return (p[0], p[2], p[1])

    def clamped(p):
        return tuple(min(max(p[k], lo[k]), hi[k]) for k in range(3))

    ax.computed_zorder = False
    faces, colors = [], []
    if obstacles is not None:
        planes = []
        for cell, kind, owner in zip(obstacles.cells, obstacles.types, obstacles.owner):
            if kind not in (VTK_TRIANGLE, VTK_QUAD, VTK_POLYGON):
                continue
            if obstacles.is_plane(owner):
                planes.append([view(clamped(obstacles.points[i])) for i in cell])
            else:
                faces.append([view(obstacles.points[i]) for i in cell])
        colors += shaded(faces, (0.7, 0.7, 0.7))
        if planes:
            ax.add_collection3d(Poly3DCollection(planes, facecolors=(0.85, 0.85, 0.85, 1.0),
                                                 edgecolors="0.6", zorder=0))
    triangles = [[view(body.points[i]) for i in c] for c in body.cells_of(VTK_TRIANGLE)]
    faces += triangles
    colors += shaded(triangles, (0.35, 0.6, 0.85))
    if faces:
        # Drawn far to near by each face's nearest vertex ("min"), not its
        # centroid: a large sphere face whose centroid is nearer than the
        # small cloth triangles resting on it was drawn over them (the sphere
        # showed through the cloth). Still a painter's algorithm, not a depth
        # buffer: tools/render_frames.py (ParaView) has one.
        ax.add_collection3d(Poly3DCollection(faces, facecolors=colors, edgecolors=colors,
                                             linewidths=0.3, zorder=1, zsort="min"))
    if not triangles:
        springs = [[view(body.points[i]) for i in c] for c in body.cells_of(VTK_LINE)]
        ax.add_collection3d(Line3DCollection(springs, colors="#08519c", linewidths=0.8,
                                             zorder=2))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", help="the --frames directory of an ipstep run")
    parser.add_argument("output", help="OUT.gif or OUT.mp4")
    parser.add_argument("--max-frames", type=int, default=60)
    parser.add_argument("--fps", type=float, default=15)
    parser.add_argument("--size", type=float, default=4.0, help="figure width [inches]")
    parser.add_argument("--dpi", type=int, default=80)
    parser.add_argument("--elev", type=float, default=25.0, help="3D camera elevation [deg]")
    parser.add_argument("--azim", type=float, default=-60.0, help="3D camera azimuth [deg]")
    args = parser.parse_args()
    extension = os.path.splitext(args.output)[1].lower()
    if extension not in (".gif", ".mp4"):
        fail(f"{args.output}: the output must be a .gif or .mp4 file")
    if args.max_frames < 2 or not args.fps > 0 or not args.size > 0 or args.dpi < 10:
        fail("--max-frames must be >= 2, --fps and --size > 0, --dpi >= 10")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        from matplotlib import animation
    except ImportError:
        fail(f"matplotlib is not installed for {sys.executable}: install python3-matplotlib "
             "and run this with /usr/bin/python3", 3)
    if extension == ".gif":
        try:
            import PIL  # noqa: F401  (matplotlib's GIF writer)
        except ImportError:
            fail(f"Pillow is not installed for {sys.executable}: install python3-pil", 3)
    elif shutil.which("ffmpeg") is None:
        fail("writing .mp4 needs ffmpeg (apt install ffmpeg); write a .gif instead", 3)

    series = pick(read_series(args.directory), args.max_frames)
    frames = []
    for time, parts in series:
        if 0 not in parts:
            fail(f"{args.directory}/run.pvd: no body (part 0) at time {time:g}")
        # A 3D solid's body is tetrahedra: its boundary (part 2) is drawn.
        frames.append((time, Mesh(parts[2] if 2 in parts else parts[0]),
                       Mesh(parts[1]) if 1 in parts else None))
    three_d = is_3d([m for _, body, obstacles in frames for m in (body, obstacles) if m])
    everything = [(m, is_obstacle) for _, body, obstacles in frames
                  for m, is_obstacle in ((body, False), (obstacles, True)) if m is not None]
    lo, hi = bounds(everything, skip_planes=True)
    pad = 0.08 * max(hi[k] - lo[k] for k in range(3)) or 0.1
    lo = [v - pad for v in lo]
    hi = [v + pad for v in hi]

    if three_d:
        fig = plt.figure(figsize=(args.size, args.size))
        ax = fig.add_subplot(projection="3d")
    else:
        width, height = hi[0] - lo[0], hi[1] - lo[1]
        fig, ax = plt.subplots(figsize=(args.size, max(1.5, args.size * height / width)))

    def draw(index):
        time, body, obstacles = frames[index]
        ax.clear()
        if three_d:
            draw_3d(ax, body, obstacles, lo, hi)
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[2], hi[2])
            ax.set_zlim(lo[1], hi[1])
            ax.set_box_aspect((hi[0] - lo[0], hi[2] - lo[2], hi[1] - lo[1]))
            ax.view_init(elev=args.elev, azim=args.azim)
            ax.set_axis_off()
            ax.text2D(0.03, 0.93, f"t = {time:.3f} s", transform=ax.transAxes)
        else:
            draw_2d(ax, body, obstacles)
            ax.set_xlim(lo[0], hi[0])
            ax.set_ylim(lo[1], hi[1])
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            ax.text(0.03, 0.92, f"t = {time:.3f} s", transform=ax.transAxes)
        return []

    fig.tight_layout()
    movie = animation.FuncAnimation(fig, draw, frames=len(frames), blit=False)
    writer = (animation.PillowWriter(fps=args.fps) if extension == ".gif"
              else animation.FFMpegWriter(fps=args.fps))
    movie.save(args.output, writer=writer, dpi=args.dpi)
    print(f"wrote {args.output}: {len(frames)} frames, t = {frames[0][0]:g} to "
          f"{frames[-1][0]:g} s")


if __name__ == "__main__":
    main()
