#!/usr/bin/env bash
# The FDTD benchmark of docs/benchmarks.md: bench/fdtd-256.toml (256^3 cells, ellipsoid, 6-cell PML,
# 200 steps) on 1 and 2 ranks, REPEAT times each, printing each run and the medians.
# Usage: bench/fdtd.sh [BUILD_DIR] [REPEAT]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
repeat=${2:-3}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for np in 1 2; do
  rates=() waits=()
  for r in $(seq "$repeat"); do
    log=$(mpiexec -n "$np" --bind-to core "$build/bin/clatter-bank" solve -c bench/fdtd-256.toml -o "$out/raw.h5" \
          --progress-interval 0 --log-view 2>&1)
    rate=$(sed -n 's/.*: \([0-9.e+]*\) cell-updates\/s$/\1/p' <<<"$log")
    wait=$(awk '/halo wait/ {print $NF}' <<<"$log")
    echo "ranks=$np run=$r cell-updates/s=$rate halo-wait-%=$wait"
    rates+=("$rate") waits+=("$wait")
  done
  median=$(printf '%s\n' "${rates[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  wmedian=$(printf '%s\n' "${waits[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  echo "MEDIAN ranks=$np cell-updates/s=$median (= $(awk -v r="$median" 'BEGIN {printf "%.1f", r * 12 / 1e9}') GB/s at 12 B/cell) halo-wait-%=$wmedian"
done
