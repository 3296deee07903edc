#!/usr/bin/env bash
# A shipped example config builds a bank: `clatter-bank KIND -c CONFIG`, shrunk by --set overrides
# to a task or a few of seconds on one rank, exits 0, and `clatter-bank info` of its bank shows
# every PATTERN (grep -E): what the config asked for (material, proxies, grounds, grid), each
# expected value derived independently in tests/CMakeLists.txt. A PATTERN `awk:PROGRAM` is instead
# an awk program over the info output whose exit status decides.
# Usage: example_config_checks.sh CLATTER_BANK SCRATCH KIND CONFIG [OVERRIDE]... -- PATTERN...
set -uo pipefail
bank=$1 scratch=$2 kind=$3 config=$4
shift 4
sets=()
while [[ $# -gt 0 && $1 != -- ]]; do sets+=("$1"); shift; done
[[ $# -gt 0 ]] && shift
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
start=$(date +%s.%N)
"$bank" "$kind" -c "$config" "${sets[@]}" -o out.h5 --progress-interval 0 </dev/null > run.log 2>&1 ||
  fail "$kind -c $config: exit $? ($(tail -3 run.log))"
echo "$kind -c $(basename "$config"), shrunk: $(awk -v s="$start" -v e="$(date +%s.%N)" 'BEGIN { printf "%.1f", e - s }') s"
"$bank" info out.h5 > info.log 2>&1 || fail "info: exit $? ($(cat info.log))"
cat info.log
for pattern in "$@"; do
  if [[ $pattern == awk:* ]]; then
    awk "${pattern#awk:}" info.log || fail "info fails the check ${pattern#awk:}"
  else
    grep -Eq -- "$pattern" info.log || fail "info does not show '$pattern'"
  fi
done
echo "example config checks: all passed"
