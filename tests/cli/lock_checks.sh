#!/usr/bin/env bash
# Banks are never lost (docs/cluster.md, "One writer per output"). Against a straight run's
# content hash:
#   (a) while a sweep holds its output, a second pan, a --resume and a merge on it each exit 2 with
#       one line naming the holder (host, PID, start time), compute nothing and change nothing;
#       the first then finishes the bank. The holder is stopped (SIGSTOP) meanwhile, so it is
#       certainly alive whatever the machine's speed.
#   (b) a holder killed with SIGKILL leaves a stale lock; --resume breaks it and completes.
#   (c) a lock of another host: broken once its heartbeat is older than CLATTER_LOCK_STALE_S,
#       respected while it is fresh.
#   (d) slices of one sweep run side by side; a whole run or a merge beside a live slice is refused.
#   (e) a partial merge never replaces a complete bank (--force does); a bank of another sweep is
#       not replaced, and a pan run says so before it computes anything; a task file of another
#       sweep id makes the merge refuse, naming the file.
# Usage: lock_checks.sh CLATTER_BANK CONFIG SCRATCH MPIEXEC...
set -uo pipefail
bank=$1 config=$2 scratch=$3
shift 3
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# The demo's coarse grid: fast enough for an ASan build; the holders are stopped (SIGSTOP) where a
# check needs them alive or mid-sweep, so no check depends on the machine's speed.
sets=(--set 'proxies.list_m=[[0.5, 0.5], [0.35, 0.2]]' --set 'solve.fields=[1, 4, 6]' --progress-interval 0)
# The holders of (a) and (b) run on 2 ranks (rank 0 holds the locks); every other run is a
# singleton, which spares mpiexec's start-up and its wait after a non-zero exit.
pan() { "$bank" pan -c "$config" "${sets[@]}" "$@" < /dev/null; }
pan_np2() { "${mpiexec[@]}" -n 2 "$bank" pan -c "$config" "${sets[@]}" "$@" < /dev/null; }
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }
holder_pid() { sed -n 's/^pid=//p' "$1"; }
# bank_ranks LAUNCHER: the clatter-bank processes below a launcher (a subshell, then mpiexec), all
# ranks of that run, never those of tests running beside this one. Stopping rank 0 alone would
# leave rank 1 working.
# shellcheck source=interrupt_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/interrupt_lib.sh"
wait_for() {  # wait_for PATH: until it exists (30 s at most)
  for _ in $(seq 600); do [[ -e $1 ]] && return 0; sleep 0.05; done
  fail "$1 never appeared"
}
# Names, sizes and times of the files (a folder's own time moves with the refused run's temporaries).
snapshot() { find . -path ./logs -prune -o -type f -print0 | sort -z | xargs -0 stat -c '%n %s %Y' 2>/dev/null; find . -path ./logs -prune -o -print | sort; }
# refused LOG WHAT CMD...: CMD exits 2, its one error line names the holder, it solved nothing and
# the files other than the logs are as they were.
refused() {
  local log=$1 what=$2 before code
  shift 2
  before=$(snapshot)
  "$@" > "logs/$log" 2>&1
  code=$?
  [[ $code -eq 2 ]] || fail "$what: exit $code, expected 2 ($(tail -3 "logs/$log"))"
  [[ $(grep -c '^clatter-bank: error' "logs/$log") -eq 1 ]] || fail "$what: not one error line"
  grep -q "locked by host $(hostname), PID $holder, since 20" "logs/$log" || fail "$what: holder not named: $(cat "logs/$log")"
  grep -q "solve:" "logs/$log" && fail "$what: computed while the output was locked"
  [[ $(snapshot) == "$before" ]] || fail "$what: changed files while the output was locked: $(diff <(echo "$before") <(snapshot))"
  echo "$what: exit 2: $(grep '^clatter-bank: error' "logs/$log" | cut -c1-150)"
}
mkdir logs
# Holders are stopped on purpose: whatever way this script ends, none may outlive it (a stopped
# rank would keep its peer spinning in MPI and eat a core of every later test).
launched=()
cleanup() {
  local l p
  for l in "${launched[@]}"; do
    for p in $(descendants "$l"); do kill -CONT "$p" 2> /dev/null; kill -KILL "$p" 2> /dev/null; done
  done
}
trap cleanup EXIT

pan -o straight.h5 > logs/straight.log 2>&1 || fail "straight run: $(tail -3 logs/straight.log)"
ref=$(sum straight.h5)
echo "straight run:                       $ref"

