#!/usr/bin/env bash
# The modal bank's reproducibility acceptance (docs/modal.md "Reproducible modes"):
#  at a fixed --ranks-per-task, the bank's content hash does not depend on the rank count, the
#  task order or an interruption and resume:
#   (a) 1 rank  == (b) 2 ranks as 2 groups of 1 == (e) 1 rank stopped by SIGTERM after the first
#   entry and resumed as 2 groups of 1
#  groups of 2 ranks factorize with parallel MUMPS, whose dynamic scheduling adds contributions in
#  the order they arrive, so its last bits vary from run to run (docs/modal.md "Reproducible
#  modes"): (c) 1 group of 2 and (d) 4 ranks as 2 groups of 2 must agree to 1e-12 in frequency and
#  1e-9 in shape; across group sizes, (a) against (c): frequencies to 1e-10, shapes to 1e-8 after
#  the basis rule, and the transfer's multipole coefficients within the truncation's tolerance
#  (measured 6e-7; analysis/compare_modal_banks.py);
#  `info` lists the entries and an entry's multiplicities; `probe` prints |p_k(x)| of every mode and
#  follows 003 eq. 9 under --scale, and refuses a listener inside 2c or a missing --entry.
#  and a mesh failing its quality bounds or a solve short of the residual limit is a recorded task
#  failure (exit 4, listed with its reason by `info`), never a crash or a short mode list.
# Usage: modal_checks.sh CLATTER_BANK CONFIG PYTHON COMPARE_PY SCRATCH MPIEXEC...
set -uo pipefail
# shellcheck source=interrupt_lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/interrupt_lib.sh"
bank=$1 config=$2 python=$3 compare=$4 scratch=$5
shift 5
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
# Two small entries: a sphere (multiplets of 5 and 3, split by the mesh) and an oblate spheroid
# (pairs); every mode up to 1.6 f_1.
sets=(--set 'patch.samples=[[0.5773502691896258, 0.5773502691896258, 0.5773502691896258],
                            [0.4042260417272216, 0.6467616667635546, 0.6467616667635546]]'
      --set modes.f_max_multiple=1.6 --set modes.largest_piece_m=0)
run() {  # run NPROCS ARGS...
  local n=$1
  shift
  "${mpiexec[@]}" -n "$n" "$bank" modal -c "$config" "${sets[@]}" --progress-interval 0 "$@" </dev/null
}
sum() { "$bank" checksum "$1" | cut -d' ' -f1; }

# Recorded failures: every entry's mesh fails (no tetrahedron has all dihedral angles >= 40 deg),
# then every solve stops short of a residual limit below rounding.
for bad in "mesh.min_dihedral_deg=40:dihedral angle" "solver.residual_limit=1e-14:relative residual"; do
  run 2 -o f.h5 --set "${bad%%:*}" --set solver.tolerance=1e-15 > f.log 2>&1
  code=$?
  [[ $code -eq 4 ]] || fail "${bad%%:*}: exit $code, expected 4 ($(tail -3 f.log))"
  "$bank" info f.h5 > f_info.log 2>&1 || fail "info of a bank with failed entries: exit $?"
  grep -q "0 of 2 entries in the bank, 2 failed" f_info.log || fail "${bad%%:*}: $(cat f_info.log)"
  grep -q "failed: .*${bad#*:}" f_info.log || fail "${bad%%:*}: no reason naming '${bad#*:}': $(cat f_info.log)"
  echo "${bad%%:*}: exit 4, $(grep -m1 'failed: ' f_info.log | cut -c1-160)"
  rm -rf f.h5 f.h5.tasks
done

run 1 -o a.h5 > a.log 2>&1 || fail "1 rank: exit $? ($(tail -3 a.log))"
run 2 -o b.h5 > b.log 2>&1 || fail "2 ranks: exit $? ($(tail -3 b.log))"
run 2 -o c.h5 --ranks-per-task 2 > c.log 2>&1 || fail "1 group of 2: exit $? ($(tail -3 c.log))"
run 4 -o d.h5 --ranks-per-task 2 > d.log 2>&1 || fail "2 groups of 2: exit $? ($(tail -3 d.log))"

