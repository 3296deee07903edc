#!/usr/bin/env python3
"""The FDTD error budget of docs/fdtd.md, term by term, for the pulse psi(t; h) heard at a distance.

  analysis/fdtd_budget.py [--h SECONDS] [--distance M]

Every term is the relative L2 error of psi(t - r/c; h) (the free-field monopole's waveform, 000's
eq. 6) that one approximation alone causes, from its exact frequency response weighted by
|psi^(f)|^2 (no field is stepped; the tests compare these with solves):
  - dispersion: the scheme's discrete dispersion relation (srl: sin^2(w dt/2) = l^2 sum X_a;
    me4: l^2 sum (X_a + X_a^2/3) - (l^4/3) (sum X_a)^2, X_a = sin^2(k_a dx/2)) by direction;
    the same model as kernels/fdtd/dispersion.cpp, written again here from the formulas;
  - source: the spread of a point source over 8 cells (linear weights; response prod cos(k_a dx/2))
    or over 64 (cubic Lagrange weights);
  - interpolation: a listener midway between cell centres along one axis, linear (cos(k dx/2))
    or cubic Lagrange ((9 cos(k dx/2) - cos(3 k dx/2)) / 8).
Prints markdown tables against cells per wavelength at psi's band edge (-40 dB) and the Courant
number.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from field_check import psi  # noqa: E402  (000's eq. 6 in numpy, the analysis' one copy)

C = 343.2


def psi_spectrum(h, f):
    t = np.linspace(0, 2 * h, 801)
    return 2 * np.trapz(psi(t, h)[None, :] * np.cos(2 * np.pi * f[:, None] * t[None, :]), t, axis=1)


def band_edge(h):
    f = np.linspace(0, 10 / h, 20001)
    s = np.abs(psi_spectrum(h, f))
    return f[np.argmax(s < 1e-2 * s[0])]


def dispersion(scheme, lam, dx, d, r, f, weight):
    d = np.asarray(d, float) / np.linalg.norm(d)
    dt = lam * dx / C
    w = 2 * np.pi * f

    def omega(kdx):
        x = np.sin(np.multiply.outer(kdx, d) / 2) ** 2
        s2 = x.sum(-1)
        s4 = (x + x * x / 3).sum(-1)
        s = lam ** 2 * s2 if scheme == "srl" else lam ** 2 * s4 - lam ** 4 / 3 * s2 ** 2
        return 2 * np.arcsin(np.sqrt(np.clip(s, 0, 1))) / dt

    kmax = math.pi / np.abs(d).max()
    lo, hi = np.zeros_like(w), np.full_like(w, kmax)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        below = omega(mid) < w
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
    carried = w < omega(np.array(kmax))
    dk = 0.5 * (lo + hi) / dx - w / C
    e2 = np.where(carried, np.abs(np.exp(-1j * dk * r) - 1) ** 2, 1.0)
    return math.sqrt((weight * e2).sum() / weight.sum())


def amplitude(factor, weight):
    return math.sqrt((weight * (factor - 1) ** 2).sum() / weight.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--h", type=float, default=1e-4)
    ap.add_argument("--distance", type=float, default=1.0)
    a = ap.parse_args()
    h, r = a.h, a.distance
    fe = band_edge(h)
    f = (np.arange(4000) + 0.5) * (8 / h) / 4000
    weight = psi_spectrum(h, f) ** 2
    k = 2 * np.pi * f / C
    print(f"psi(t; h = {h:g} s): band edge {fe / 1e3:.2f} kHz (-40 dB), shortest wavelength {C / fe * 1e3:.1f} mm\n")
    print(f"## Dispersion at {r:g} m, relative L2 (axis / face diagonal / body diagonal)\n")
    cells = [4, 5, 6.52, 8, 10, 13]
    print("| scheme | Courant | " + " | ".join(f"{n:g} cells/λ (dx {C / fe / n * 1e3:.1f} mm)" for n in cells) + " |")
    print("|---|---|" + "---|" * len(cells))
    for scheme in ("srl", "me4"):
        for lam in (0.3, 0.45, 0.55, 0.577):
            row = []
            for n in cells:
                dx = C / fe / n
                e = [dispersion(scheme, lam, dx, d, r, f, weight) for d in ((1, 0, 0), (1, 1, 0), (1, 1, 1))]
                row.append(" / ".join(f"{100 * v:.2g}" for v in e))
            print(f"| {scheme} | {lam:g} | " + " | ".join(row) + " |")
    print("\nvalues in %\n")
    print("## Source and interpolation, relative L2 (% )\n")
    print("| term | " + " | ".join(f"{n:g} cells/λ" for n in cells) + " |")
    print("|---|" + "---|" * len(cells))
    terms = [
        ("8-cell source (srl)", lambda kd: np.cos(kd / 2) ** 1),
        ("64-cell cubic source (me4)", lambda kd: (9 * np.cos(kd / 2) - np.cos(3 * kd / 2)) / 8),
        ("trilinear listener, midway on 1 axis", lambda kd: np.cos(kd / 2)),
        ("tricubic listener, midway on 1 axis", lambda kd: (9 * np.cos(kd / 2) - np.cos(3 * kd / 2)) / 8),
    ]
    for name, fac in terms:
        row = [f"{100 * amplitude(fac(k * C / fe / n), weight):.2g}" for n in cells]
        print(f"| {name} | " + " | ".join(row) + " |")
    lam = 0.55
    row = []
    for n in cells:
        dt = lam * (C / fe / n) / C
        row.append(f"{100 * amplitude(1 + (2 * np.pi * f * dt) ** 2 / 6, weight):.2g}")
    print("| me4 source without the (dt^2/12)(d_tt + c^2 Lap) correction, Courant 0.55 | " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
