#!/usr/bin/env bash
# Usage: expect_output.sh REGEX... -- COMMAND...: COMMAND exits 0 and every extended REGEX matches
# some line of its output (stdout and stderr: the logs are on stderr). (What must not appear is the CTest's FAIL_REGULAR_EXPRESSION.)
set -u
patterns=()
while [[ $# -gt 0 && $1 != -- ]]; do patterns+=("$1"); shift; done
[[ $# -gt 1 ]] || { echo "usage: expect_output.sh REGEX... -- COMMAND..."; exit 2; }
shift
out=$("$@" 2>&1)
rc=$?
echo "$out"
[[ $rc -eq 0 ]] || { echo "FAIL: exit code $rc"; exit 1; }
status=0
for p in "${patterns[@]}"; do
  grep -qE -- "$p" <<<"$out" || { echo "FAIL: no line matches '$p'"; status=1; }
done
exit $status
