"""What a render costs from Python against clatter-synth, on one scene and the same banks
(docs/benchmarks.md "Python"). Each turn runs clatter-synth --log-view, then a fresh Python process
that does the same work through the module (load_scene, then render with the same banks), on one
pinned core; the two alternate, so the machine's drift hits both alike. Compared, as medians over
the turns and their ratio:
- the job: clatter-synth's "rendered in" span (scene file read, banks opened, render) against the
  Python process's load_scene + render (its numpy arrays included);
- the stages both print (--log-view's rows; Render.stages_s): scene, banks, render.
The last turn's outputs are compared sample for sample.

Usage: python_vs_cli.py CLATTER_SYNTH SCENE PAN_BANK [MODAL_BANK|-] [GROUND_BANK] [--repeats N]
(PYTHONPATH: the module, e.g. build/release/python)"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import warnings

import numpy as np
from scipy.io import wavfile

parser = argparse.ArgumentParser()
parser.add_argument("synth")
parser.add_argument("scene")
parser.add_argument("pan")
parser.add_argument("modal", nargs="?", default="-")
parser.add_argument("ground", nargs="?")
parser.add_argument("--repeats", type=int, default=7)
args = parser.parse_args()
os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})  # one core, inherited by both

folder = tempfile.mkdtemp()
flags = ["-b", args.pan] + (["-m", args.modal] if args.modal != "-" else []) + (["-g", args.ground] if args.ground else [])
kwargs = dict(pan=args.pan, modal=None if args.modal == "-" else args.modal, ground=args.ground)
# The Python side, in a fresh interpreter like clatter-synth's fresh process.
python_job = f"""
import json, time, numpy as np, clatter
t0 = time.perf_counter()
scene = clatter.load_scene({args.scene!r})
t1 = time.perf_counter()
out = clatter.render(scene, **{kwargs!r})
t2 = time.perf_counter()
np.save({folder + '/mix.npy'!r}, out.mix)
print(json.dumps(dict(job=t2 - t0, scene=t1 - t0, impacts=out.summary()["impacts"], **out.stages_s)))
"""


def stage_row(text, name):
    return float(re.search(rf"^\s*{name}\s+\d+\s+(\S+)", text, re.M).group(1))


rows = {"cli": [], "python": []}
for turn in range(args.repeats):
    done = subprocess.run([args.synth, "-i", args.scene, *flags, "-o", f"{folder}/cli.wav", "--log-view"],
                          capture_output=True, text=True, check=True)
    cli = {"job": float(re.search(r"rendered in (\S+) s", done.stdout).group(1)),
           "scene": stage_row(done.stdout, "scene"), "banks": stage_row(done.stdout, "banks"),
           "render": stage_row(done.stdout, "render")}
    impacts = int(re.search(r"clatter-synth: (\d+) impacts", done.stdout).group(1))
    done = subprocess.run([sys.executable, "-c", python_job], capture_output=True, text=True, check=True)
    py = json.loads(done.stdout)
    assert py["impacts"] == impacts
    rows["cli"].append(cli)
    rows["python"].append(py)
    print(f"turn {turn + 1}: clatter-synth job {cli['job']:.3f} s (render {cli['render']:.3f}), "
          f"Python job {py['job']:.3f} s (render {py['render']:.3f})", flush=True)

with warnings.catch_warnings():  # libsndfile's PEAK chunk
    warnings.simplefilter("ignore", wavfile.WavFileWarning)
    wav = wavfile.read(f"{folder}/cli.wav")[1]
mix = np.load(f"{folder}/mix.npy")
same = np.array_equal(mix.astype(np.float32), wav.T.reshape(mix.shape))
print(f"scene {args.scene}: {impacts} impacts, banks {' '.join(flags)}; {args.repeats} turns, one core")
print(f"{'':8} {'clatter-synth':>14} {'Python':>10} {'ratio':>8}   (medians, s)")
for key in ("job", "scene", "banks", "render"):
    c = statistics.median(r[key] for r in rows["cli"])
    p = statistics.median(r[key] for r in rows["python"])
    print(f"{key:8} {c:14.3f} {p:10.3f} {p / c:8.4f}")
print(f"samples identical: {same}")
