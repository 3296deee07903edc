#!/usr/bin/env bash
# Usage: expect_error.sh CODE WORKDIR 'PATTERN|PATTERN...' -- COMMAND...
# Runs COMMAND in an empty WORKDIR. Passes when it exits with CODE; its own stderr (lines starting
# with "clatter-") is exactly one line containing every PATTERN (fixed strings); without mpiexec
# nothing else is printed on stderr; and WORKDIR is still empty: no output, no temporary.
set -u
code=$1 workdir=$2 patterns=$3
shift 3
[[ $1 == -- ]] && shift
rm -rf "$workdir" && mkdir -p "$workdir" && cd "$workdir" || exit 1
"$@" >stdout.txt 2>stderr.txt
rc=$?
status=0
fail() { echo "FAIL: $*"; status=1; }
[[ $rc -eq $code ]] || fail "exit code $rc, expected $code"
own=$(grep -c '^clatter-' stderr.txt)
[[ $own -eq 1 ]] || fail "$own lines from the program on stderr, expected 1"
if [[ $(basename "$1") != mpiexec && $(basename "$1") != mpirun ]]; then
  [[ $(wc -l <stderr.txt) -eq 1 ]] || fail "stderr has more than the one error line"
fi
line=$(grep '^clatter-' stderr.txt | head -1)
IFS='|' read -ra parts <<<"$patterns"
for p in "${parts[@]}"; do
  [[ $line == *"$p"* ]] || fail "error line lacks '$p'"
done
left=$(ls -A | grep -v -x -e stdout.txt -e stderr.txt)
[[ -z $left ]] || fail "files left behind: $left"
echo "command: $*"
echo "stderr:"; sed 's/^/  /' stderr.txt
[[ $status -eq 0 ]] && echo "PASS"
exit $status