# (e) SIGTERM to the ranks once the first task has landed, then --resume. The interrupted run is
# on 1 rank, so the two entries run one after the other and the signal, a fraction of a second
# after the first task file, lands while the second entry is being computed (seconds): the sweep
# must exit 3 (interrupted) and leave that entry to the resume, which runs as 2 groups of 1.
# Two groups would run both entries at once, and one finishing just before the other could take
# the signal after the last task was handed out (exit 0): never a pass here.
run 1 -o e.h5 > e1.log 2>&1 &
launcher=$!
interrupt_sweep "$launcher" 'e.h5.tasks/e*.h5' e1.log || fail "(e) was not interrupted"
[[ -e e.h5 ]] && fail "an interrupted sweep wrote the bank"
run 2 -o e.h5 --resume > e2.log 2>&1 || fail "resume: exit $? ($(tail -3 e2.log))"
grep -q "sweep: 1 tasks in this run (2 of 2 in slice 0/1, 1 already done)" e2.log ||
  fail "(e) the resume did not find exactly one entry done and one to compute: $(grep -m1 'tasks in this run' e2.log)"
echo "(e) $(grep -m1 -o 'interrupted by signal.*' e1.log | cut -d';' -f1); the resume computed the other"

echo "(a) 1 rank:                   $(sum a.h5)"
echo "(b) 2 groups of 1:            $(sum b.h5)"
echo "(e) 1 rank stopped, resumed:  $(sum e.h5)"
echo "(c) 1 group of 2:             $(sum c.h5)"
echo "(d) 2 groups of 2 on 4 ranks: $(sum d.h5)"
[[ $(sum a.h5) == "$(sum b.h5)" ]] || fail "(a) and (b) differ"
[[ $(sum a.h5) == "$(sum e.h5)" ]] || fail "(a) and (e) differ"
[[ $(sum c.h5) == "$(sum d.h5)" ]] && echo "(c) and (d): the same hash (MUMPS scheduled alike in both runs)"
"$python" "$compare" c.h5 d.h5 --frequency-tolerance 1e-12 --shape-tolerance 1e-9 || fail "(c) and (d) differ beyond rounding"

"$python" "$compare" a.h5 c.h5 --frequency-tolerance 1e-10 --shape-tolerance 1e-8 || fail "(a) and (c) differ beyond tolerance"

"$bank" info a.h5 > info.log 2>&1 || fail "info: exit $?"
grep -q "2 ellipsoids" info.log || fail "info does not count the entries: $(cat info.log)"
grep -Eq "5x[0-9]+" info.log || fail "info shows no 5-fold multiplet for the sphere: $(cat info.log)"
"$bank" info a.h5 --entry 0 > entry.log 2>&1 || fail "info --entry: exit $?"
grep -q "^mode,frequency_hz,damping_ratio,cluster,cluster_size,multiplet,multiplet_size,symmetry_order,relative_residual,transfer_order,boundary_residual" entry.log || fail "no mode table"

# probe: |p_k(x)| of every mode (docs/transfer.md); the proxy scaled by 0.1 and heard at 0.1 x the
# distance has 10x the frequencies and 0.1^-5/2 = 316.23x the pressure (003 eq. 9).
"$bank" probe a.h5 --entry 0 --point 0.3,-0.4,2.5 > p1.csv 2>&1 || fail "probe: exit $?: $(cat p1.csv)"
"$bank" probe a.h5 --entry 0 --point 0.03,-0.04,0.25 --scale 0.1 > p2.csv 2>&1 || fail "probe --scale: exit $?"
[[ $(wc -l < p1.csv) -eq $(( $(grep -c '' entry.log) - 1 )) ]] || fail "probe: not one line per mode: $(head -3 p1.csv)"
paste -d, p1.csv p2.csv | awk -F, 'NR > 1 { f = $7 / $2; p = $8 / $3; if (f < 9.999999 || f > 10.000001 || p < 316.2 || p > 316.26) { print "mode " $1 ": frequency x " f ", |p| x " p; bad = 1 } }
  END { exit bad }' || fail "probe --scale does not follow gamma^-5/2"
awk -F, 'NR > 1 && !($3 > 0) { exit 1 }' p1.csv || fail "probe: a mode with no pressure: $(head -3 p1.csv)"
for bad in "--entry 0 --point 0,0,0.5:the transfer holds from 2c" "--point 0,0,3:a modal bank needs --entry N" \
           "--entry 9 --point 0,0,3:--entry 9: a.h5 holds entries 0-1"; do
  args=${bad%%:*}
  # shellcheck disable=SC2086
  "$bank" probe a.h5 $args > pb.log 2>&1
  rc=$?
  [[ $rc -eq 2 ]] || fail "probe ${args}: exit $rc, not 2"
  grep -q -- "${bad#*:}" pb.log || fail "probe ${args}: $(cat pb.log)"
done
cat info.log
echo "modal checks: all passed"
