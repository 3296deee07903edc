#!/usr/bin/env bash
# The modal bank's reproducibility acceptance (docs/modal.md "Reproducible modes"):
#  at a fixed --ranks-per-task, the bank's content hash does not depend on the rank count, the
#  task order or an interruption and resume:
#   (a) 1 rank  == (b) 2 ranks as 2 groups of 1 == (e) 2 groups of 1 stopped by SIGTERM and resumed
#   (c) 2 ranks as 1 group of 2 == (d) 4 ranks as 2 groups of 2
#  across group sizes, (a) against (c): frequencies to 1e-10, shapes to 1e-8 after the basis rule
#  (analysis/compare_modal_banks.py); and `info` lists the entries and an entry's multiplicities.
# Usage: modal_checks.sh CLATTER_BANK CONFIG COMPARE_PY SCRATCH MPIEXEC...
set -uo pipefail
bank=$1 config=$2 compare=$3 scratch=$4
shift 4
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# Two small entries: a sphere (multiplets of 5 and 3, split by the mesh) and an oblate spheroid
# (pairs); every mode up to 1.6 f_1.
sets=(--set 'patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258],
                            [0.4042260417272216, 0.6467616667635546, 0.6467616667635546]]'
      --set modes.f_max_multiple=1.6)
run() {  # run NPROCS ARGS...
  local n=$1
  shift
  "${mpiexec[@]}" -n "$n" "$bank" modal -c "$config" "${sets[@]}" --progress-interval 0 "$@" </dev/null
}
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }

run 1 -o a.h5 > a.log 2>&1 || fail "1 rank: exit $? ($(tail -3 a.log))"
run 2 -o b.h5 > b.log 2>&1 || fail "2 ranks: exit $? ($(tail -3 b.log))"
run 2 -o c.h5 --ranks-per-task 2 > c.log 2>&1 || fail "1 group of 2: exit $? ($(tail -3 c.log))"
run 4 -o d.h5 --ranks-per-task 2 > d.log 2>&1 || fail "2 groups of 2: exit $? ($(tail -3 d.log))"

# (e) SIGTERM to the ranks once the first task has landed, then --resume.
run 2 -o e.h5 > e1.log 2>&1 &
launcher=$!
for _ in $(seq 1200); do
  compgen -G 'e.h5.tasks/e*.h5' > /dev/null && break
  sleep 0.05
done
descendants() { local c; for c in $(pgrep -P "$1"); do echo "$c"; descendants "$c"; done; }
ranks=$(for p in $(descendants "$launcher"); do [[ $(ps -o comm= -p "$p") == clatter-bank ]] && echo "$p"; done)
[[ -n $ranks ]] || fail "found no clatter-bank rank below the launcher to interrupt"
kill -TERM $ranks
wait "$launcher"
code=$?
if [[ $code -eq 0 ]]; then
  echo "(e) the sweep finished before the signal arrived; resume runs on a complete folder"
else
  [[ $code -eq 3 ]] || fail "interrupted sweep: exit $code, expected 3 ($(tail -5 e1.log))"
  [[ -e e.h5 ]] && fail "an interrupted sweep wrote the bank"
  run 2 -o e.h5 --resume > e2.log 2>&1 || fail "resume: exit $? ($(tail -3 e2.log))"
fi

echo "(a) 1 rank:                   $(sum a.h5)"
echo "(b) 2 groups of 1:            $(sum b.h5)"
echo "(e) 2 groups of 1, resumed:   $(sum e.h5)"
echo "(c) 1 group of 2:             $(sum c.h5)"
echo "(d) 2 groups of 2 on 4 ranks: $(sum d.h5)"
[[ $(sum a.h5) == "$(sum b.h5)" ]] || fail "(a) and (b) differ"
[[ $(sum a.h5) == "$(sum e.h5)" ]] || fail "(a) and (e) differ"
[[ $(sum c.h5) == "$(sum d.h5)" ]] || fail "(c) and (d) differ"

python3 "$compare" a.h5 c.h5 --frequency-tolerance 1e-10 --shape-tolerance 1e-8 || fail "(a) and (c) differ beyond tolerance"

"$bank" info a.h5 > info.log 2>&1 || fail "info: exit $?"
grep -q "2 ellipsoids" info.log || fail "info does not count the entries: $(cat info.log)"
grep -Eq "5x[0-9]+" info.log || fail "info shows no 5-fold multiplet for the sphere: $(cat info.log)"
"$bank" info a.h5 --entry 0 > entry.log 2>&1 || fail "info --entry: exit $?"
grep -q "^mode,frequency_hz,damping_ratio,multiplet,multiplicity,relative_residual" entry.log || fail "no mode table"
cat info.log
echo "modal checks: all passed"
