#!/usr/bin/env python3
"""How many directions a proxy's far field needs (the groundwork of adaptive directions, issue 32):
the far field F(d, tau) from the Kirchhoff surface (`solve --set kirchhoff.far_directions`) at the
vertices of the octant triangulation with d divisions, interpolated quadratically (the PAN bank's
six-node elements, kernels/pan/directions.hpp) at four points inside every element (the centroids
of its four triangles), against F computed there. As in the bank, each direction is first advanced
by the ellipsoid's support distance in whole samples and the advances are interpolated with the
same weights (docs/pan.md "Two choices the paper leaves open"). Relative L2 per point; prints the median, the
90th percentile and the worst per field and d.

  analysis/pan_direction_error.py OUT.h5 [--b B --c C] [--fields "[1,2,3,4,5,6]"] [--divisions 8,16]

Defaults: proxy (0.2625, 0.12) at the paper's resolution (6.5 mm, 1/96000 s, h = 1e-4 s).
"""
import argparse
import os
import shlex
import subprocess

import h5py
import numpy as np


def vertices(d):
    """Lattice (a, b) -> gnomonic point (a, b, d - a - b) / d, in kernels/pan/directions.cpp's order."""
    return {(a, b): np.array([a, b, d - a - b], float) / d for a in range(d + 1) for b in range(d + 1 - a)}


def elements(d):
    """The six-node elements: corner lattice points of the (d/2)^2 triangles of the coarse lattice."""
    c = d // 2
    out = []
    for a in range(c):
        for b in range(c - a):
            out.append(((2 * a, 2 * b), (2 * a + 2, 2 * b), (2 * a, 2 * b + 2)))
            if a + b + 1 < c:
                out.append(((2 * a + 2, 2 * b + 2), (2 * a + 2, 2 * b), (2 * a, 2 * b + 2)))
    return out


POINTS = [(2 / 3, 1 / 6, 1 / 6), (1 / 6, 2 / 3, 1 / 6), (1 / 6, 1 / 6, 2 / 3), (1 / 3, 1 / 3, 1 / 3)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--b", type=float, default=0.2625)
    ap.add_argument("--c", type=float, default=0.12)
    ap.add_argument("--fields", default="[1, 2, 3, 4, 5, 6]")
    ap.add_argument("--divisions", default="8,16")
    ap.add_argument("--dx", type=float, default=0.0065)
    ap.add_argument("--dt", type=float, default=1 / 96000)
    ap.add_argument("--h", type=float, default=1e-4)
    ap.add_argument("--bin", default="build/release/bin/clatter-bank")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    a = ap.parse_args()
    divisions = [int(v) for v in a.divisions.split(",")]
    # Every direction needed: the vertices of each d, and the test points of its elements.
    dirs, plan = [], []
    for d in divisions:
        verts = vertices(d)
        index = {}
        for key, g in verts.items():
            index[key] = len(dirs)
            dirs.append(g / np.linalg.norm(g))
        tests = []
        for corners in elements(d):
            mids = [tuple((np.array(corners[i]) + np.array(corners[(i + 1) % 3])) // 2) for i in range(3)]
            for l in POINTS:
                g = sum(l[i] * verts[corners[i]] for i in range(3))
                w = [l[i] * (2 * l[i] - 1) for i in range(3)] + [4 * l[i] * l[(i + 1) % 3] for i in range(3)]
                nodes = [index[corners[i]] for i in range(3)] + [index[m] for m in mids]
                tests.append((len(dirs), nodes, w))
                dirs.append(g / np.linalg.norm(g))
        plan.append((d, tests))
    text = "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in u) + "]" for u in dirs) + "]"
    if not os.path.exists(a.out):
        subprocess.run(shlex.split(a.mpiexec) + [
            a.bin, "solve", "-o", a.out, "--progress-interval", "0", "--log-level", "warn",
            "--set", f"grid.dx_m={a.dx!r}", "--set", f"time.dt_s={a.dt!r}", "--set", f"pulse.h_s={a.h!r}",
            "--set", f"grid.half_width_m={0.5 + 17 * a.dx!r}", "--set", "time.duration_s=0.012",
            "--set", "object.a_m=0.5", "--set", f"object.b_m={a.b!r}", "--set", f"object.c_m={a.c!r}",
            "--set", f"solve.fields={a.fields}", "--set", f"listeners.points_m=[[{0.5 + 5 * a.dx!r}, 0, 0]]",
            "--set", f"kirchhoff.radius_m={0.5 + 3 * a.dx!r}", "--set", f"kirchhoff.far_directions={text}"], check=True)
    with h5py.File(a.out) as f:
        far = {int(k[1:]): f["far"][k][...].astype(float) for k in f["far"] if k.startswith("p")}
    # Support-distance advance per direction in whole samples, as bank format 2 aligned (format 3
    # aligns exactly, kernels/pan/fit.hpp; clatter-pan-direction-study measures with that).
    delay = [round(np.sqrt((0.5 * u[0]) ** 2 + (a.b * u[1]) ** 2 + (a.c * u[2]) ** 2) / (343.2 * a.dt)) for u in dirs]
    n_samples = next(iter(far.values())).shape[1]
    k = np.arange(n_samples)
    shift = lambda series, by: np.interp(k + by, k, series, left=0, right=0)
    print(f"proxy (0.5, {a.b}, {a.c}): far field interpolated quadratically at 4 points per element")
    for field in sorted(far):
        F = far[field]
        peak = max(np.linalg.norm(F[i]) for i in range(len(dirs)))
        for d, tests in plan:
            errs = []
            for i, nodes, w in tests:
                got = sum(wk * shift(F[n], -delay[n]) for wk, n in zip(w, nodes))
                ref = shift(F[i], -sum(wk * delay[n] for wk, n in zip(w, nodes)))
                # Directions where the field is weak (below 1 % of its strongest) are judged against that 1 %.
                errs.append(np.linalg.norm(got - ref) / max(np.linalg.norm(ref), 0.01 * peak))
            errs = np.array(errs)
            print(f"field {field}, {d:2d} divisions ({(d + 1) * (d + 2) // 2:3d} directions): median {100 * np.median(errs):5.2f} %, "
                  f"90th percentile {100 * np.percentile(errs, 90):5.2f} %, worst {100 * errs.max():5.2f} %, "
                  f"points above 5 %: {np.sum(errs > 0.05)}/{len(errs)}", flush=True)


if __name__ == "__main__":
    main()
