#!/usr/bin/env bash
# The sweep engine's acceptance (docs/cluster.md, "Sweeps"): the bank's content hash is identical
# for (a) 1 rank, (b) 2 ranks, (c) 2 ranks as one group of 2, (d) 2 ranks stopped by SIGTERM and
# resumed; the interrupted run leaves only complete task files and releases its locks; a task that
# fails (an I/O error: its result path is taken by a folder) is recorded, the sweep goes on, the
# exit code is 4, `info` lists it, and --resume retries it into the same bank; --resume on a complete
# bank does nothing; (f) a SIGTERM while a task hears through its Kirchhoff surface stops it there.
# Usage: sweep_checks.sh CLATTER_BANK CONFIG SCRATCH MPIEXEC...
set -uo pipefail
# shellcheck source=interrupt_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/interrupt_lib.sh"
bank=$1 config=$2 scratch=$3
shift 3
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# Small enough for CI, slow enough (about a second per task) to be interrupted mid-sweep.
sets=(--set 'proxies.list_m=[[0.5, 0.5], [0.35, 0.2]]' --set 'solve.fields=[1, 4, 6]' --set grid.dx_m=0.02
      --set time.dt_s=3.3e-5)
run() {  # run NPROCS ARGS...: the sweep on NPROCS ranks
  local n=$1
  shift
  "${mpiexec[@]}" -n "$n" "$bank" pan -c "$config" "${sets[@]}" --progress-interval 0 "$@"
}
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }

# Bad sweep options: exit 2, one line, nothing created.
for bad in "--ranks-per-task 3" "--slice 2/2" "--slice x"; do
  # shellcheck disable=SC2086
  run 2 -o bad.h5 $bad > bad.log 2>&1
  code=$?
  [[ $code -eq 2 ]] || fail "$bad: exit $code, expected 2"
  [[ -z $(ls -A) || $(ls -A) == "bad.log" ]] || fail "$bad left files: $(ls -A)"
  echo "$bad: exit 2: $(grep error bad.log | head -1)"
done
rm -f bad.log

run 1 -o a.h5 > a.log 2>&1 || fail "1 rank: exit $? ($(tail -3 a.log))"
run 2 -o b.h5 > b.log 2>&1 || fail "2 ranks: exit $?"
run 2 -o c.h5 --ranks-per-task 2 > c.log 2>&1 || fail "2 ranks per task: exit $?"
[[ -e a.h5.tasks ]] && fail "a complete sweep left its results folder"
echo "(a) 1 rank:                $(sum a.h5)"
echo "(b) 2 ranks:               $(sum b.h5)"
echo "(c) 2 ranks per task:      $(sum c.h5)"

# (d) SIGTERM to the ranks once the first task has landed. Six ~1 s tasks on 2 groups: the signal,
# a fraction of a second after the first file, lands with at least two tasks not yet handed out:
# exit 3 (anything else fails), and tasks are left to the resume.
run 2 -o d.h5 > d1.log 2>&1 &
launcher=$!
interrupt_sweep "$launcher" 'd.h5.tasks/p*.h5' d1.log || fail "(d) was not interrupted"
grep -q "resume with:" d1.log || fail "no resume hint in the log"
[[ -e d.h5 ]] && fail "an interrupted sweep wrote the bank"
[[ -n $(compgen -G 'd.h5*.lock*') ]] && fail "the interrupted sweep left its locks: $(compgen -G 'd.h5*.lock*')"
stray=$(find . -name '.*tmp*')
[[ -z "$stray" ]] || fail "stray temporaries: $stray"
kept=$(find d.h5.tasks -name 'p*.h5' | wc -l)
for f in d.h5.tasks/p*.h5; do "$bank" checksum "$f" > /dev/null || fail "$f is not a complete HDF5 file"; done
[[ $kept -lt 6 ]] || fail "(d) the interrupted run finished all 6 tasks: nothing left to resume"
echo "(d) interrupted after $kept of 6 tasks (exit 3); no temporaries"
run 2 -o d.h5 > d2.log 2>&1 && fail "a second run without --resume must refuse the results folder"
grep -q "add --resume" d2.log || fail "no --resume hint"
run 2 -o d.h5 --resume > d3.log 2>&1 || fail "resume: exit $?"
grep -q "$kept already done" d3.log || fail "resume did not skip the $kept finished tasks"
echo "(d) resumed:               $(sum d.h5)"
[[ -e d.h5.tasks ]] && fail "the resumed sweep left its results folder"
# Resumed once more, the bank is whole and its task files are gone: nothing is solved or rewritten.
before=$(stat -c %Y.%s d.h5)
run 2 -o d.h5 --resume > d4.log 2>&1 || fail "resume of a complete bank: exit $?"
grep -q "nothing to resume" d4.log || fail "resume of a complete bank did not say so: $(tail -3 d4.log)"
grep -q "merge: wrote" d4.log && fail "resume of a complete bank solved and merged it again"
[[ $(stat -c %Y.%s d.h5) == "$before" && ! -e d.h5.tasks ]] || fail "resume of a complete bank touched it"
echo "(d) resumed again:         nothing to do, bank untouched"

