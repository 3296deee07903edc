#!/usr/bin/env bash
# Every command of the README's "Using it" block runs as written, from a fresh folder laid out as
# a checkout (build/release/bin, configs/, scenes/), in order; then what they made is checked.
# (The README's build commands are what `make test` itself runs.)
# Usage: readme_commands.sh README BIN_DIR SOURCE_DIR WORKDIR PYTHON (a python3 with h5py) [fast]
# fast: all but the ground bank's and the simulated plate's commands (minutes; make test's run,
# the CTest test readme_commands_all runs every one).
set -u
readme=$1 bin=$2 src=$3 work=$4 python=$5 mode=${6:-all}
rm -rf "$work" && mkdir -p "$work/build/release" && cd "$work" || exit 1
ln -s "$bin" build/release/bin && ln -s "$src/configs" configs && ln -s "$src/scenes" scenes
ln -s "$bin/../python" build/release/python  # the Python module beside the programs
# `python3` in the README is the one with numpy the build chose.
mkdir -p pybin && ln -s "$python" pybin/python3 && export PATH=$PWD/pybin:$PATH
status=0
fail() { echo "FAIL: $*"; status=1; }

# The first ```sh block after "## Using it".
mapfile -t commands < <(awk '/^## Using it/ {on = 1} on && /^```sh$/ {inside = 1; next} inside && /^```$/ {exit} inside && NF' "$readme")
[[ ${#commands[@]} -ge 10 ]] || fail "found ${#commands[@]} commands in $readme's 'Using it' block"
n=0
skipped=0
for line in "${commands[@]}"; do
  n=$((n + 1))
  if [[ $mode == fast && $line =~ (ground|plate) ]]; then
    skipped=$((skipped + 1))
    echo "[$n] skipped (fast): $line"
    continue
  fi
  start=$(date +%s)
  bash -o pipefail -c "$line" >"cmd$n.out" 2>"cmd$n.err" </dev/null
  rc=$?
  echo "[$n] rc=$rc $(($(date +%s) - start)) s: $line"
  if [[ $rc -ne 0 ]]; then
    fail "command $n exited $rc"
    sed 's/^/    /' "cmd$n.err" | tail -5
  fi
done

# What the commands promise, checked on what they left (independent of the code: h5py and text).
need() { [[ -s $1 ]] || fail "$1 was not made"; }
for f in out/field.h5 out/big.h5 out/raw.h5 out/bank.h5 my.toml pan.sbatch out/debris.wav out/rings.wav out/rings.pan.wav out/rings.modal.wav out/rings-py.wav; do need "$f"; done
[[ $mode == fast ]] || for f in out/ground.h5 out/all.wav out/plate.json out/plate.wav; do need "$f"; done
"$python" - <<'PY' || fail "the HDF5 outputs are not what the README says"
import h5py
for path, fmt in [("out/field.h5", "clatter-field"), ("out/big.h5", "clatter-field"),
                  ("out/raw.h5", "clatter-fdtd-raw"), ("out/bank.h5", "clatter-pan-bank")]:
    with h5py.File(path) as f:
        assert f.attrs["format"] == fmt, (path, f.attrs["format"])
with h5py.File("out/big.h5") as f:
    assert f["field/p"].shape[-3:] == (256, 256, 256), f["field/p"].shape  # --set grid.n_cells=256 took effect
with h5py.File("out/raw.h5") as f:
    assert sorted(f["fields"]) == ["p%d" % i for i in range(1, 7)], list(f["fields"])  # 6 pulse fields
with h5py.File("out/bank.h5") as f:
    assert f["proxies/b_m"].shape == (3,), f["proxies/b_m"].shape  # the 3-proxy demo bank
import numpy as np
from scipy.io import wavfile
cli, py = wavfile.read("out/rings.wav")[1], wavfile.read("out/rings-py.wav")[1]
assert cli.shape == py.shape and np.array_equal(cli, py), "the Python render differs from clatter-synth's"
print("README outputs: formats, the 256^3 grid, 6 fields and 3 proxies as stated; the Python render is clatter-synth's")
PY
grep -q "Subcommands:" cmd1.out || fail "--help printed no subcommands"
grep -q "3 ellipsoids" cmd*.out || fail "info did not describe 3 proxies"
grep -q "66 tasks\|66 proxies\|396" cmd*.out cmd*.err pan.sbatch || fail "plan did not size the default 66-proxy bank"
grep -q "#SBATCH" pan.sbatch || fail "pan.sbatch is not a batch script"
probe=$(grep -l '^t_s,p_Pa' cmd*.out | head -1)
[[ -n $probe && $(wc -l <"$probe") -gt 100 ]] || fail "probe printed no CSV series"
[[ $mode == fast ]] || grep -q "outside the bank.s coverage" cmd*.out || fail "the plate render did not list the objects the demo banks do not cover"
[[ $status -eq 0 && $skipped -gt 0 ]] && echo "README commands: $((${#commands[@]} - skipped)) of ${#commands[@]} ran as written ($skipped of the ground bank and the plate skipped: readme_commands_all runs them)"
[[ $status -eq 0 && $skipped -eq 0 ]] && echo "README commands: all ${#commands[@]} ran as written"
exit $status
