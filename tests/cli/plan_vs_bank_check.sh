#!/usr/bin/env bash
# analysis/plan_vs_bank.py against arithmetic known in advance, and on plan's real report:
#  - a plan log written here that predicts exactly twice each stage the bank measured must read
#    "2.00x" for the whole, the FEM and the transfer, no entry within 30 % as predicted and every
#    entry scaled to the whole;
#  - `clatter-bank plan` of the bank's own config must parse (its task lines are the contract);
#  - a log without task lines, a PAN bank, and a log that plans more tasks than the bank holds are
#    each refused with exit 2 and a message naming the file.
# Usage: plan_vs_bank_check.sh PLAN_VS_BANK_PY CLATTER_BANK MODAL_BANK PAN_BANK PYTHON SCRATCH -- PLAN_ARGS...
set -euo pipefail
script=$1 clatter_bank=$2 modal=$3 pan=$4 python=$5 scratch=$6
shift 6
[[ $1 == -- ]] && shift
rm -rf "$scratch" && mkdir -p "$scratch"
fail() { echo "FAIL: $*"; exit 1; }

"$python" - "$modal" "$scratch/twice.log" <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
n = f["/entries/axes_m"].shape[0]
with open(sys.argv[2], "w") as out:
    out.write("plan: a log written by the test\n  tasks:\n")
    for i in range(n):
        c = f[f"/provenance/run/entries/{i:04d}"].attrs
        fem, tr = c["total_s"] - c["transfer_s"], c["transfer_s"]
        out.write(f"    e{i:03d}  (0.5, 0.5, 0.7071)  f_1 1000.0 Hz  ~ {2 * (fem + tr):.6f} s = {2 * fem:.6f} FEM + {2 * tr:.6f} transfer  (coarse 1 dofs)\n")
PY
n=$("$python" -c "import sys, h5py; print(h5py.File(sys.argv[1], 'r')['/entries/axes_m'].shape[0])" "$modal")
out=$("$python" "$script" "$scratch/twice.log" "$modal") || fail "exit $? on the twice log: $out"
echo "$out"
grep -q "2.00x; FEM 2.00x, transfer 2.00x" <<<"$out" || fail "not 2.00x throughout"
grep -q "entries within 30 %: 0 of $n; scaled to the whole: $n of $n" <<<"$out" || fail "wrong counts"

"$clatter_bank" "$@" > "$scratch/plan.log" 2>&1 || fail "clatter-bank plan failed: $(tail -3 "$scratch/plan.log")"
out=$("$python" "$script" "$scratch/plan.log" "$modal") || fail "exit $? on plan's own report: $out"
echo "$out"
grep -q "scaled to the whole: [0-9]* of $n" <<<"$out" || fail "plan's report not read"

refused() {  # refused WHAT PATTERN ARGS...
  local what=$1 pattern=$2 rc=0 err
  shift 2
  err=$("$python" "$script" "$@" 2>&1 >/dev/null) || rc=$?
  [[ $rc == 2 ]] || fail "$what: exit $rc, not 2"
  grep -q -- "$pattern" <<<"$err" || fail "$what: message '$err' lacks '$pattern'"
  echo "refused ($what): $err"
}
echo "plan: nothing here" > "$scratch/empty.log"
refused "no task line" "empty.log: no task line" "$scratch/empty.log" "$modal"
refused "a PAN bank" "$(basename "$pan"): not a modal bank" "$scratch/twice.log" "$pan"
{ cat "$scratch/twice.log"; sed -n "3p" "$scratch/twice.log" | sed "s/e000/e$(printf %03d "$n")/"; } > "$scratch/more.log"
refused "more tasks than entries" "$n entries, but" "$scratch/more.log" "$modal"
echo "plan vs bank checks: all passed"
