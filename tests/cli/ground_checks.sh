#!/usr/bin/env bash
# The ground bank end to end (docs/ground.md, docs/bank-format.md "Ground bank"):
#  (a) 2 ranks, (b) 1 rank and (e) 2 ranks stopped by SIGTERM once a task has landed and resumed
#  give the same content hash (tasks are deterministic and independent of who runs them); a rerun
#  with --resume on a complete results folder leaves the bank as it was;
#  `info` lists the materials and the grid; `merge` of a kept results folder rebuilds the bank;
#  ground_checks.py then reads the bank with h5py: layout, shapes, attributes and the physics.
# Usage: ground_checks.sh CLATTER_BANK CONFIG PYTHON CHECKS_PY SCRATCH MPIEXEC...
set -uo pipefail
# shellcheck source=interrupt_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/interrupt_lib.sh"
bank=$1 config=$2 python=$3 checks=$4 scratch=$5
shift 5
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
run() {  # run NPROCS ARGS...
  local n=$1
  shift
  "${mpiexec[@]}" -n "$n" "$bank" ground -c "$config" --progress-interval 0 "$@" </dev/null
}
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }

run 2 -o a.h5 --keep-results > a.log 2>&1 || fail "2 ranks: exit $? ($(tail -3 a.log))"
run 1 -o b.h5 > b.log 2>&1 || fail "1 rank: exit $? ($(tail -3 b.log))"

# (e) SIGTERM to the ranks once the first task has landed, then --resume. The four tasks are
# uneven: steel at 45 deg is ~4.5 s (its volume series), the other three < 1 s together (at 90 deg
# the series is short). On 2 groups one takes steel-el00 and the other the rest, whose first file
# lands within a second: the signal comes while steel-el00's volume series has seconds to go, and
# its check before the first eta stops it. So the sweep must exit 3 (anything else fails) without
# steel-el00, and the resume computes what is left.
run 2 -o e.h5 > e1.log 2>&1 &
launcher=$!
interrupt_sweep "$launcher" 'e.h5.tasks/*-el*.h5' e1.log || fail "(e) was not interrupted"
[[ -e e.h5 ]] && fail "an interrupted sweep wrote the bank"
[[ -e e.h5.tasks/steel-el00.h5 ]] && fail "(e) the long task steel-el00 finished: the signal came late"
kept=$(compgen -G 'e.h5.tasks/*-el*.h5' | wc -l)
echo "(e) interrupted after $kept task file(s): $(grep -m1 -o 'interrupted by signal.*' e1.log | cut -d';' -f1)"
run 2 -o e.h5 --resume > e2.log 2>&1 || fail "resume: exit $? ($(tail -3 e2.log))"
grep -q "sweep: $((4 - kept)) tasks in this run (4 of 4 in slice 0/1, $kept already done)" e2.log ||
  fail "(e) the resume did not compute the $((4 - kept)) tasks left: $(grep -m1 'tasks in this run' e2.log)"
# A rerun of the complete, kept sweep with --resume computes nothing and writes the same bank.
run 2 -o a.h5 --keep-results --resume > a2.log 2>&1 || fail "rerun with --resume: exit $? ($(tail -3 a2.log))"
grep -q "0 tasks in this run" a2.log || echo "note: the rerun found tasks to do: $(grep -m1 'tasks in this run' a2.log)"
"$bank" merge --results a.h5.tasks -o m.h5 > m.log 2>&1 || fail "merge: exit $? ($(tail -3 m.log))"

echo "(a) 2 ranks:                $(sum a.h5)"
echo "(b) 1 rank:                 $(sum b.h5)"
echo "(e) 2 ranks, resumed:       $(sum e.h5)"
echo "(m) merged from (a)'s tasks: $(sum m.h5)"
[[ $(sum a.h5) == "$(sum b.h5)" ]] || fail "(a) and (b) differ"
[[ $(sum a.h5) == "$(sum e.h5)" ]] || fail "(a) and (e) differ"
[[ $(sum a.h5) == "$(sum m.h5)" ]] || fail "(a) and (m) differ"

"$bank" info a.h5 > info.log 2>&1 || fail "info: exit $?"
cat info.log
grep -q "ground bank (format clatter-ground-bank v2), 2 materials" info.log || fail "info: $(head -1 info.log)"
grep -q "elevations \[deg\]: 45 90; 3 etas in \[0.05, 0.2\]" info.log || fail "info does not show the grid"
grep -q "4 of 4 tasks (material x elevation) in the bank, 0 failed" info.log || fail "info: no sweep line"

"$python" "$checks" a.h5 || fail "the bank's h5py checks"
echo "ground checks: all passed"