# (a)
pan_np2 -o a.h5 > logs/a1.log 2>&1 &
first=$!
launched+=("$first")
wait_for a.h5.tasks.lock
holder=$(holder_pid a.h5.tasks.lock)
ranks=$(bank_ranks "$first")
[[ $ranks == *"$holder"* ]] || fail "(a) the lock's PID $holder is not one of the ranks ($ranks)"
kill -STOP $ranks
refused a2.log "second pan on the same output" pan -o a.h5
refused a3.log "--resume on the same output    " pan -o a.h5 --resume
refused a4.log "merge into the same output     " "$bank" merge --results a.h5.tasks -o a.h5
kill -CONT $ranks
wait "$first" || fail "the first run: exit $? ($(tail -3 logs/a1.log))"
[[ $(sum a.h5) == "$ref" ]] || fail "(a) the bank differs from the straight run"
[[ -n $(compgen -G 'a.h5*.lock') ]] && fail "(a) the finished run left a lock"
echo "(a) the holder's bank:              $(sum a.h5)"

# (b) The holder is stopped once its first task file appears. A sweep of 6 tasks of 0.7 s can
# still finish first on a loaded machine (CI saw it once): then no interruption happened, and the
# run is started again on a fresh output, three times at most.
interrupted=0
for attempt in 1 2 3; do
  rm -rf b.h5 b.h5.tasks b.h5*.lock*
  pan_np2 -o b.h5 > logs/b1.log 2>&1 &
  first=$!
  launched+=("$first")
  wait_for b.h5.tasks.lock
  holder=$(holder_pid b.h5.tasks.lock)
  ranks=$(bank_ranks "$first")  # before its first task ends, so only the wait below is in the race
  for _ in $(seq 3000); do [[ -e b.h5.tasks/p000-f1.h5 ]] && break; sleep 0.01; done
  kill -STOP $ranks 2> /dev/null  # mid-sweep, unless it has already finished
  if [[ -e b.h5.tasks.lock && -e b.h5.tasks/p000-f1.h5 ]]; then
    kill -KILL "$holder"
    kill -CONT $ranks 2> /dev/null  # the other rank, for mpiexec to end it
    wait "$first"
    interrupted=1
    break
  fi
  kill -CONT $ranks 2> /dev/null
  wait "$first"
  echo "(b) attempt $attempt: the sweep finished before it could be stopped; again"
done
[[ $interrupted -eq 1 ]] || fail "(b) the sweep could not be stopped mid-way in 3 attempts"
[[ -e b.h5.tasks.lock && -e b.h5.lock ]] || fail "(b) the killed run left no lock to break"
[[ -e b.h5 ]] && fail "(b) the killed run wrote the bank"
pan -o b.h5 --resume > logs/b2.log 2>&1 || fail "(b) --resume after SIGKILL: exit $? ($(tail -3 logs/b2.log))"
grep -q "breaking the stale lock of host $(hostname), PID $holder.*process $holder is gone" logs/b2.log ||
  fail "(b) no log line about the stale lock"
grep -q "already done" logs/b2.log || fail "(b) the resumed run kept nothing of the killed one"
[[ $(sum b.h5) == "$ref" ]] || fail "(b) the bank differs from the straight run"
echo "(b) SIGKILL, then --resume:         $(sum b.h5)"

# (c) a lock as another node's run writes it
fake_lock() {  # fake_lock PATH AGE: a lock of host other-node, last touched AGE ago
  printf 'clatter-lock 1\nhost=other-node\nboot_id=x\npid=4242\nstart_ticks=1\njob=\nrestart=0\nstarted_utc=2026-01-01T00:00:00Z\ncommand=clatter-bank pan\n' > "$1"
  touch -d "$2" "$1"
}
fake_lock c.h5.tasks.lock "now"
CLATTER_LOCK_STALE_S=30 pan -o c.h5 > logs/c1.log 2>&1
code=$?
[[ $code -eq 2 ]] && grep -q "locked by host other-node, PID 4242.*last heartbeat" logs/c1.log ||
  fail "(c) a fresh lock of another host was not respected: exit $code ($(tail -2 logs/c1.log))"
[[ -e c.h5.tasks ]] && fail "(c) the refused run created the results folder"
fake_lock c.h5.tasks.lock "-40 seconds"
CLATTER_LOCK_STALE_S=30 pan -o c.h5 > logs/c2.log 2>&1 || fail "(c) stale lock of another host: exit $?"
grep -q "breaking the stale lock of host other-node.*no heartbeat for" logs/c2.log || fail "(c) no stale-lock line"
[[ $(sum c.h5) == "$ref" ]] || fail "(c) the bank differs from the straight run"
echo "(c) another host's lock: fresh refused, stale broken"

