#!/usr/bin/env python3
"""The FDTD schemes side by side: error against cost for the free-field monopole at 1 m.

  analysis/fdtd_error_cost.py [--bank BIN] [--dx MM,MM,...] [--distance M] [--csv FILE] [--plot PNG]
                              [--rate-srl R --rate-me4 R] [--from-csv FILE]

For each scheme (srl, me4) and cell size, runs `clatter-bank solve` on one rank with a monopole
in octant mode (h = 1e-4 s, Courant 0.55 as at the paper's 6.5 mm and 1/96000 s), listeners at
`distance` along a grid axis, a face diagonal and the body diagonal, and measures each series'
relative L2 error against the exact field rho psi(t - r/c) / (4 pi r) (computed here from 000's
eq. 6 in numpy, analysis/field_check.py, independently of the C++). It also reads the solve's own prediction (the error budget's
dispersion term, docs/fdtd.md) from its log.

Cost is in core-seconds: the solve's cell-updates divided by each scheme's per-core rate. The rates
default to the wall time the solves report; pass --rate-srl/--rate-me4 (cell-updates/s, e.g.
medians of `clatter-bench --benchmark_filter=FdtdStep`) to take them from a quiet benchmark run
instead, since a shared machine makes single timings noisy. Writes a CSV and, with --plot, the
error-vs-cost figure of docs/fdtd.md. --from-csv redraws from an earlier CSV (with new rates)
instead of solving again.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from field_check import psi  # noqa: E402  (000's eq. 6 in numpy, the analysis' one copy)

DIRECTIONS = [("axis", (1, 0, 0)), ("face diagonal", (1, 1, 0)), ("body diagonal", (1, 1, 1))]


def run(bank, scheme, dx, distance, work):
    out = os.path.join(work, f"{scheme}-{dx * 1e3:.2f}.h5")
    points = []
    for _, d in DIRECTIONS:
        n = math.sqrt(sum(x * x for x in d))
        points.append([distance * x / n for x in d])
    sets = [f"object.kind=monopole", f"grid.dx_m={dx!r}", f"grid.half_width_m={distance + 12 * dx!r}",
            f"time.dt_s={dx / 0.0065 / 96000.0!r}", f"time.duration_s={distance / 343.2 + 4e-4!r}",
            f"solver.scheme={scheme}", "listeners.points_m=" + str(points)]
    cmd = [bank, "solve", "-o", out, "--progress-interval", "0"]
    for s in sets:
        cmd += ["--set", s]
    env = dict(os.environ, OMP_NUM_THREADS="1")
    log = subprocess.run(cmd, capture_output=True, text=True, env=env)
    if log.returncode != 0:
        sys.exit(f"fdtd_error_cost: {' '.join(cmd)} failed: {log.stderr[-500:]}")
    text = log.stdout + log.stderr
    m = re.search(r"([0-9.e+]+) cell-updates in ([0-9.e+]+) s", text)
    updates, seconds = float(m.group(1)), float(m.group(2))
    predicted = float(re.search(r"predicted dispersion error ([0-9.e+-]+) %", text).group(1)) / 100
    with h5py.File(out) as f:
        s = f["solve"].attrs
        p = f["fields/p0"][...]
        x = f["listeners/x_m"][...]
        t = s["t_first_s"] + np.arange(p.shape[1]) * s["dt_s"]
        errors = []
        for l in range(x.shape[0]):
            r = float(np.linalg.norm(x[l]))
            want = s["rho_kg_m3"] * psi(t - r / s["c_m_s"], s["h_s"]) / (4 * math.pi * r)
            errors.append(float(np.sqrt(((p[l] - want) ** 2).sum() / (want ** 2).sum())))
    os.remove(out)
    return updates, seconds, predicted, errors


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bank", default="build/release/bin/clatter-bank")
    ap.add_argument("--dx", default="13,9.2,6.5,4.6", help="cell sizes [mm]")
    ap.add_argument("--distance", type=float, default=1.0)
    ap.add_argument("--csv", default="")
    ap.add_argument("--plot", default="")
    ap.add_argument("--rate-srl", type=float, default=0.0)
    ap.add_argument("--rate-me4", type=float, default=0.0)
    ap.add_argument("--from-csv", default="")
    a = ap.parse_args()
    rates = {"srl": a.rate_srl, "me4": a.rate_me4}
    rows = []
    if a.from_csv:
        with open(a.from_csv) as f:
            for line in f.read().splitlines()[1:]:
                v = line.split(",")
                scheme, updates, seconds = v[0], float(v[2]), float(v[3])
                core_s = updates / rates[scheme] if rates[scheme] > 0 else seconds
                rows.append((scheme, float(v[1]), updates, seconds, core_s, *[float(x) for x in v[5:]]))
    with tempfile.TemporaryDirectory() as work:
        for scheme in ("srl", "me4") if not a.from_csv else ():
            for dx_mm in [float(v) for v in a.dx.split(",")]:
                updates, seconds, predicted, errors = run(a.bank, scheme, dx_mm / 1e3, a.distance, work)
                core_s = updates / rates[scheme] if rates[scheme] > 0 else seconds
                rows.append((scheme, dx_mm, updates, seconds, core_s, predicted, *errors))
                print(f"{scheme} dx = {dx_mm:5.2f} mm: {updates:.3g} cell-updates, {seconds:.2f} s measured, "
                      f"{core_s:.2f} core-s; error axis {errors[0]:.4f}, face {errors[1]:.4f}, body {errors[2]:.4f} "
                      f"(budget's dispersion term, worst direction: {predicted:.4f})", flush=True)
    header = "scheme,dx_mm,cell_updates,measured_s,core_s,predicted_worst,err_axis,err_face,err_body"
    if a.csv:
        with open(a.csv, "w") as f:
            f.write(header + "\n")
            for r in rows:
                f.write(",".join(str(v) for v in r) + "\n")
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        styles = {"srl": ("tab:red", "7-point leapfrog (srl)"), "me4": ("tab:blue", "fourth order (me4)")}
        marks = ["o", "s", "^"]
        for scheme, (color, label) in styles.items():
            sel = [r for r in rows if r[0] == scheme]
            cost = [r[4] for r in sel]
            for d, (name, _) in enumerate(DIRECTIONS):
                ax.loglog(cost, [r[6 + d] for r in sel], marker=marks[d], color=color, ls="-" if d == 0 else ":",
                          label=f"{label}, {name}")
            for r in sel:
                ax.annotate(f"{r[1]:g} mm", (r[4], r[6]), fontsize=7, color=color, textcoords="offset points",
                            xytext=(4, 4))
        ax.axhline(0.02, color="gray", lw=0.8, ls="--")
        ax.text(ax.get_xlim()[0], 0.021, " 2 % goal", color="gray", fontsize=8)
        ax.set_xlabel("cost of the solve [core-seconds, one field]")
        ax.set_ylabel(f"relative L2 error at {a.distance:g} m")
        ax.set_title("Monopole, h = 1e-4 s, Courant 0.55: error against cost")
        ax.legend(fontsize=7, ncol=2, loc="lower left")
        ax.grid(True, which="both", lw=0.3)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
        print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
