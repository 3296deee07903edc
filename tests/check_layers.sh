#!/usr/bin/env bash
# The dependency rules of docs/architecture.md, checked on #include lines:
#   kernels/ uses no MPI, HDF5, config or logging code; mpi/ knows no physics, HDF5 or config;
#   core/ depends on nothing of Clatter's; synth/ is serial (no MPI); model/ is plain data (std only).
set -u
cd "$(dirname "$0")/.."
status=0
forbid() {  # forbid DIR REGEX WHY
  local hits
  hits=$(grep -nE "^\s*#\s*include\s*[<\"]($2)" -r "$1" --include='*.hpp' --include='*.cpp' --include='*.h' || true)
  if [[ -n $hits ]]; then echo "FAIL: $1 $3:"; echo "$hits"; status=1; fi
}
forbid kernels 'mpi\.h|hdf5\.h|H5|toml|io/|mpi/|jobs/|spdlog|CLI/' "must not use MPI, HDF5, config or logging code"
forbid mpi 'hdf5\.h|H5|toml|io/|kernels/|jobs/' "must not know physics, HDF5 or config"
forbid core 'mpi\.h|hdf5\.h|toml|io/|mpi/|kernels/|jobs/|spdlog' "must depend on nothing of Clatter's"
forbid io 'kernels/|jobs/|mpi/' "must not depend on physics or the MPI layer"
forbid synth 'mpi\.h|mpi/|jobs/' "must stay serial"
# model/: the standard library only. Angle includes of other libraries have a '/' or '.' (<fmt/...>,
# <mpi.h>, <Eigen/Dense>); quoted includes are all Clatter's.
forbid model '"|[A-Za-z0-9_]+[/.]' "must be plain data: the standard library only"
[[ $status -eq 0 ]] && echo "PASS: layer rules hold"
exit $status
