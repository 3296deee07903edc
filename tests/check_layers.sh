#!/usr/bin/env bash
# The dependency rules of docs/architecture.md, checked on #include lines and, given the
# link_libraries.txt CMake writes into the build tree (cmake/LinkReport.cmake), on what each
# target links (directly or through the libraries it links):
#   kernels/ uses no MPI, HDF5, config or logging code; mpi/ knows no physics, HDF5 or config;
#   core/ depends on nothing of Clatter's; io/ knows no physics and no MPI layer, and its serial
#   build no MPI at all; synth/ is serial (no MPI); model/ is plain data (std only); no binary links both builds of io;
#   petsc/ knows no physics, HDF5 or config, and only banks/ (and tests/) use it or PETSc;
#   python/ (the module) is serial like synth/, on synth/, io/ and kernels/;
#   sim/ (clatter-sim) is serial and alone uses Bullet and voro++; the synthesizer knows neither;
#   cli/ (the command-line scaffolding) and sweep/ (the sweep engine) know no physics and no bank
#   kind; a bank kind's folder banks/NAME/ includes no other kind's, and outside it only the
#   registry (banks/registry.cpp) includes it.
# Usage: check_layers.sh [BUILD/link_libraries.txt]
set -u
links_file=${1:-}
cd "$(dirname "$0")/.."
status=0
forbid() {  # forbid DIR REGEX WHY
  local hits
  hits=$(grep -nE "^\s*#\s*include\s*[<\"]($2)" -r "$1" --include='*.hpp' --include='*.cpp' --include='*.h' || true)
  if [[ -n $hits ]]; then echo "FAIL: $1 $3:"; echo "$hits"; status=1; fi
}
forbid kernels 'mpi\.h|hdf5\.h|H5|toml|io/|mpi/|banks/|sweep/|cli/|spdlog|CLI/|petsc|slepc' "must not use MPI, PETSc, HDF5, config or logging code"
forbid petsc 'hdf5\.h|H5|toml|io/|kernels/|banks/|sweep/|cli/|synth/|model/' "must not know physics, HDF5 or config"
# PETSc and SLEPc (and petsc/) belong to petsc/ and the bank kinds that use it.
for dir in core model mpi io kernels synth cli sweep; do
  forbid $dir 'petsc|slepc' "must not use PETSc (only petsc/ and banks/ may)"
done
forbid mpi 'hdf5\.h|H5|toml|io/|kernels/|banks/|sweep/|cli/' "must not know physics, HDF5 or config"
forbid core 'mpi\.h|hdf5\.h|toml|io/|mpi/|kernels/|banks/|sweep/|cli/|model/|synth/|spdlog' "must depend on nothing of Clatter's"
forbid io 'kernels/|banks/|sweep/|cli/|mpi/' "must not depend on physics or the MPI layer"
# model/: the standard library and model/ itself only. Angle includes of other libraries have a '/'
# or '.' (<fmt/...>, <mpi.h>, <Eigen/Dense>); quoted includes are all Clatter's.
hits=$(grep -nE '^\s*#\s*include\s*[<"]("|[A-Za-z0-9_]+[/.])' -r model | grep -vE ':\s*#\s*include\s*"model/' || true)
if [[ -n $hits ]]; then echo "FAIL: model must be plain data: the standard library only:"; echo "$hits"; status=1; fi
forbid synth 'mpi\.h|mpi/|banks/|sweep/|cli/|io/h5_parallel' "must stay serial"
# The Python module is clatter-synth's twin: serial, on the synthesizer, io (serial) and kernels.
forbid python 'mpi\.h|mpi/|banks/|sweep/|cli/|io/h5_parallel|petsc|slepc|sim/|bt[A-Z]|voro\+\+' "(the Python module) must stay serial, on synth/, io/ and kernels/"
# The synthesizer reads scenes; the simulator that makes them (sim/) is a separate program.
forbid synth 'sim/|bt[A-Z]|Bullet|LinearMath|voro\+\+' "must stay free of the rigid-body simulator"
forbid sim 'mpi\.h|mpi/|banks/|sweep/|cli/|synth/|io/h5_parallel|petsc|slepc' "must stay serial and apart from the synthesizer"
for dir in core model mpi io kernels synth cli sweep banks petsc; do
  forbid $dir 'bt[A-Z]|BulletCollision|BulletDynamics|LinearMath|voro\+\+' "must not use Bullet or voro++ (only sim/ may)"
done
for dir in cli sweep banks; do
  forbid $dir 'synth/|sim/' "must not depend on the synthesizer or the simulator (a bank's data model is in model/)"
