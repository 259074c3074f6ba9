#!/usr/bin/env bash
# ctest vtk_reader: the frames of a 3D elastic solid with contact (ball_drop_3d,
# 3 steps) read back by VTK's own vtkXMLUnstructuredGridReader (Debian's
# python3-vtk9, or the VTK of python3-paraview), in each --frames_format:
# run.pvd's timesteps are the simulated times of --stats; part 0 is
# tetrahedra (cell type 10) with cell data J, energy_density,
# von_mises_stress and point data velocity, contact_force; each tetrahedron's
# volume is J times its volume at rest; part 1 is the ground; part 2 the
# boundary, a closed triangulated sphere (V - F/2 = 2); zlib, raw and ascii
# read back to the same numbers (with --frames_precision=float64); the
# default float32 frames, zlib and ascii, have Float32 points and fields that
# agree with the float64 ones to 1e-6 of each array's largest value and with
# each other exactly; tools/render_frames.py rejects a missing
# directory with exit code 2. Exit code 77 (skipped) without an
# interpreter that has VTK's Python modules.
#   vtk_reader_test.sh IPSTEP WORK_DIR
set -euo pipefail
ipstep=$1 work=$2
python=""
for candidate in /usr/bin/python3 python3; do
  if "$candidate" -c 'import vtkmodules.vtkIOXML, numpy' 2> /dev/null; then
    python=$candidate
    break
  fi
done
if [ -z "$python" ]; then
  echo "no python3 with VTK (python3-vtk9) and numpy: skipped"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
for format in zlib raw ascii; do
  "$ipstep" --scene=ball_drop_3d --steps=3 --frames="$work/$format" --frames_format=$format \
    --frames_precision=float64 --stats="$work/stats.csv" > /dev/null
  if [ $format != raw ]; then
    "$ipstep" --scene=ball_drop_3d --steps=3 --frames="$work/${format}32" --frames_format=$format \
      > /dev/null
  fi
done
"$python" - "$work" << 'PY'
import csv, os, sys
import xml.etree.ElementTree as ET
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
from vtkmodules.util.numpy_support import vtk_to_numpy

work = sys.argv[1]
times = [0.0] + [float(r["time"]) for r in csv.DictReader(open(f"{work}/stats.csv"))]


