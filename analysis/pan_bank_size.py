#!/usr/bin/env python3
"""The PAN bank's size for the 66 proxies, extrapolated from a measured subset (issue 32).

  pan_bank_size.py BANK.h5 [BANK2.h5 ...] --bank CLATTER_BANK [--a 0.5 --grid-min 0.025
                   --grid-step 0.0475] [--paper-mb 26] [-o DIR]

Each BANK is a PAN bank of some of the proxies (a subset, or partial merges of a sweep); each
entry's size is its share of its file as `clatter-bank info` gives it (by its kept coefficients,
the bulk of a file), or the whole file for a bank of one entry. An entry measured in several files
counts once (the last). The 66 proxies are the grid (B, C), grid_min + k grid_step up to A, with
C <= B (configs/pan.toml's proxies.*). Three estimates of the 66's size, as docs/pan.md quotes them:
  - fit: log(size) = a + b log B + c log C by least squares over the measured entries, summed over
    the grid (the measured entries at their own sizes);
  - nearest: each grid proxy at its nearest measured entry's size (in log B, log C);
  - mean: the measured entries' mean times 66 (over-weights thin proxies where the subset does).
Writes DIR/pan_bank_size.csv (per measured entry: B, C, MB, the fit's MB) and
DIR/pan_bank_size.png (measured sizes over (B, C) and the fit's grid), and prints the table.
Exit 2 on bad input (a missing file, fewer measured entries than the fit's three unknowns).
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

import numpy as np

ENTRY = re.compile(r"^\s{4}\(([0-9.eE+-]+), ([0-9.eE+-]+)\)\s+\d+\s+\d+\s+([0-9.]+) MB$")
SIZE = re.compile(r"^\s+size:\s+([0-9.]+) MB on disk")
PROXIES = re.compile(r"^\s+\(B, C\) \[m\]:\s+\(([0-9.eE+-]+), ([0-9.eE+-]+)\)\s*$")


def fail(message):
    print(f"pan_bank_size.py: {message}", file=sys.stderr)
    sys.exit(2)


def entry_sizes(bank_tool, path):
    """{(B, C): MB} of one bank, from `clatter-bank info`."""
    if not os.path.isfile(path):
        fail(f"{path}: no such file")
    run = subprocess.run([bank_tool, "info", path], capture_output=True, text=True)
    if run.returncode != 0:
        fail(f"{path}: clatter-bank info failed: {run.stderr.strip().splitlines()[-1:]}")
    sizes, total, single = {}, None, None
    for line in run.stdout.splitlines():
        if m := ENTRY.match(line):
            sizes[(float(m[1]), float(m[2]))] = float(m[3])
        elif m := SIZE.match(line):
            total = float(m[1])
        elif m := PROXIES.match(line):
            single = (float(m[1]), float(m[2]))
    if not sizes and single is not None and total is not None:
        sizes[single] = total  # a bank of one entry: info prints no per-entry lines
    if not sizes:
        fail(f"{path}: no PAN entries in `clatter-bank info` (not a PAN bank of ellipsoid proxies?)")
    return sizes


def proxy_grid(a_m, grid_min_m, grid_step_m):
    values = []
    k = 0
    while grid_min_m + k * grid_step_m <= a_m + 1e-9:
        values.append(round(grid_min_m + k * grid_step_m, 10))
        k += 1
    return [(b, c) for b in values for c in values if c <= b + 1e-12]


def extrapolate(measured, grid):
    """The three estimates over `grid` from {(B, C): MB}; returns (fit, nearest, mean, coefficients)."""
    keys = sorted(measured)
    if len(keys) < 3:
        fail(f"{len(keys)} measured entries: the fit needs at least 3")
    x = np.array([[1.0, math.log(b), math.log(c)] for b, c in keys])
    y = np.array([math.log(measured[k]) for k in keys])
    coef, *_ = np.linalg.lstsq(x, y, rcond=None)

    def fitted(b, c):
        return math.exp(coef[0] + coef[1] * math.log(b) + coef[2] * math.log(c))

    def measured_at(b, c):
        for k in keys:
            if abs(k[0] - b) < 1e-6 and abs(k[1] - c) < 1e-6:
                return measured[k]
        return None

    fit = sum(measured_at(b, c) if measured_at(b, c) is not None else fitted(b, c) for b, c in grid)
    nearest = 0.0
    for b, c in grid:
        k = min(keys, key=lambda k: (math.log(k[0] / b)) ** 2 + (math.log(k[1] / c)) ** 2)
        nearest += measured[k]
    mean = len(grid) * sum(measured.values()) / len(keys)
    return fit, nearest, mean, coef, fitted


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("banks", nargs="+")
    ap.add_argument("--bank", required=True, help="the clatter-bank executable")
    ap.add_argument("--a", type=float, default=0.5, help="proxies.a_m")
    ap.add_argument("--grid-min", type=float, default=0.025, help="proxies.grid_min_m")
    ap.add_argument("--grid-step", type=float, default=0.0475, help="proxies.grid_step_m")
    ap.add_argument("--paper-mb", type=float, default=26.0, help="the size to compare with (000: 26 MB)")
    ap.add_argument("-o", "--out", default=".")
    args = ap.parse_args()
    measured = {}
    for path in args.banks:
        measured.update(entry_sizes(args.bank, path))
    grid = proxy_grid(args.a, args.grid_min, args.grid_step)
    fit, nearest, mean, coef, fitted = extrapolate(measured, grid)
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "pan_bank_size.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["b_m", "c_m", "mb", "fit_mb"])
        for (b, c) in sorted(measured):
            w.writerow([b, c, measured[(b, c)], f"{fitted(b, c):.4f}"])
    print(f"{len(measured)} measured entries, {len(grid)} proxies in the grid")
    print("| (B, C) [m] | MB | fit MB |")
    print("|---|---|---|")
    for (b, c) in sorted(measured, key=lambda k: (-k[1], -k[0])):
        print(f"| ({b:g}, {c:g}) | {measured[(b, c)]:.3f} | {fitted(b, c):.3f} |")
    print(f"fit: size = {math.exp(coef[0]):.4g} MB x B^{coef[1]:.2f} x C^{coef[2]:.2f}")
    print(f"the {len(grid)} proxies: fit {fit:.1f} MB, nearest {nearest:.1f} MB, mean x {len(grid)} {mean:.1f} MB "
          f"(against {args.paper_mb:g} MB)")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return 0
    fig, ax = plt.subplots(figsize=(6, 5))
    gb = [b for b, _ in grid]
    gc = [c for _, c in grid]
    sc = ax.scatter(gb, gc, c=[fitted(b, c) for b, c in grid], cmap="viridis", s=60, marker="s",
                    norm=matplotlib.colors.LogNorm())
    ax.scatter([b for b, _ in measured], [c for _, c in measured], facecolors="none", edgecolors="red", s=160,
               label="measured")
    for (b, c), mb in measured.items():
        ax.annotate(f"{mb:.2f}", (b, c), textcoords="offset points", xytext=(6, 6), fontsize=7, color="red")
    fig.colorbar(sc, label="MB per proxy (fit)")
    ax.set_xlabel("B [m]")
    ax.set_ylabel("C [m]")
    ax.set_title(f"PAN size per proxy: 66 by the fit {fit:.1f} MB (paper {args.paper_mb:g} MB)")
    ax.legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "pan_bank_size.png"), dpi=120)
    return 0


if __name__ == "__main__":
    sys.exit(main())
