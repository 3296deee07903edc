#!/usr/bin/env bash
# run_fuzzer.sh FUZZER CORPUS SCRATCH SECONDS: every input of CORPUS (regressions included), then
# SECONDS of fuzzing ($CLATTER_FUZZ_SECONDS instead when set: make test's shorter runs). New inputs and crash reproducers go to SCRATCH, emptied first so that every
# run starts from the committed corpus and takes the same time; CORPUS is only read. libFuzzer
# exits non-zero on any crash, leak, timeout or sanitizer report.
set -euo pipefail
fuzzer=$1 corpus=$2 scratch=$3 seconds=${CLATTER_FUZZ_SECONDS:-$4}
rm -rf "$scratch/new"
mkdir -p "$scratch/new" "$scratch/artifacts"
exec "$fuzzer" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix="$scratch/artifacts/" "$scratch/new" "$corpus"