def read(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    assert grid.GetNumberOfPoints() > 0, path
    return grid


def arrays(data):
    return {data.GetArrayName(i): vtk_to_numpy(data.GetArray(i))
            for i in range(data.GetNumberOfArrays())}


def volumes(grid):
    points = vtk_to_numpy(grid.GetPoints().GetData())
    tets = vtk_to_numpy(grid.GetCells().GetConnectivityArray()).reshape(-1, 4)
    edges = points[tets[:, 1:]] - points[tets[:, :1]]
    return np.linalg.det(edges) / 6.0


everything = {}
for format in ("zlib", "raw", "ascii"):
    directory = os.path.join(work, format)
    parts = {}
    for d in ET.parse(os.path.join(directory, "run.pvd")).getroot().iter("DataSet"):
        parts.setdefault(int(d.get("part")), []).append((float(d.get("timestep")), d.get("file")))
    assert sorted(parts) == [0, 1, 2], sorted(parts)
    for part in parts.values():
        assert [t for t, _ in part] == times, ([t for t, _ in part], times)
    rest = None
    for (time, body_file), (_, surface_file) in zip(parts[0], parts[2]):
        body = read(os.path.join(directory, body_file))
        cells = vtk_to_numpy(body.GetCellTypesArray())
        assert body.GetNumberOfPoints() == 258 and len(cells) > 258, body.GetNumberOfCells()
        assert (cells == 10).all(), set(cells)
        cell, point = arrays(body.GetCellData()), arrays(body.GetPointData())
        assert {"J", "energy_density", "von_mises_stress", "kind"} <= set(cell), sorted(cell)
        assert {"velocity", "contact_force"} <= set(point), sorted(point)
        assert point["velocity"].shape == (258, 3) and point["contact_force"].shape == (258, 3)
        v = volumes(body)
        rest = v if rest is None else rest
        assert np.allclose(v, cell["J"] * rest, rtol=1e-12, atol=0), abs(v - cell["J"] * rest).max()
        assert (cell["energy_density"] >= -1e-9).all() and (cell["von_mises_stress"] >= 0).all()
        surface = read(os.path.join(directory, surface_file))
        triangles = surface.GetNumberOfCells()
        assert (vtk_to_numpy(surface.GetCellTypesArray()) == 5).all()
        assert surface.GetNumberOfPoints() == 2 + triangles // 2, (surface.GetNumberOfPoints(), triangles)
        assert "J" in arrays(surface.GetCellData()) and "velocity" in arrays(surface.GetPointData())
        everything.setdefault(format, []).append((cell, point))
    assert abs(rest.sum() - 4 / 3 * np.pi * 0.5 ** 3) < 0.05 * 0.53, rest.sum()
    ground = read(os.path.join(directory, parts[1][0][1]))
    assert ground.GetNumberOfCells() == 1 and ground.GetCellType(0) == 9  # a quad
for format in ("raw", "ascii"):
    for (cell, point), (cell_z, point_z) in zip(everything[format], everything["zlib"]):
        for name in cell:
            assert np.array_equal(cell[name], cell_z[name]), (format, name)
        for name in point:
            assert np.array_equal(point[name], point_z[name]), (format, name)
# The default precision, float32: the same frames' files, Float32 arrays.
for format in ("zlib32", "ascii32"):
    directory = os.path.join(work, format)
    files = [d.get("file") for d in ET.parse(os.path.join(directory, "run.pvd")).getroot().iter("DataSet")]
    exact = os.path.join(work, "zlib")
    for name in files:
        grid, grid64 = read(os.path.join(directory, name)), read(os.path.join(exact, name))
        data = {"points": vtk_to_numpy(grid.GetPoints().GetData())}
        data64 = {"points": vtk_to_numpy(grid64.GetPoints().GetData())}
        for get in ("GetPointData", "GetCellData"):
            data.update(arrays(getattr(grid, get)()))
            data64.update(arrays(getattr(grid64, get)()))
        assert sorted(data) == sorted(data64), (name, sorted(data), sorted(data64))
        for key, values in data.items():
            if values.dtype.kind in "iu":  # kind, obstacle
                assert np.array_equal(values, data64[key]), (name, key)
                continue
            assert values.dtype == np.float32, (name, key, values.dtype)
            scale = max(abs(data64[key]).max(), 1e-300)
            error = abs(values.astype(np.float64) - data64[key]).max() / scale
            assert error <= 1e-6, (name, key, error)
            if format == "ascii32":
                other = read(os.path.join(work, "zlib32", name))
                assert np.array_equal(values, {"points": vtk_to_numpy(other.GetPoints().GetData()),
                                               **arrays(other.GetPointData()),
                                               **arrays(other.GetCellData())}[key]), (name, key)
print(f"{len(times)} frames in zlib, raw and ascii (float64) and zlib, ascii (float32) read by VTK: tetrahedra, J, energy_density, "
      "von_mises_stress, velocity, contact_force, surface, times")
PY
# tools/render_frames.py (ParaView, not needed here): bad input is exit code 2
# naming the file, before ParaView is imported.
if "$python" "$(dirname "$0")/../../tools/render_frames.py" "$work/none" "$work/x.gif" \
  2> "$work/err"; then
  echo "render_frames.py accepted a missing directory"
  exit 1
elif [ $? -ne 2 ] || ! grep -q "none/run.pvd" "$work/err"; then
  echo "render_frames.py: expected exit code 2 naming run.pvd:"
  cat "$work/err"
  exit 1
fi
