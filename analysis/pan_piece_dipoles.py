#!/usr/bin/env python3
"""Fracture pieces' acceleration noise at low frequency, where it is one number per axis: the
dipole M (m^3) that a translation carries, V + m_added / rho (docs/pan.md "Proxy validation"). A
flat piece radiates mostly when it moves across its thin axis (its field 3 carries 7 to 26 times
the energy of the next strongest), so M along that axis measures how well a proxy stands in for it:

- its own PAN (`clatter-bank pan-object`, fields 1-3, at each --dx): the first moment of the far
  field along the axis, M = -4 pi c / (rho h) int t R p dt (exact as omega -> 0; see
  `PanBank.ThinProxiesTranslateWithLambsAddedMass`), then extrapolated to dx -> 0 at first order
  from the two finest (a sharp edge converges at first order);
- its equivalent ellipsoid (the proxy fit of the synthesizer, eq. 11: the ellipsoid of its
  principal moments and volume), by Lamb's formula 2V / (2 - alpha);
- the nearest proxy of the 66-proxy grid (B, C from 0.025 by 0.0475 m), scaled to the piece's a,
  by Lamb's formula (the bank's own proxies hold it within 1.4 % at 2 cm cells);
- a sphere of the piece's volume (3V/2), the simpler proxy 000 section 5 compares against.

  analysis/pan_piece_dipoles.py SCENE.json --out DIR [--pieces K] [--dx 0.02 0.01 0.0065]
      [--bin DIR] [--mpiexec "mpiexec -n 2"]

Writes DIR/piece-dipoles.csv and DIR/piece-dipoles.png; the banks DIR/dx-*.h5 are kept (a run
resumes there).
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys

import numpy as np
from scipy.special import elliprd

from pan_proxy_validation import read_obj, scene_pieces  # beside this script

A_M, RHO, C_M_S, H_S, R_PROBE_M = 0.5, 1.2041, 343.2, 0.0005, 5.0
GRID = [0.025 + 0.0475 * i for i in range(11)]


def mass_properties(v, f):
    """Volume, centre of mass and inertia per density of the polyhedron (signed tetrahedra)."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    volume = vol.sum()
    com = ((a + b + c) / 4 * vol[:, None]).sum(axis=0) / volume
    a, b, c = a - com, b - com, c - com
    s = a + b + c
    second = np.einsum("t,ti,tj->ij", vol / 20, a, a) + np.einsum("t,ti,tj->ij", vol / 20, b, b) \
        + np.einsum("t,ti,tj->ij", vol / 20, c, c) + np.einsum("t,ti,tj->ij", vol / 20, s, s)
    return volume, com, np.trace(second) * np.eye(3) - second


def equivalent_ellipsoid(volume, inertia):
    """kernels::fit_proxy at unit density: semi-axes a >= b >= c and their axes (columns)."""
    moments, axes = np.linalg.eigh(inertia)
    k = 5 / (2 * volume)
    a2, b2, c2 = k * (moments[1] + moments[2] - moments[0]), k * (moments[0] + moments[2] - moments[1]), \
        k * (moments[0] + moments[1] - moments[2])
    scale = np.cbrt(volume / (4 / 3 * math.pi * math.sqrt(a2 * b2 * c2)))
    return scale * math.sqrt(a2), scale * math.sqrt(b2), scale * math.sqrt(c2), axes


def lamb_dipole(a, b, c, axis):
    """Lamb's 2V / (2 - alpha) along semi-axis `axis` (0, 1, 2) of the ellipsoid (a, b, c)."""
    s = [a, b, c]
    alpha = 2 / 3 * a * b * c * elliprd(s[(axis + 1) % 3] ** 2, s[(axis + 2) % 3] ** 2, s[axis] ** 2)
    return 2 * (4 / 3 * math.pi * a * b * c) / (2 - alpha)


def probe(bin_dir, bank, key, field, point):
    out = subprocess.run([f"{bin_dir}/clatter-bank", "probe", bank, "--mesh", key, "--field", str(field), "--point",
                          ",".join(f"{x:.9f}" for x in point)], capture_output=True, text=True, check=True).stdout
    return np.loadtxt(out.splitlines()[1:], delimiter=",")


