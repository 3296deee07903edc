#!/usr/bin/env python3
"""Held-out error of PAN banks against radius, out to 3 m (docs/pan.md, "The far field and the
radial series"): banks of one proxy built with several fit settings, probed at radii 0.85-3 m in
three directions strictly inside triangles, against (a) the same solve heard through a Kirchhoff
surface (`solve --set kirchhoff.radius_m`) and, with --raw, (b) a raw grid that holds listeners out
to 3 m (slow at the paper's resolution).

  analysis/pan_radial_check.py CONFIG B C FIELDS OUTDIR [--variant NAME:key=v,key=v ...] [--raw]

e.g. analysis/pan_radial_check.py configs/pan-demo.toml 0.2625 0.12 "[1,4]" out/radial \\
       --variant paper:fit.far_field=false --variant far3:fit.far_field=true,fit.terms=3
Prints, per field, reference and variant, the worst relative L2 over the directions at each radius.
"""
import argparse
import io
import os
import shlex
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pan_plots import toml_value  # noqa: E402

DIRECTIONS = [(0.37, 0.52, 0.77), (0.8, 0.25, 0.55), (0.2, 0.6, 0.4)]
RADII = [0.85, 1.05, 1.35, 1.8, 3.0]


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode:
        sys.exit(f"{' '.join(cmd[:4])} ...: {r.stderr[-2000:]}")
    return r.stdout


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("config")
    ap.add_argument("b", type=float)
    ap.add_argument("c", type=float)
    ap.add_argument("fields")
    ap.add_argument("out")
    ap.add_argument("--variant", action="append", default=[], help="NAME:key=value,key=value (default: paper and far3)")
    ap.add_argument("--raw", action="store_true", help="also solve a grid holding the listeners out to 3 m")
    ap.add_argument("--bin", default="build/release/bin/clatter-bank")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    mpi = shlex.split(a.mpiexec)
    variants = a.variant or ["paper:fit.far_field=false", "far3:fit.far_field=true,fit.terms=3"]
    banks = {}
    for v in variants:
        name, sets = v.split(":", 1)
        bank = os.path.join(a.out, f"bank-{name}.h5")
        if os.path.exists(bank):
            os.remove(bank)
        cmd = mpi + [a.bin, "pan", "-c", a.config, "-o", bank, "--progress-interval", "0", "--log-level", "warn",
                     "--set", f"proxies.list_m=[[{a.b!r},{a.c!r}]]", "--set", f"solve.fields={a.fields}"]
        for kv in filter(None, sets.split(",")):
            cmd += ["--set", kv]
        run(cmd)
        banks[name] = bank
    pts = [r * np.array(d) / np.linalg.norm(d) for r in RADII for d in DIRECTIONS]
    dx = float(toml_value(a.config, "grid", "dx_m"))
    tail = float(toml_value(a.config, "time", "tail_s"))
    c_m_s = float(toml_value(a.config, "medium", "c_m_s"))
    listeners = "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in q) + "]" for q in pts) + "]"

    def solve(path, half_width, extra):
        cmd = mpi + [a.bin, "solve", "-o", path, "--progress-interval", "0", "--log-level", "warn"]
        for key in ("medium.c_m_s", "medium.rho_kg_m3", "pulse.h_s", "grid.dx_m", "grid.pml_cells", "time.dt_s",
                    "solver.cut_cell_samples"):
            s, k = key.split(".")
            cmd += ["--set", f"{key}={toml_value(a.config, s, k)}"]
        cmd += ["--set", f"grid.half_width_m={half_width!r}", "--set", "grid.octant=true",
                "--set", f"time.duration_s={3.0 / c_m_s + tail!r}", "--set", "object.a_m=0.5",
                "--set", f"object.b_m={a.b!r}", "--set", f"object.c_m={a.c!r}", "--set", f"solve.fields={a.fields}",
                "--set", f"listeners.points_m={listeners}"] + extra
        run(cmd)
        with h5py.File(path) as f:
            s = f["solve"].attrs
            data = {int(k[1:]): f["fields"][k][...] for k in f["fields"]}
            t = s["t_first_s"] + s["dt_s"] * np.arange(next(iter(data.values())).shape[1])
        return t, data

    # The surface 3 cells off the bounding sphere, as fit.far_field puts it.
    refs = {"surface": solve(os.path.join(a.out, "surface.h5"), 0.5 + 17 * dx,
                             ["--set", f"kirchhoff.radius_m={0.5 + 3 * dx!r}"])}
    if a.raw:
        refs["raw"] = solve(os.path.join(a.out, "raw.h5"), 3.0 + 11 * dx, [])
    for field in sorted(refs["surface"][1]):
        for ref_name, (t, data) in refs.items():
            for name, bank in banks.items():
                line = []
                for ri, r in enumerate(RADII):
                    worst = 0.0
                    for di in range(len(DIRECTIONS)):
                        i = ri * len(DIRECTIONS) + di
                        out = run([a.bin, "probe", bank, "--proxy", f"{a.b!r},{a.c!r}", "--field", str(field),
                                   "--point", ",".join(repr(float(v)) for v in pts[i])])
                        pd = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
                        ref = data[field][i]
                        got = np.interp(t, pd[:, 0], pd[:, 1], left=0, right=0)
                        m = t <= pd[-1, 0]
                        worst = max(worst, np.sqrt(np.sum((got[m] - ref[m]) ** 2) / np.sum(ref[m] ** 2)))
                    line.append(f"{r} m: {100 * worst:5.2f} %")
                print(f"field {field} against {ref_name:7s} {name:8s} " + "  ".join(line), flush=True)


if __name__ == "__main__":
    main()
