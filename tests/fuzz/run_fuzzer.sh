#!/usr/bin/env bash
# run_fuzzer.sh FUZZER CORPUS SCRATCH SECONDS: every input of CORPUS (regressions included) and
# of earlier runs, then SECONDS of fuzzing. New inputs and crash reproducers go to SCRATCH, never
# into CORPUS. libFuzzer exits non-zero on any crash, leak, timeout or sanitizer report.
set -euo pipefail
fuzzer=$1 corpus=$2 scratch=$3 seconds=$4
mkdir -p "$scratch/new" "$scratch/artifacts"
exec "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$scratch/artifacts/" "$scratch/new" "$corpus"
