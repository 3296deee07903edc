#!/usr/bin/env python3
"""`clatter-bank plan`'s per-task prediction for a modal sweep against the bank it then built
(docs/benchmarks.md "The transfer's queue of modes, one rank per task or two").

Reads the task lines of plan's report (saved from its standard output: "eNNN (a, b, c) ... ~ T s =
F FEM + X transfer") and each entry's measured wall times in the bank's /provenance/run/entries
(docs/bank-format.md "Cost"), and prints the whole bank's predicted / measured time, the FEM's and
the transfer's, the entries within --within (relative) as predicted and scaled to the whole, and
the entries that miss. Compare a plan run with --ranks-per-task R against a bank built with R.

Usage: plan_vs_bank.py PLAN.log BANK.h5 [--within 0.3]
Exit 0 after the report, 2 when the log holds no task line or the bank is not a modal bank with
one entry per task line.
"""
import argparse
import re
import sys

import h5py
import numpy as np

TASK = re.compile(r"^\s+e(\d+)\s+\(.*?~\s*([\d.]+) s = ([\d.]+) FEM \+ ([\d.]+) transfer")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("plan_log")
    ap.add_argument("bank")
    ap.add_argument("--within", type=float, default=0.3, help="relative band an entry must fall in (default 0.3)")
    a = ap.parse_args()
    predicted = {}
    with open(a.plan_log) as log:
        for line in log:
            m = TASK.match(line)
            if m:
                predicted[int(m.group(1))] = [float(m.group(k)) for k in (2, 3, 4)]
    if not predicted:
        print(f"{a.plan_log}: no task line of a modal plan (eNNN ... ~ T s = F FEM + X transfer)", file=sys.stderr)
        return 2
    with h5py.File(a.bank, "r") as f:
        if f.attrs.get("format") not in ("clatter-modal-bank", b"clatter-modal-bank"):
            print(f"{a.bank}: not a modal bank", file=sys.stderr)
            return 2
        n = f["/entries/axes_m"].shape[0]
        if sorted(predicted) != list(range(n)):
            print(f"{a.bank}: {n} entries, but {a.plan_log} plans {len(predicted)} tasks", file=sys.stderr)
            return 2
        cost = [f[f"/provenance/run/entries/{i:04d}"].attrs for i in range(n)]
        measured = np.array([[c["total_s"], c["total_s"] - c["transfer_s"], c["transfer_s"]] for c in cost])
    pred = np.array([predicted[i] for i in range(n)])
    band = np.log1p(a.within)

    def inside(r):
        return int(np.sum(np.abs(np.log(r)) <= band))

    whole = pred[:, 0].sum() / measured[:, 0].sum()
    ratio = pred[:, 0] / measured[:, 0]
    scaled = ratio / whole
    print(f"whole bank: predicted {pred[:, 0].sum():.0f} s, measured {measured[:, 0].sum():.0f} s (sum of entries' wall): "
          f"{whole:.2f}x; FEM {pred[:, 1].sum() / measured[:, 1].sum():.2f}x, transfer {pred[:, 2].sum() / measured[:, 2].sum():.2f}x")
    print(f"entries within {100 * a.within:.0f} %: {inside(ratio)} of {n}; scaled to the whole: {inside(scaled)} of {n}")
    misses = [f"e{i:03d} {scaled[i]:.2f}x" for i in range(n) if abs(np.log(scaled[i])) > band]
    print("misses (scaled): " + (", ".join(misses) if misses else "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