done
forbid cli 'kernels/|banks/|sweep/|model/' "(the command-line scaffolding) must know no physics and no bank kind"
forbid sweep 'kernels/|banks/' "(the sweep engine) must know no physics and no bank kind"
# A kind's folder is its own: no other kind includes it, and of the shared code only the registry does.
for kind in banks/*/; do
  kind=${kind%/}
  hits=$(grep -nE "^\s*#\s*include\s*\"$kind/" -r banks --include='*.hpp' --include='*.cpp' |
         grep -vE "^($kind/|banks/registry\.cpp:)" || true)
  if [[ -n $hits ]]; then echo "FAIL: $kind is included from outside it (only banks/registry.cpp may):"; echo "$hits"; status=1; fi
done
# Only io/h5_parallel.* (built into clatter_io_mpi alone) may see MPI inside io/.
hits=$(grep -nE '^\s*#\s*include\s*<mpi\.h>' -r io --include='*.hpp' --include='*.cpp' | grep -v '^io/h5_parallel\.' || true)
if [[ -n $hits ]]; then echo "FAIL: io/ includes mpi.h outside io/h5_parallel.*:"; echo "$hits"; status=1; fi

if [[ -n $links_file ]]; then
  if [[ ! -r $links_file ]]; then
    echo "FAIL: cannot read $links_file (configure the build first)"
    exit 1
  fi
  declare -A direct=()
  while IFS= read -r line; do
    [[ $line == *=* ]] && direct[${line%%=*}]=${line#*=}
  done <"$links_file"
  # closure TARGET: every name TARGET links, following the targets named in the file.
  closure() {
    local -A seen=()
    local todo=("$1") t d
    while [[ ${#todo[@]} -gt 0 ]]; do
      t=${todo[0]}
      todo=("${todo[@]:1}")
      IFS=';' read -ra deps <<<"${direct[$t]:-}"
      for d in "${deps[@]}"; do
        d=${d#\$<LINK_ONLY:}
        d=${d%>}
        [[ -z $d || -n ${seen[$d]:-} ]] && continue
        seen[$d]=1
        todo+=("$d")
      done
    done
    printf '%s\n' "${!seen[@]}"
  }
  # forbid_link TARGET REGEX WHY: no name TARGET links may match REGEX (whole-name, extended).
  forbid_link() {
    if [[ -z ${direct[$1]+set} ]]; then echo "FAIL: $1 not in $links_file"; status=1; return; fi
    local hits
    hits=$(closure "$1" | grep -E "^($2)$" | sort | tr '\n' ' ' || true)
    if [[ -n $hits ]]; then echo "FAIL: $1 $3: links $hits"; status=1; fi
  }
  mpi='MPI::MPI_C|MPI::MPI_CXX|.*/libmpi[^/]*|clatter_io_mpi|clatter_hdf5_mpi|clatter_mpi|clatter_cli|clatter_sweep|clatter_banks'
  hdf5='clatter_hdf5_serial|clatter_hdf5_mpi|.*/libhdf5[^/]*|clatter_io|clatter_io_mpi'
  ours='clatter_[a-z_]+|clatter-[a-z-]+'
  forbid_link clatter_core "$ours|$mpi|$hdf5|toml11::toml11|spdlog::spdlog|CLI11::CLI11" "must depend on nothing of Clatter's"
  forbid_link clatter_kernels "$mpi|$hdf5|toml11::toml11|spdlog::spdlog|CLI11::CLI11" \
    "must not use MPI, HDF5, config or logging code"
  forbid_link clatter_mpi "$hdf5|toml11::toml11|clatter_kernels|clatter_cli|clatter_sweep|clatter_banks" "must not know physics, HDF5 or config"
  forbid_link clatter_petsc "$hdf5|toml11::toml11|clatter_kernels|clatter_cli|clatter_sweep|clatter_banks|clatter_synth" "must not know physics, HDF5 or config"
  petsc='clatter_petsc|PkgConfig::PETSC|PkgConfig::SLEPC|.*/lib(petsc|slepc)[^/]*'
  for t in clatter_core clatter_mpi clatter_io clatter_io_mpi clatter_kernels clatter_synth clatter-synth clatter_cli clatter_sweep; do
    forbid_link $t "$petsc" "must not link PETSc (only petsc/ and banks/ may)"
  done
  for io in clatter_io clatter_io_mpi; do
    forbid_link $io "clatter_kernels|clatter_cli|clatter_sweep|clatter_banks|clatter_mpi|clatter_synth" "must not depend on physics or the MPI layer"
  done
  forbid_link clatter_io "$mpi" "(the serial io) must not link MPI"
  forbid_link clatter_synth "$mpi" "must stay serial"
  forbid_link clatter-synth "$mpi" "must stay serial"
  forbid_link clatter_python "$mpi|$petsc|clatter_sim|clatter_specs" "(the Python module) must stay serial, on synth/, io/ and kernels/"
  forbid_link clatter_banks "clatter_synth" "must not depend on the synthesizer"
  forbid_link clatter_cli "clatter_kernels|clatter_sweep|clatter_banks|clatter_specs" "must know no physics and no bank kind"
  forbid_link clatter_sweep "clatter_kernels|clatter_banks|clatter_specs" "must know no physics and no bank kind"
  for t in clatter_synth clatter-synth clatter_banks clatter_kernels clatter_io; do
    forbid_link $t "clatter_sim|PkgConfig::BULLET|clatter_voro" "must not link the rigid-body simulator (only sim/ may)"
  done
  forbid_link clatter_sim "$mpi|$petsc|clatter_synth|clatter_banks" "must stay serial and apart from the synthesizer"
  forbid_link clatter-sim "$mpi|$petsc|clatter_synth|clatter_banks" "must stay serial and apart from the synthesizer"
  # The specs and the config are checked by the fuzz harnesses, which link neither MPI nor HDF5.
  forbid_link clatter_specs "$mpi|$hdf5|CLI11::CLI11|spdlog::spdlog" "must stay free of MPI, HDF5 and the command line"
  forbid_link clatter_config "$mpi|$hdf5|clatter_kernels" "must stay free of MPI, HDF5 and physics"
  # Two builds of the same sources (io/CMakeLists.txt, synth/CMakeLists.txt) in one binary
  # would be one definition each of two different things.
  for t in "${!direct[@]}"; do
    all=$(closure "$t")
    if grep -qx clatter_io <<<"$all" && grep -qx clatter_io_mpi <<<"$all"; then
      echo "FAIL: $t links both clatter_io and clatter_io_mpi"; status=1
    fi
  done
fi
[[ $status -eq 0 ]] && echo "PASS: layer rules hold"
exit $status