def mesh_keys(bank):
    """The bank's mesh entries' keys in entry order (docs/bank-format.md `/meshes`): pan-object
    makes them in the order of objects.meshes."""
    import h5py
    with h5py.File(bank) as f:
        keys = f["meshes"].attrs["keys"]
    return (keys.decode() if isinstance(keys, bytes) else str(keys)).split()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("--out", required=True)
    ap.add_argument("--pieces", type=int, default=8)
    ap.add_argument("--dx", type=float, nargs="+", default=[0.02, 0.01, 0.0065])
    ap.add_argument("--bin", default="build/release/bin")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    a = ap.parse_args()
    if len(a.dx) < 2:
        sys.exit("--dx: give at least two cell sizes (the extrapolation uses the two finest)")
    os.makedirs(a.out, exist_ok=True)
    _, pieces, meshes = scene_pieces(a.scene, a.pieces)

    dxs = sorted(a.dx, reverse=True)
    banks = []
    for dx in dxs:
        bank = os.path.join(a.out, f"dx-{dx:g}.h5")
        banks.append(bank)
        if os.path.exists(bank):
            continue
        # The coarsest of 24, 48, 96, 192 kHz under the CFL limit dx / (c sqrt 3).
        dt = next(1 / r for r in (24000, 48000, 96000, 192000) if 1 / r <= 0.99 * dx / (C_M_S * math.sqrt(3)))
        cmd = shlex.split(a.mpiexec) + [f"{a.bin}/clatter-bank", "pan-object", "-o", bank, "--progress-interval", "0",
                                        "--set", f"pulse.h_s={H_S}", "--set", f"grid.dx_m={dx}", "--set", f"time.dt_s={dt!r}",
                                        "--set", "solve.fields=[1, 2, 3]", "--set", "fit.divisions=2",
                                        "--set", "fit.direction_tolerance=0", "--set", "check.held_out_directions=0",
                                        "--set", "fit.epsilon=0",  # the first moment weighs the low-frequency tail
                                        "--set", "objects.meshes=[" + ", ".join(json.dumps(m) for m in meshes) + "]"]
        print(" ".join(shlex.quote(c) for c in cmd), flush=True)
        subprocess.run(cmd, check=True)

    rows = []
    for i, path in enumerate(meshes):
        v, f = read_obj(path)
        volume, com, inertia = mass_properties(v, f)
        ea, eb, ec, axes = equivalent_ellipsoid(volume, inertia)
        n = axes[:, 2]  # the largest moment's axis: the thin one
        scale = A_M / np.linalg.norm(v - com, axis=1).max()
        own = []
        for bank in banks:
            keys = mesh_keys(bank)
            if len(keys) != len(meshes):
                sys.exit(f"{bank}: {len(keys)} mesh entries, not the {len(meshes)} pieces (an older run's? remove it)")
            key = keys[i]
            series = None
            for field in (1, 2, 3):
                d = probe(a.bin, bank, key, field, R_PROBE_M * n)
                series = d[:, 1] * n[field - 1] if series is None else series + d[:, 1] * n[field - 1]
            t, dt = d[:, 0] - R_PROBE_M / C_M_S, d[1, 0] - d[0, 0]
            moment = -4 * math.pi * C_M_S * R_PROBE_M / RHO * float(np.sum(t * series)) * dt / H_S
            own.append(moment / scale ** 3)  # the entry is the piece scaled by `scale`
        fine, coarse = own[-1], own[-2]
        own_limit = fine + (fine - coarse) * dxs[-1] / (dxs[-2] - dxs[-1])
        b_n, c_n = A_M * eb / ea, A_M * ec / ea
        proxy = min(((bb, cc) for bb in GRID for cc in GRID if cc <= bb + 1e-12), key=lambda q: (q[0] - b_n) ** 2 + (q[1] - c_n) ** 2)
        rows.append({"piece": i + 1, "mesh": os.path.basename(path), "mass_g": pieces[i]["mass_kg"] * 1e3,
                     "a_mm": ea * 1e3, "b_mm": eb * 1e3, "c_mm": ec * 1e3, "B": b_n, "C": c_n, "proxy_B": proxy[0], "proxy_C": proxy[1],
                     "width_cells": {dx: 2 * eb * scale / dx for dx in dxs},
                     "own_cm3": {dx: m * 1e6 for dx, m in zip(dxs, own)}, "own_limit_cm3": own_limit * 1e6,
                     "ellipsoid_cm3": lamb_dipole(ea, eb, ec, 2) * 1e6,
                     "proxy_cm3": lamb_dipole(A_M, proxy[0], proxy[1], 2) * (ea / A_M) ** 3 * 1e6,
                     "sphere_cm3": 1.5 * volume * 1e6})

    with open(os.path.join(a.out, "piece-dipoles.csv"), "w") as out:
        out.write("piece,mesh,mass_g,a_mm,b_mm,c_mm,B,C,proxy_B,proxy_C," + ",".join(f"own_dx{dx:g}_cm3" for dx in dxs)
                  + ",own_limit_cm3,ellipsoid_cm3,nearest_proxy_cm3,equal_volume_sphere_cm3\n")
        for r in rows:
            out.write(f"{r['piece']},{r['mesh']},{r['mass_g']:.4g},{r['a_mm']:.4g},{r['b_mm']:.4g},{r['c_mm']:.4g},{r['B']:.4g},{r['C']:.4g},"
                      f"{r['proxy_B']:.4g},{r['proxy_C']:.4g}," + ",".join(f"{r['own_cm3'][dx]:.5g}" for dx in dxs)
                      + f",{r['own_limit_cm3']:.5g},{r['ellipsoid_cm3']:.5g},{r['proxy_cm3']:.5g},{r['sphere_cm3']:.5g}\n")
    print("M across the thin axis [cm^3], and against the own PAN extrapolated to dx -> 0:")
    print("piece  (B, C)          own at dx = " + " ".join(f"{dx:g}" for dx in dxs) + "  -> limit | ellipsoid  nearest proxy  sphere of V")
    for r in rows:
        lim = r["own_limit_cm3"]
        print(f"{r['piece']:5d}  ({r['B']:.3f}, {r['C']:.3f})  " + " ".join(f"{r['own_cm3'][dx]:7.3f}" for dx in dxs)
              + f"  -> {lim:7.3f} | {r['ellipsoid_cm3'] / lim:6.3f}  {r['proxy_cm3'] / lim:6.3f} ({r['proxy_B']:.4g}, {r['proxy_C']:.4g})"
              f"  {r['sphere_cm3'] / lim:6.3f}")
    for name in ("ellipsoid", "proxy", "sphere"):
        q = np.array([r[f"{name}_cm3"] / r["own_limit_cm3"] for r in rows])
        print(f"{name:9s}: ratio to the own limit median {np.median(q):.3f}, range {q.min():.3f}-{q.max():.3f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    x = np.arange(len(rows)) + 1
    for name, label, marker in (("ellipsoid", "equivalent ellipsoid (Lamb)", "o"), ("proxy", "nearest of the 66 proxies", "s"),
                                ("sphere", "sphere of the same volume", "v")):
        left.plot(x, [r[f"{name}_cm3"] / r["own_limit_cm3"] for r in rows], marker, label=label)
    left.axhline(1, color="k", lw=0.8)
    left.set_xlabel("piece")
    left.set_ylabel("M / the piece's own (dx -> 0)")
    left.set_title("Broadside dipole of each piece")
    left.legend(fontsize=8)
    left.grid(alpha=0.3)
    for r in rows:
        w = [r["width_cells"][dx] for dx in dxs]
        right.plot(w, [r["own_cm3"][dx] / r["own_limit_cm3"] for dx in dxs], ".-", label=f"piece {r['piece']}")
    right.set_xscale("log")
    right.set_xlabel("width 2b in cells (equivalent ellipsoid at the entry's scale)")
    right.set_ylabel("own M / its limit")
    right.set_title("Own PAN against the cell size")
    right.grid(alpha=0.3)
    right.legend(fontsize=7, ncol=2)
    fig.suptitle(f"{len(rows)} pieces of {os.path.basename(a.scene)}: acceleration noise as omega -> 0")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "piece-dipoles.png"), dpi=120)
    print(f"wrote {a.out}/piece-dipoles.csv and .png")


if __name__ == "__main__":
    main()