# (d)
pan -o d.h5 --slice 0/2 > logs/d0.log 2>&1 &
first=$!
launched+=("$first")
wait_for d.h5.tasks.lock-slice-0-of-2
holder=$(holder_pid d.h5.tasks.lock-slice-0-of-2)
kill -STOP "$holder"
pan -o d.h5 --slice 1/2 > logs/d1.log 2>&1 || fail "(d) slice 1/2 beside slice 0/2: exit $? ($(tail -2 logs/d1.log))"
refused d2.log "whole run beside a live slice   " pan -o d.h5 --resume
refused d3.log "merge beside a live slice       " "$bank" merge --results d.h5.tasks -o d.h5
kill -CONT "$holder"
wait "$first" || fail "(d) slice 0/2: exit $?"
"$bank" merge --results d.h5.tasks -o d.h5 > logs/d4.log 2>&1 || fail "(d) merge: exit $?"
[[ $(sum d.h5) == "$ref" ]] || fail "(d) the merged slices differ from the straight run"
echo "(d) slices side by side, merged:    $(sum d.h5)"

# (e)
pan -o e.h5 --keep-results > logs/e1.log 2>&1 || fail "(e) complete run: exit $?"
cp -r e.h5.tasks partial && rm partial/p001-*
"$bank" merge --results partial -o e.h5 > logs/e2.log 2>&1
code=$?
[[ $code -eq 2 ]] || fail "(e) partial merge onto a complete bank: exit $code"
grep -q "e.h5: holds 6 of 6 tasks of this sweep, more than the 3 of this merge; not replaced" logs/e2.log ||
  fail "(e) the refusal does not say why: $(cat logs/e2.log)"
[[ $(sum e.h5) == "$ref" ]] || fail "(e) the complete bank changed"
echo "(e) partial merge refused:          $(grep error logs/e2.log | cut -c1-120)"
"$bank" merge --results partial -o e-copy.h5 > /dev/null 2>&1
[[ $? -eq 4 ]] || fail "(e) partial merge to a new file: not exit 4"
pan -o e.h5 --set fit.epsilon=0.02 > logs/e3.log 2>&1
code=$?
[[ $code -eq 2 ]] && grep -q "e.h5: holds a complete bank of another sweep" logs/e3.log ||
  fail "(e) a run of another config over a complete bank: exit $code ($(tail -2 logs/e3.log))"
grep -q "solve:" logs/e3.log && fail "(e) computed before refusing to replace a bank of another sweep"
[[ $(sum e.h5) == "$ref" ]] || fail "(e) the complete bank changed"
pan -o other.h5 --set fit.epsilon=0.02 --keep-results > logs/e4.log 2>&1 || fail "(e) other sweep: exit $?"
cp other.h5.tasks/p000-f4.h5 e.h5.tasks/p000-f4.h5
"$bank" merge --results e.h5.tasks -o e.h5 > logs/e5.log 2>&1
code=$?
[[ $code -eq 2 ]] && grep -q "e.h5.tasks/p000-f4.h5: a task file of another sweep" logs/e5.log ||
  fail "(e) a task file of another sweep: exit $code ($(cat logs/e5.log))"
echo "(e) foreign task file refused:      $(grep error logs/e5.log | cut -c1-120)"
"$bank" merge --results partial -o e.h5 --force > logs/e6.log 2>&1
[[ $? -eq 4 ]] && grep -q "replacing e.h5.*(--force)" logs/e6.log || fail "(e) --force did not replace"
[[ $(sum e.h5) != "$ref" ]] || fail "(e) --force left the bank as it was"
echo notes > g.h5
pan -o g.h5 > logs/e7.log 2>&1
code=$?
[[ $code -eq 2 ]] && grep -q "g.h5: holds no bank of a sweep" logs/e7.log && [[ $(cat g.h5) == notes ]] ||
  fail "(e) a run onto a file that is no bank: exit $code ($(tail -1 logs/e7.log))"
CLATTER_LOCK_STALE_S=abc pan -o e8.h5 > logs/e8.log 2>&1
code=$?
[[ $code -eq 2 ]] && grep -q "CLATTER_LOCK_STALE_S='abc': expected a number of seconds > 0" logs/e8.log ||
  fail "(e) bad CLATTER_LOCK_STALE_S: exit $code ($(tail -1 logs/e8.log))"
[[ -n $(find . -name '*.lock*' -o -name '.*.tmp-*' -o -name '.*.probe-*') ]] && fail "locks or temporaries left behind"
echo "every lock check passed"
