#!/usr/bin/env bash
# ctest animate_drop: ipstep --frames --frames_format=ascii writes a ParaView
# series that Python's XML parser reads (run.pvd's timesteps are the simulated
# times of --stats, every .vtu has the scene's node count), and tools/animate.py
# draws it, and the default zlib frames, as GIFs with the requested number of
# frames. Exit code 77 (skipped) without an interpreter
# that has matplotlib and Pillow.
#   animate_test.sh IPSTEP SOURCE_DIR WORK_DIR [PYTHON]
set -euo pipefail
ipstep=$1 source=$2 work=$3
python=""
for candidate in ${4:-} python3 /usr/bin/python3; do
  if "$candidate" -c 'import matplotlib, PIL' 2> /dev/null; then
    python=$candidate
    break
  fi
done
if [ -z "$python" ]; then
  echo "no python3 with matplotlib and Pillow: skipped"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
"$ipstep" --scene=drop --steps=30 --frames="$work/frames" --frame_every=3 --stats="$work/stats.csv" \
  --frames_format=ascii > /dev/null
"$ipstep" --scene=drop --steps=30 --frames="$work/zlib" --frame_every=3 > /dev/null
"$python" - "$work" << 'PY'
import csv, os, sys
import xml.etree.ElementTree as ET
work = sys.argv[1]
times = [0.0] + [float(r["time"]) for r in csv.DictReader(open(f"{work}/stats.csv"))][2::3]
bodies = [d for d in ET.parse(f"{work}/frames/run.pvd").getroot().iter("DataSet")
          if d.get("part") == "0"]
assert len(bodies) == len(times) == 11, (len(bodies), len(times))
for dataset, time in zip(bodies, times):
    assert abs(float(dataset.get("timestep")) - time) <= 1e-12 * (1 + time), (dataset.get("timestep"), time)
    piece = ET.parse(os.path.join(work, "frames", dataset.get("file"))).getroot().find(
        "UnstructuredGrid/Piece")
    assert piece.get("NumberOfPoints") == "25", piece.get("NumberOfPoints")
    points = piece.find("Points/DataArray").text.split()
    assert len(points) == 3 * 25, len(points)
print("run.pvd and the .vtu files parse; timesteps are the simulated times")
PY
"$python" "$source/tools/animate.py" "$work/frames" "$work/drop.gif" --max-frames 6
"$python" "$source/tools/animate.py" "$work/zlib" "$work/drop_zlib.gif" --max-frames 6
"$python" - "$work/drop.gif" "$work/drop_zlib.gif" << 'PY'
import sys
from PIL import Image, ImageChops
ascii, zlib = Image.open(sys.argv[1]), Image.open(sys.argv[2])
assert ascii.format == "GIF" and ascii.n_frames == 6, (ascii.format, ascii.n_frames)
for frame in range(6):
    ascii.seek(frame)
    zlib.seek(frame)
    same = ImageChops.difference(ascii.convert("RGB"), zlib.convert("RGB")).getbbox() is None
    assert same, f"frame {frame} differs between the ascii and the zlib frames"
print("drop.gif: 6 frames, the same from ascii and zlib frames")
PY
# Bad input: one error line, exit code 2.
if "$python" "$source/tools/animate.py" "$work/no_such_dir" "$work/x.gif" 2> "$work/err"; then
  echo "animate.py accepted a missing directory"
  exit 1
elif [ $? -ne 2 ] || ! grep -q "no_such_dir/run.pvd" "$work/err"; then
  echo "animate.py: expected exit code 2 naming run.pvd:"
  cat "$work/err"
  exit 1
fi
