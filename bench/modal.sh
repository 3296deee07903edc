#!/usr/bin/env bash
# The modal-bank benchmark of docs/benchmarks.md ("Modal bank"): one entry at the default
# settings (configs/modal.toml: f_max = 4 f_1, 3 elements per shear wavelength) on 1 rank and on
# 1 group of 2 ranks, REPEAT times each: dofs, modes, shifts, stage times (pre-solve, assembly,
# MUMPS factorizations, slicing, basis rule), MUMPS and resident memory per rank, wall time.
# Usage: bench/modal.sh [BUILD_DIR] [REPEAT] [A,B,C]   (default: the sphere)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
repeat=${2:-1}
axes=${3:-0.5773502691896258,0.5773502691896258,0.5773502691896258}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for np in 1 2; do
  for r in $(seq "$repeat"); do
    rm -rf "$out/m.h5" "$out/m.h5.tasks"
    start=$(date +%s.%N)
    log=$(mpiexec -n "$np" "$build/bin/clatter-bank" modal -c configs/modal.toml --set "patch.samples=[[${axes}]]" \
          --ranks-per-task "$np" -o "$out/m.h5" --progress-interval 0 --log-view 2>&1 </dev/null)
    wall=$(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN {printf "%.1f", e - s}')
    row=$(/usr/bin/python3 - "$out/m.h5" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1])
e, c = f["/entries/0000"], f["/provenance/run/entries/0000"].attrs
print(f"dofs={e['mesh'].attrs['dofs']} modes={e['frequencies_hz'].shape[0]} shifts={e['solve'].attrs['shifts']} "
      f"estimate_s={c['estimate_s']:.1f} mesh_s={c['mesh_s']:.2f} assembly_s={c['assembly_s']:.2f} "
      f"solve_s={c['solve_s']:.1f} total_s={c['total_s']:.1f} mumps_mb_per_rank={c['factor_memory_mb']:.0f} "
      f"resident_mb_max_rank={c['memory_max_mb']:.0f}")
PY
)
    echo "ranks=$np run=$r wall_s=$wall $row factor_numeric_s=$(awk '/factor numeric/ {s += $(NF-3)} END {printf "%.1f", s}' <<<"$log")"
  done
done
