"""What the command-line check scripts share: a fresh scratch folder to work in, check() that
records a failure and goes on, run() of a program, and finish() that reports and sets the exit code."""
import os
import shutil
import subprocess
import sys

failures = []


def start(scratch):
    """Works in `scratch`, emptied first."""
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    os.chdir(scratch)


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def run(*args):
    return subprocess.run(list(args), capture_output=True, text=True, stdin=subprocess.DEVNULL)


def finish(name):
    print(f"{name}: " + ("all passed" if not failures else f"{len(failures)} FAILED"))
    sys.exit(1 if failures else 0)
