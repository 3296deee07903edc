#!/usr/bin/env bash
# `clatter-bank modal-samples` (docs/modal.md "Sampling the patch", docs/configuration.md):
#  - its [patch] table is a modal config's: `clatter-bank modal --print-config` takes it, and every
#    sample lies on the patch it names (the config's own check);
#  - resume: a run to level 0, then --resume to level 1, solves only level 1's new candidates
#    (the log counts level 0's from the cache, so a resume that solved everything again fails) and
#    writes the same table, to the bit, as a fresh run to level 1;
#  - an existing OUT.solves without --resume, and one made with other settings, are errors that
#    name the file (exit 2), and they leave the file as it was.
# Bulky shapes only (min_ratio 0.35: the cigar is raised to it), so each solve takes a second.
# Usage: samples_checks.sh CLATTER_BANK CONFIG SCRATCH MPIEXEC...
set -uo pipefail
bank=$1 config=$2 scratch=$3
shift 3
mpiexec=("$@")
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
samples() {  # samples OUT MAX_LEVEL ARGS...
  local out=$1 level=$2
  shift 2
  "${mpiexec[@]}" -n 2 "$bank" modal-samples -c "$config" --set patch.min_ratio=0.35 --max-level "$level" -o "$out" "$@" \
    </dev/null
}

samples fresh.toml 1 > fresh.log 2>&1 || fail "fresh run: $(cat fresh.log)"
grep -q '^cigar_ratio = 0.35$' fresh.toml || fail "the cigar below min_ratio is not raised to it: $(head -5 fresh.toml)"
n_fresh=$(grep -c '^  \[' fresh.toml)
[[ $n_fresh -gt 6 ]] || fail "level 1 added no sample ($n_fresh)"
"$bank" modal -c "$config" --set patch.min_ratio=0.35 --set patch.cigar_ratio=0.35 \
  --set "patch.samples=$(sed -n '/^samples = \[/,/^\]/p' fresh.toml | sed 's/^samples = //' | tr -d '\n')" \
  --print-config > printed.toml 2> printed.err || fail "the table is not a modal config's: $(cat printed.err)"

samples resumed.toml 0 > first.log 2>&1 || fail "level-0 run: $(cat first.log)"
grep -q "6 ellipsoids (6 solved, 0 from the cache)" first.log || fail "level 0: $(grep ellipsoids first.log)"
cp resumed.toml.solves before.solves
samples resumed.toml 1 > again.log 2>&1
rc=$?
[[ $rc -eq 2 ]] || fail "an existing .solves without --resume: exit $rc, not 2"
grep -q "resumed.toml.solves: the solves of an earlier run are there: --resume" again.log || fail "$(cat again.log)"
cmp -s before.solves resumed.toml.solves || fail "the refused run changed resumed.toml.solves"
samples resumed.toml 1 --set mesh.coarse_edge_m=0.2 --resume > other.log 2>&1
rc=$?
[[ $rc -eq 2 ]] || fail "a .solves of other settings: exit $rc, not 2"
grep -q "resumed.toml.solves: made with other settings" other.log || fail "$(cat other.log)"
samples resumed.toml 1 --resume > resume.log 2>&1 || fail "resume: $(cat resume.log)"
grep -q "6 solves read from resumed.toml.solves" resume.log || fail "$(cat resume.log)"
grep -q "6 ellipsoids (0 solved, 6 from the cache)" resume.log || fail "level 0 solved again: $(grep ellipsoids resume.log)"
cmp fresh.toml resumed.toml || fail "resumed table differs from the fresh one: $(diff fresh.toml resumed.toml)"
echo "samples checks: all passed ($n_fresh samples at level 1)"
