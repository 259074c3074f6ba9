#!/usr/bin/env bash
# Installs ipstep's build and test dependencies from Debian's packages.
# Nothing is downloaded at build time; this is the only install step.
set -euo pipefail
packages=(
  cmake g++ make
  libceres-dev libeigen3-dev libgoogle-glog-dev libgflags-dev
  libgtest-dev libbenchmark-dev nlohmann-json3-dev
  libgmsh-dev  # elastic solids: meshing and .msh files (mesh/gmsh_mesh.h)
  # projected_newton's sparse Cholesky: CHOLMOD (SuiteSparse) with METIS, on
  # OpenBLAS (solver/sparse_cholesky.cc)
  libsuitesparse-dev libmetis-dev libopenblas-serial-dev
  # bench/plot_benchmarks.py (matplotlib), tools/animate.py (matplotlib, Pillow
  # for GIFs): run them with /usr/bin/python3, which has these packages.
  python3 python3-matplotlib python3-pil
  # the Python module `import ipstep` (python/, docs/python.md): pybind11 for
  # /usr/bin/python3, NumPy arrays, and its tests (pytest)
  pybind11-dev python3-dev python3-numpy python3-pytest
)
run_as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}
run_as_root apt-get update -qq
run_as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  "${packages[@]}" > /dev/null
echo "dependencies installed: ${packages[*]}"
