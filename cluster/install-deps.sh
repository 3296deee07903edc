#!/usr/bin/env bash
# Installs the Debian 12 packages Clatter builds and tests with. Idempotent: when every package is
# already installed it only runs dpkg-query and exits (well under a second).
# Usage: cluster/install-deps.sh [--check]   (--check: list what is missing, exit 1 if anything is)
set -euo pipefail

packages=(
  # toolchain
  g++ make cmake pkg-config git
  # MPI and the numerical stack
  openmpi-bin libopenmpi-dev
  # HDF5 twice: parallel (MPI-IO) for clatter-bank, serial for clatter-synth (no MPI runtime)
  libhdf5-openmpi-dev libhdf5-dev
  libeigen3-dev libgsl-dev
  # PETSc/SLEPc (real, with MUMPS) for petsc/; TetGen for kernels/fem/ellipsoid_mesh.cpp; CGAL
  # (header-only) for the flat ellipsoids' mid-plane triangulation (kernels/fem/ellipse_triangulation.cpp)
  libpetsc-real3.18-dev libslepc-real3.18-dev libcgal-dev libtet1.5-dev
  # an optimized single-threaded BLAS/LAPACK behind MUMPS (through Debian's libblas.so.3
  # alternative): the reference BLAS factorizes a 35k-dof modal entry ~6x slower; serial, so
  # MPI ranks do not oversubscribe cores with BLAS threads
  libopenblas0-serial
  # LAPACK's headers-free link library: kernels/transfer's dense least squares (zgels), run by
  # the same OpenBLAS
  liblapack-dev
  # CHOLMOD (SuiteSparse): the supernodal Cholesky factor of kernels/fracture's quasistatic
  # stress solve (003 section 3.1)
  libsuitesparse-dev
  # small libraries the code uses
  libtoml11-dev libcli11-dev libspdlog-dev libfmt-dev nlohmann-json3-dev libsndfile1-dev
  # the synthesizer's kd-tree over the modal bank's ellipsoids (003 section 5.4; header only)
  libnanoflann-dev
  # clatter-sim (sim/): the rigid-body simulator behind the example scenes, and the Voronoi
  # pre-fracture of its plate and rocks
  libbullet-dev voro++-dev
  # tests and benchmarks; clang-14 and its libFuzzer runtime (libclang_rt.fuzzer) for the fuzz preset
  libgtest-dev libbenchmark-dev clang-14 libclang-rt-14-dev
  # analysis scripts (run with /usr/bin/python3)
  python3 python3-numpy python3-scipy python3-h5py python3-matplotlib
  # the Python module `clatter` (python/): pybind11's headers and CMake config, the interpreter's
  # headers, and pytest for its tests
  pybind11-dev python3-dev python3-pytest
  # the private single-node Slurm of the `slurm` tests (and the real thing on a workstation)
  slurmctld slurmd slurm-client munge
)

# One dpkg-query for all: packages it does not list as installed are missing.
installed=$(dpkg-query -W -f='${Package} ${Status}\n' "${packages[@]}" 2>/dev/null | awk '/ install ok installed$/ {print $1}' || true)
missing=()
for p in "${packages[@]}"; do
  grep -qx -- "$p" <<<"$installed" || missing+=("$p")
done

if [[ ${#missing[@]} -eq 0 ]]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
if [[ "${1:-}" == "--check" ]]; then
  echo "install-deps: missing: ${missing[*]}"
  exit 1
fi

echo "install-deps: installing ${#missing[@]} package(s): ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
echo "install-deps: done"