# A failing task: its result path is a folder.
mkdir -p e.h5.tasks/p001-f4.h5
run 2 -o e.h5 --resume > e1.log 2>&1
code=$?
[[ $code -eq 4 ]] || fail "a failed task: exit $code, expected 4"
"$bank" info e.h5 > e-info.txt || fail "info of a bank with a failed task"
grep -q "5 of 6 tasks" e-info.txt && grep -q "failed: *p001-f4" e-info.txt || fail "info does not list the failed task: $(cat e-info.txt)"
echo "failed task: exit 4, info lists it"
rmdir e.h5.tasks/p001-f4.h5
run 2 -o e.h5 --resume > e2.log 2>&1 || fail "retry of the failed task: exit $?"
echo "(e) failed, then retried:  $(sum e.h5)"

ref=$(sum a.h5)
for f in b.h5 c.h5 d.h5 e.h5; do [[ $(sum $f) == "$ref" ]] || fail "$f differs from a.h5"; done
echo "all 5 banks have the same content hash $ref"

# (f) SIGTERM while a task hears through its Kirchhoff surface, which its group's rank 0 does alone
# while the other waits: the cigar's field 1 at 1 cm cells and a 0.15 ms pulse (near the paper's), one group
# of 2 ranks, about 1700 directions to hear (minutes). The signal goes out once the first line of
# the hearing's progress is in the log; the task must stop there (exit 3, no task file), not hear
# to the end and land.
paper=(--set 'proxies.list_m=[[0.025, 0.025]]' --set 'solve.fields=[1]' --set grid.dx_m=0.01
       --set time.dt_s=1.6e-05 --set pulse.h_s=0.00015 --set fit.max_directions=2500)
"${mpiexec[@]}" -n 2 "$bank" pan -c "$config" "${paper[@]}" --ranks-per-task 2 --progress-interval 0.2 -o f.h5 > f.log 2>&1 &
launcher=$!
for _ in $(seq 6000); do grep -q "hearing direction" f.log && break; kill -0 "$launcher" 2>/dev/null || break; sleep 0.1; done
grep -q "hearing direction" f.log || fail "(f) no hearing progress within 600 s: $(tail -3 f.log)"
ranks=$(bank_ranks "$launcher")
[[ -n $ranks ]] || fail "(f) the sweep ended before it could be signalled"
# shellcheck disable=SC2086
kill -TERM $ranks
wait "$launcher"
code=$?
[[ $code -eq 3 ]] || fail "(f) exit $code after SIGTERM while hearing, expected 3: $(tail -3 f.log)"
[[ -z $(compgen -G 'f.h5.tasks/p*.h5') && ! -e f.h5 ]] || fail "(f) the interrupted task landed: it heard to the end"
grep -q "interrupted by signal 15" f.log || fail "(f) exit 3 but no 'interrupted by signal 15' in the log: $(tail -3 f.log)"
echo "(f) interrupted while hearing, after $(grep -c 'hearing direction' f.log) progress lines: exit 3, no task file"
