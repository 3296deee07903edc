#!/usr/bin/env bash
# Usage: make_bad_results.sh CLATTER_BANK CONFIG OUTDIR. Results folders that a sweep of CONFIG must
# refuse or repair (docs/validation.md, "Bad-input catalogue"):
#   OUTDIR/other.tasks    the sweep.toml of another config
#   OUTDIR/present.tasks  CONFIG's sweep.toml and a task file, for a run without --resume
#   OUTDIR/corrupt.tasks  the same, for a run with --resume, which redoes the unreadable task
#   OUTDIR/nokind.tasks   CONFIG's sweep.toml without its first line, the bank kind
# A manifest is the line `kind = "pan"` and then the config as --print-config prints it (docs/cluster.md).
set -euo pipefail
bank=$1 config=$2 out=$3
rm -rf "$out" && mkdir -p "$out"/{other,present,corrupt,nokind}.tasks
printf 'kind = "pan"\n# a sweep of another config\n[fit]\nterms = 3\n' >"$out/other.tasks/sweep.toml"
for d in present corrupt; do
  { echo 'kind = "pan"'; "$bank" pan -c "$config" --print-config; } >"$out/$d.tasks/sweep.toml"
  echo "not HDF5: a task file cut short" >"$out/$d.tasks/p000-f1.h5"
done
"$bank" pan -c "$config" --print-config >"$out/nokind.tasks/sweep.toml"
echo "results folders in $out: other.tasks present.tasks corrupt.tasks nokind.tasks"
