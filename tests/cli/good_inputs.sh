#!/usr/bin/env bash
# Usage: good_inputs.sh BIN BAD_INPUTS GOOD_BANK TINY_CONFIG SCRATCH. The good inputs that the bad
# ones of the catalogue (docs/validation.md) are made from are accepted, so each bad-input test
# fails for its one defect: good.json, box.json (an object given by a closed mesh), side.json with
# good.txt (James-lab impulses), and the tiny sweep config.
set -euo pipefail
bin=$1 inputs=$2 bank=$3 tiny=$4 scratch=$5
rm -rf "$scratch" && mkdir -p "$scratch" && cd "$scratch"
"$bin/clatter-synth" -i "$inputs/good.json" -b "$bank" -o good.wav
"$bin/clatter-synth" -i "$inputs/box.json" -b "$bank" -o box.wav
"$bin/clatter-synth" -i "$inputs/side.json" --impulses "$inputs/good.txt" -b "$bank" -o impulses.wav
"$bin/clatter-bank" pan -c "$tiny" -o tiny.h5 --progress-interval 0 >/dev/null
echo "good inputs: all accepted"
