#!/usr/bin/env python3
"""How well radial models represent one direction of a proxy's field (docs/pan.md, "The far field
and the radial series"): the series p = sum_k q_k / R^k fitted over the PAN radii (N = 2, 3, 4),
the same with q_1 the far field, and R p interpolated in 1/R between the radii with the far field
at 1/R = 0. No wavelets, compression or direction interpolation: the solve's own series, heard
through a Kirchhoff surface at the radii and at 1.05, 1.8 and 3 m, and its far field.

  analysis/pan_radial_series.py OUT.h5 [--field F] [--b B --c C] [--dx DX --dt DT --h H]

Defaults: proxy (0.2625, 0.12), field 1, the paper's resolution (6.5 mm, 1/96000 s, h = 1e-4 s),
the PAN radii 0.7-1.5 m, held out 1.05, 1.8 and 3 m; the direction is the vertex (1, 0, 3)/sqrt(10)
of the 45-direction grid.
"""
import argparse
import os
import shlex
import subprocess

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--field", type=int, default=1)
    ap.add_argument("--b", type=float, default=0.2625)
    ap.add_argument("--c", type=float, default=0.12)
    ap.add_argument("--dx", type=float, default=0.0065)
    ap.add_argument("--dt", type=float, default=1 / 96000)
    ap.add_argument("--h", type=float, default=1e-4)
    ap.add_argument("--radii", default="0.7,0.85,1.0,1.2,1.5", help="the stored radii [m] (the PAN default)")
    ap.add_argument("--held", default="1.05,1.8,3.0", help="held-out radii [m]")
    ap.add_argument("--bin", default="build/release/bin/clatter-bank")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    a = ap.parse_args()
    c_m_s, dt, dx = 343.2, a.dt, a.dx
    steps = lambda r: round(r / (c_m_s * dt))
    fitted = [steps(float(r)) * c_m_s * dt for r in a.radii.split(",")]
    held = [steps(float(r)) * c_m_s * dt for r in a.held.split(",")]
    d = np.array([1.0, 0.0, 3.0]) / np.sqrt(10.0)
    radii = fitted + held
    pts = "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in r * d) + "]" for r in radii) + "]"
    if not os.path.exists(a.out):
        subprocess.run(shlex.split(a.mpiexec) + [
            a.bin, "solve", "-o", a.out, "--progress-interval", "0", "--log-level", "warn",
            "--set", f"grid.dx_m={dx!r}", "--set", f"time.dt_s={dt!r}", "--set", f"pulse.h_s={a.h!r}",
            "--set", f"grid.half_width_m={0.5 + 17 * dx!r}", "--set", f"time.duration_s={max(fitted + held) / c_m_s + 0.012!r}",
            "--set", "object.a_m=0.5", "--set", f"object.b_m={a.b!r}", "--set", f"object.c_m={a.c!r}",
            "--set", f"solve.fields=[{a.field}]", "--set", f"listeners.points_m={pts}",
            "--set", f"kirchhoff.radius_m={0.5 + 3 * dx!r}",
            "--set", "kirchhoff.far_directions=[[" + ", ".join(repr(float(v)) for v in d) + "]]"], check=True)
    with h5py.File(a.out) as f:
        data = f["fields"][f"p{a.field}"][...].astype(float)[f["listeners"].attrs["grid_listeners"]:]
        t_first = float(f["solve"].attrs["t_first_s"])
        far_p = f["far"][f"p{a.field}"][0].astype(float)
        tau_first = float(f["far"].attrs["tau_first_s"])
    n = data.shape[1]

    def retarded(i, r):  # p(r, tau + r/c) on the solve's samples
        return np.interp(np.arange(n) + r / (c_m_s * dt), np.arange(n), data[i], left=0, right=0)

    # The far field on the same retarded samples: tau_k = t_first + k dt.
    far = np.interp(t_first + dt * np.arange(n), tau_first + dt * np.arange(len(far_p)), far_p, left=0, right=0)
    p = np.array([retarded(i, r) for i, r in enumerate(fitted)])
    rel = lambda m, ref: 100 * np.linalg.norm(m - ref) / np.linalg.norm(ref)
    every = fitted + held
    print("radii [m]:              " + "  ".join(f"{r:6.2f}" for r in every))
    for n_terms in (2, 3, 4):
        free = np.linalg.lstsq(np.array([[r ** -(k + 1) for k in range(n_terms)] for r in fitted]), p, rcond=None)[0]
        near = np.linalg.lstsq(np.array([[r ** -(k + 2) for k in range(n_terms - 1)] for r in fitted]),
                               p - far[None, :] / np.array(fitted)[:, None], rcond=None)[0]
        for name, model in (("over the radii", lambda r: sum(free[k] * r ** -(k + 1) for k in range(n_terms))),
                            ("q_1 = far field", lambda r: far / r + sum(near[k] * r ** -(k + 2) for k in range(n_terms - 1)))):
            errs = [rel(model(r), retarded(i, r)) for i, r in enumerate(every)]
            print(f"N = {n_terms}, {name:15s} " + "  ".join(f"{e:5.2f}%" for e in errs))
    u = [1 / r for r in fitted] + [0.0]
    y = [r * p[i] for i, r in enumerate(fitted)] + [far]
    for order in (1, 2, 3):
        errs = []
        for i, r in enumerate(held):
            idx = sorted(range(len(u)), key=lambda j: abs(u[j] - 1 / r))[:order + 1]
            model = sum(np.prod([(1 / r - u[m]) / (u[j] - u[m]) for m in idx if m != j]) * y[j] for j in idx) / r
            errs.append(rel(model, retarded(len(fitted) + i, r)))
        print(f"R p in 1/R, order {order}:   " + "  ".join(f"{r:.2f} m {e:5.2f}%" for r, e in zip(held, errs)))


if __name__ == "__main__":
    main()
