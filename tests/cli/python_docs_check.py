"""Runs docs/python.md's worked example as a reader would after `make demo`: in a scratch folder
whose out/demo/bank.h5 and modal.h5 are the test fixtures' PAN and modal banks. Checks that it
printed every source's peak (not silent), drew its figure and wrote its WAV and stems.

Usage: python_docs_check.py DOCS_PYTHON_MD PAN_BANK MODAL_BANK SCRATCH (PYTHONPATH: the module)"""
import os
import re
import shutil
import subprocess
import sys

docs, pan, modal, scratch = sys.argv[1:5]
text = open(docs).read()
section = text.split("## A scene from a few lines of numpy", 1)[1]
code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(f"{scratch}/out/demo")
os.symlink(os.path.abspath(pan), f"{scratch}/out/demo/bank.h5")
os.symlink(os.path.abspath(modal), f"{scratch}/out/demo/modal.h5")
open(f"{scratch}/example.py", "w").write(code)
done = subprocess.run([sys.executable, "example.py"], cwd=scratch, capture_output=True, text=True)
print(done.stdout, done.stderr, sep="")
assert done.returncode == 0, "the example failed"
peaks = dict(re.findall(r"^(\w+): peak (\S+) Pa$", done.stdout, re.M))
assert set(peaks) == {"pan", "modal"}, peaks
assert all(float(v) > 0 for v in peaks.values()), f"a silent source: {peaks}"
for f in ("balls.png", "balls.wav", "balls.pan.wav", "balls.modal.wav"):
    assert os.path.getsize(f"{scratch}/{f}") > 1000, f
print("python docs checks: all passed")
