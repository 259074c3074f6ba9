#!/usr/bin/env bash
# Installs ipstep's build and test dependencies from Debian's packages.
# Nothing is downloaded at build time; this is the only install step.
set -euo pipefail
packages=(
  cmake g++ make
  libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
  libgtest-dev libbenchmark-dev nlohmann-json3-dev
  libgmsh-dev  # elastic solids: meshing and .msh files (mesh/gmsh_mesh.h)
  zlib1g-dev  # compressed frames (io/vtk_unstructured_grid.cc, --frames_format=zlib)
  # projected_newton's sparse Cholesky: CHOLMOD (SuiteSparse) with METIS, on
  # OpenBLAS (solver/sparse_cholesky.cc)
  libsuitesparse-dev libmetis-dev libopenblas-serial-dev
  # bench/plot_benchmarks.py (matplotlib), tools/animate.py (matplotlib, Pillow
  # for GIFs): run them with /usr/bin/python3, which has these packages.
  python3 python3-matplotlib python3-pil
  # the Python module `import ipstep` (python/, docs/python.md): pybind11 for
  # /usr/bin/python3, NumPy arrays, and its tests (pytest)
  pybind11-dev python3-dev python3-numpy python3-pytest
  # ctest vtk_reader reads the frames back with VTK's own reader
  # (tests/io/vtk_reader_test.sh). ParaView (docs/paraview.md) is not needed.
  python3-vtk9
)
# python3-paraview conflicts with python3-vtk9 and has the same VTK modules:
# where it is installed, keep it (apt would remove it for python3-vtk9).
if dpkg -s python3-paraview > /dev/null 2>&1; then
  kept=()
  for package in "${packages[@]}"; do
    if [ "$package" != python3-vtk9 ]; then kept+=("$package"); fi
  done
  packages=("${kept[@]}")
fi
run_as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}
run_as_root apt-get update -qq
run_as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  "${packages[@]}" > /dev/null
echo "dependencies installed: ${packages[*]}"
