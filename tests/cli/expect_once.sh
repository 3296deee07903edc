#!/usr/bin/env bash
# Usage: expect_once.sh TEXT COMMAND...: COMMAND succeeds and TEXT appears in its stdout exactly once
# (under mpiexec: only rank 0 prints).
set -u
text=$1
shift
out=$("$@") || { echo "FAIL: exit code $?"; exit 1; }
n=$(grep -cF -- "$text" <<<"$out")
echo "$out"
[[ $n -eq 1 ]] || { echo "FAIL: '$text' printed $n times"; exit 1; }
echo PASS
