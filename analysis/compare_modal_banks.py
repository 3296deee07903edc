#!/usr/bin/env python3
"""Compares two modal banks (docs/bank-format.md "Modal bank") entry by entry, within tolerances.

Two banks of one config built with different --ranks-per-task differ in the last bits (MUMPS and
the reductions add in another order), so their content hashes differ; this is the check that they
agree as numbers: the same ellipsoids, surface meshes and multiplet structure, frequencies within
--frequency-tolerance (relative), each mode shape within --shape-tolerance (relative 2-norm over
the surface) and each mode's multipole coefficients (docs/transfer.md) within --transfer-tolerance
(relative 2-norm; the shorter expansion padded with zeros). Measured about 1e-6 between group
sizes (the fit amplifies the shapes' 1e-10); the default 2e-3 allows the truncation to move by an
order, whose terms hold at most the bank's tail tolerance (1e-3). No sign or basis fix is
applied: the bank's basis rule must already make them agree.

Usage: compare_modal_banks.py A.h5 B.h5 [--frequency-tolerance 1e-10] [--shape-tolerance 1e-8]
                              [--transfer-tolerance 2e-3]
Exit 0 when they agree, 1 when not (each difference printed), 2 when a file is not a modal bank.
"""
import argparse
import sys

import h5py
import numpy as np


def entries(path):
    f = h5py.File(path, "r")
    if f.attrs.get("format") not in ("clatter-modal-bank", b"clatter-modal-bank"):
        print(f"{path}: not a modal bank", file=sys.stderr)
        sys.exit(2)
    n = f["/entries/axes_m"].shape[0]
    return f, [f[f"/entries/{i:04d}"] for i in range(n)]


def coefficients(entry, m):
    order = entry["transfer/order"][()]
    offset = int(np.sum((order[:m] + 1) ** 2))
    c = entry["transfer/coefficients"][offset:offset + (order[m] + 1) ** 2]
    return c[:, 0] + 1j * c[:, 1]


def transfer_difference(ea, eb, modes):
    worst = 0.0
    for m in range(modes):
        ca, cb = coefficients(ea, m), coefficients(eb, m)
        n = max(ca.size, cb.size)
        ca, cb = np.pad(ca, (0, n - ca.size)), np.pad(cb, (0, n - cb.size))
        worst = max(worst, np.linalg.norm(ca - cb) / max(np.linalg.norm(ca), 1e-300))
    return worst


def compare(a, b, ftol, stol, ttol):
    problems, worst_f, worst_s = [], 0.0, 0.0
    if len(a) != len(b):
        return [f"{len(a)} entries against {len(b)}"], 0, 0
    for i, (ea, eb) in enumerate(zip(a, b)):
        if not np.array_equal(ea["axes_m"][()], eb["axes_m"][()]):
            problems.append(f"entry {i}: axes differ")
            continue
        if not np.array_equal(ea["surface/nodes_m"][()], eb["surface/nodes_m"][()]):
            problems.append(f"entry {i}: surface meshes differ")
            continue
        fa, fb = ea["frequencies_hz"][()], eb["frequencies_hz"][()]
        if fa.shape != fb.shape or not np.array_equal(ea["cluster"][()], eb["cluster"][()]):
            problems.append(f"entry {i}: {fa.size} modes against {fb.size}, or other multiplets")
            continue
        df = np.max(np.abs(fa / fb - 1)) if fa.size else 0.0
        sa, sb = ea["shapes"][()], eb["shapes"][()]
        ds = max((np.linalg.norm(sa[m] - sb[m]) / np.linalg.norm(sa[m]) for m in range(fa.size)), default=0.0)
        dt = transfer_difference(ea, eb, fa.size)
        worst_f, worst_s = max(worst_f, df), max(worst_s, ds)
        print(f"entry {i}: {fa.size} modes, frequencies within {df:.2e}, shapes within {ds:.2e}, "
              f"transfer within {dt:.2e}")
        if dt > ttol:
            problems.append(f"entry {i}: transfer coefficients differ by {dt:.3e} > {ttol:g}")
        if df > ftol:
            problems.append(f"entry {i}: frequencies differ by {df:.3e} > {ftol:g}")
        if ds > stol:
            problems.append(f"entry {i}: shapes differ by {ds:.3e} > {stol:g}")
    return problems, worst_f, worst_s


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--frequency-tolerance", type=float, default=1e-10)
    p.add_argument("--shape-tolerance", type=float, default=1e-8)
    p.add_argument("--transfer-tolerance", type=float, default=2e-3)
    args = p.parse_args()
    fa, a = entries(args.a)
    fb, b = entries(args.b)
    problems, wf, ws = compare(a, b, args.frequency_tolerance, args.shape_tolerance, args.transfer_tolerance)
    for line in problems:
        print("DIFFERENT:", line)
    print(f"worst: frequencies {wf:.2e} (tolerance {args.frequency_tolerance:g}), shapes {ws:.2e} "
          f"(tolerance {args.shape_tolerance:g})")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
