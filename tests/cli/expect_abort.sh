#!/usr/bin/env bash
# Usage: expect_abort.sh WORKDIR COMMAND...
# COMMAND (an MPI run in which rank 1 alone throws while rank 0 waits in a barrier, both holding an
# open parallel output file in WORKDIR/out) must end within 20 s with a non-zero exit code, print
# rank 1's message exactly once, and leave WORKDIR/out empty.
set -u
workdir=$1
shift
rm -rf "$workdir" && mkdir -p "$workdir/out" && cd "$workdir" || exit 1
start=$(date +%s)
"$@" out >stdout.txt 2>stderr.txt
rc=$?
elapsed=$(( $(date +%s) - start ))
cat stderr.txt
status=0
fail() { echo "FAIL: $*"; status=1; }
[[ $rc -ne 0 ]] || fail "exit code 0"
[[ $elapsed -le 20 ]] || fail "took ${elapsed} s"
n=$(grep -c 'error on rank 1 of 2: injected failure on rank 1' stderr.txt)
[[ $n -eq 1 ]] || fail "rank 1's message printed $n times"
grep -q 'error on rank 0' stderr.txt && fail "rank 0 reported an error of its own"
[[ -z $(ls -A out) ]] || fail "left in out/: $(ls -A out)"
[[ $status -eq 0 ]] && echo "PASS (exit code $rc after ${elapsed} s)"
exit $status
