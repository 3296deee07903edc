"""What a render costs from Python against clatter-synth, on one scene and the same banks
(docs/benchmarks.md "Python"). Both do the same work: read the scene file, open the banks, render;
clatter-synth's own "rendered in" span covers exactly that, and the Python side times
load_scene + render (its arrays included) in the same process. The runs alternate on one pinned
core; medians and their ratio are printed, and the outputs compared sample for sample.

Usage: python_vs_cli.py CLATTER_SYNTH SCENE PAN_BANK [MODAL_BANK|-] [GROUND_BANK] [--repeats N]
(PYTHONPATH: the module, e.g. build/release/python)"""
import argparse
import os
import re
import statistics
import subprocess
import tempfile
import time

import numpy as np
from scipy.io import wavfile

import clatter

parser = argparse.ArgumentParser()
parser.add_argument("synth")
parser.add_argument("scene")
parser.add_argument("pan")
parser.add_argument("modal", nargs="?", default="-")
parser.add_argument("ground", nargs="?")
parser.add_argument("--repeats", type=int, default=5)
args = parser.parse_args()
os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})  # one core, inherited by clatter-synth

flags = ["-b", args.pan] + (["-m", args.modal] if args.modal != "-" else []) + (["-g", args.ground] if args.ground else [])
kwargs = dict(pan=args.pan, modal=None if args.modal == "-" else args.modal, ground=args.ground)
wav = os.path.join(tempfile.mkdtemp(), "cli.wav")
cli, cli_process, python = [], [], []
for r in range(args.repeats):
    t0 = time.perf_counter()
    done = subprocess.run([args.synth, "-i", args.scene, *flags, "-o", wav], capture_output=True, text=True, check=True)
    cli_process.append(time.perf_counter() - t0)
    cli.append(float(re.search(r"rendered in (\S+) s", done.stdout).group(1)))
    impacts = int(re.search(r"clatter-synth: (\d+) impacts", done.stdout).group(1))
    t0 = time.perf_counter()
    out = clatter.render(clatter.load_scene(args.scene), **kwargs)
    python.append(time.perf_counter() - t0)
    print(f"run {r + 1}: clatter-synth {cli[-1]:.3f} s (process {cli_process[-1]:.3f} s), Python {python[-1]:.3f} s", flush=True)

same = np.array_equal(out.mix.astype(np.float32), wavfile.read(wav)[1].T.reshape(out.mix.shape))
c, p = statistics.median(cli), statistics.median(python)
print(f"scene {args.scene}: {impacts} impacts, sources {out.sources}, {args.repeats} runs each, alternating, one core")
print(f"clatter-synth (scene + banks + render): median {c:.3f} s (min {min(cli):.3f}); whole process median "
      f"{statistics.median(cli_process):.3f} s")
print(f"Python load_scene + render:            median {p:.3f} s (min {min(python):.3f})")
print(f"Python / clatter-synth: {p / c:.4f} (medians), {min(python) / min(cli):.4f} (minima); samples identical: {same}")
