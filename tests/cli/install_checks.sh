#!/usr/bin/env bash
# Usage: install_checks.sh BUILD_DIR SCRATCH SERIAL_HDF5_LIB MPI_HDF5_LIB PYTHON MPIEXEC...
# Installs BUILD_DIR into SCRATCH/prefix and checks the installed tree: the programs run from
# there (clatter-bank --version and a 2-rank field job, clatter-synth --help), the data and docs
# are in place, clatter-synth and the Python module load no MPI library and the serial HDF5,
# clatter-bank the MPI HDF5 (the two HDF5 libraries CMake found, known to the loader by their
# SONAMEs); PYTHON imports the installed module from PREFIX/lib/python3.X/dist-packages.
set -u
build=$1 scratch=$2
soname() { readelf -d "$1" | sed -n 's/.*Library soname: \[\(.*\)\]/\1/p'; }
serial_hdf5=$(soname "$3") mpi_hdf5=$(soname "$4") python=$5
shift 5
mpiexec=("$@")
prefix=$scratch/prefix
status=0
fail() { echo "FAIL: $*"; status=1; }
run() {  # run WHAT COMMAND...: COMMAND must exit 0
  local what=$1
  shift
  "$@" >"$scratch/out.txt" 2>&1 || { cat "$scratch/out.txt"; fail "$what exited $?"; return 1; }
}

rm -rf "$scratch" && mkdir -p "$scratch" || exit 1
run "cmake --install" cmake --install "$build" --prefix "$prefix" || { echo "install failed"; exit 1; }

for f in bin/clatter-bank bin/clatter-synth share/clatter/configs/pan-demo.toml share/clatter/scenes/demo.json \
         share/doc/clatter/formats.md share/doc/clatter/README.md; do
  [[ -e $prefix/$f ]] || fail "not installed: $f"
done

cd "$scratch" || exit 1
run "installed clatter-bank --version" "$prefix/bin/clatter-bank" --version &&
  { grep -q "^clatter-bank " out.txt || fail "clatter-bank --version: no version line"; }
run "installed clatter-bank field on 2 ranks" "${mpiexec[@]}" -n 2 "$prefix/bin/clatter-bank" field \
    --set grid.n_cells=8 -o "$scratch/field.h5" &&
  { [[ -s $scratch/field.h5 ]] || fail "clatter-bank field wrote no $scratch/field.h5"; }
run "installed clatter-synth --help" "$prefix/bin/clatter-synth" --help

# What the dynamic loader resolves (ldd: the whole tree of NEEDED entries).
synth_libs=$(ldd "$prefix/bin/clatter-synth") || fail "ldd clatter-synth exited $?"
bank_libs=$(ldd "$prefix/bin/clatter-bank") || fail "ldd clatter-bank exited $?"
if grep -E "libmpi|libopen-rte|libopen-pal|hdf5_openmpi|not found" <<<"$synth_libs"; then
  fail "clatter-synth loads MPI, the MPI HDF5 or a missing library (above)"
fi
[[ -n $serial_hdf5 && -n $mpi_hdf5 && $serial_hdf5 != "$mpi_hdf5" ]] ||
  fail "cannot tell the two HDF5 libraries apart by SONAME: '$serial_hdf5', '$mpi_hdf5'"
grep -qF "$serial_hdf5 " <<<"$synth_libs" || fail "clatter-synth does not load the serial HDF5 ($serial_hdf5)"
grep -qF "$mpi_hdf5 " <<<"$bank_libs" || fail "clatter-bank does not load the MPI HDF5 ($mpi_hdf5)"
grep -qE "libmpi" <<<"$bank_libs" || fail "clatter-bank does not load libmpi"
if grep -F -e "$serial_hdf5 " -e "not found" <<<"$bank_libs"; then
  fail "clatter-bank loads the serial HDF5 or a missing library (above)"
fi

# The Python module: where Debian's python3 looks under a prefix, importable from there alone.
site=$prefix/lib/$("$python" -c 'import sys; print(f"python{sys.version_info[0]}.{sys.version_info[1]}")')/dist-packages
module=$(ls "$site"/clatter/_clatter*.so 2>/dev/null | head -1)
[[ -f $site/clatter/__init__.py && -n $module ]] || fail "the Python module is not installed in $site/clatter"
if [[ -n $module ]]; then
  run "import the installed module" env PYTHONPATH="$site" "$python" -c \
      'import clatter, sys; print(clatter.__file__); print(clatter.version)' &&
    { grep -qF "$site/clatter/__init__.py" out.txt || fail "python imported another clatter: $(head -1 out.txt)"; }
  module_libs=$(ldd "$module") || fail "ldd $module exited $?"
  if grep -E "libmpi|libopen-rte|libopen-pal|hdf5_openmpi|not found" <<<"$module_libs"; then
    fail "the Python module loads MPI, the MPI HDF5 or a missing library (above)"
  fi
  grep -qF "$serial_hdf5 " <<<"$module_libs" || fail "the Python module does not load the serial HDF5 ($serial_hdf5)"
fi

[[ $status -eq 0 ]] && echo "install checks: all passed"
exit $status
