#!/usr/bin/env python3
"""PAN bank analysis (Chadwick et al. 2012, section 5 and Figures 3-4), driven through the
command-line tools, so it checks what users get.

  pan_plots.py --out DIR [--bin build/release/bin/clatter-bank] [--mpiexec "mpiexec -n 2"]
               [--config configs/pan.toml] [--proxies 3]

Writes to DIR:
  epsilon.png, epsilon.csv   (a) bank size and held-out error versus epsilon
                                 (0.01 ... 0.64): the full bank of --config for the sizes, its
                                 first --proxies proxies for the errors against raw FDTD signals
                                 at held-out radii and directions between vertices
  proxies_p3.png             (b) p3 at one point for several proxies (Figure 4)
  direction_fit.png          (c) one direction: raw FDTD at the radii up to 1.5 m, shifted by R/c, and the
                                 bank's fit (Figure 3)
"""
import argparse
import csv
import io
import os
import shlex
import subprocess
import tempfile

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

EPSILONS = [0.01, 0.02, 0.04, 0.08, 0.16, 0.32, 0.64]
HELD_OUT = [(0.85, (0.37, 0.52, 0.77)), (1.05, (0.8, 0.25, 0.55)), (1.35, (0.2, 0.6, 0.4))]


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def toml_value(config, section, key):
    current = None
    for line in open(config):
        line = line.strip()
        if line.startswith("["):
            current = line.strip("[]")
        elif current == section and line.startswith(key + " ="):
            return line.split("=", 1)[1].strip()
    raise KeyError(f"{section}.{key}")


def probe(args, bank, b, c, field, x):
    out = run([args.bin, "probe", bank, "--proxy", f"{b!r},{c!r}", "--field", str(field), "--point",
               ",".join(repr(float(v)) for v in x)]).stdout
    data = np.loadtxt(io.StringIO(out), delimiter=",", skiprows=1)
    return data[:, 0], data[:, 1]


def bank_info(bank):
    with h5py.File(bank) as f:
        g = f["bank"].attrs
        # Per (proxy, field) direction sets (docs/bank-format.md); each starts with the layout's
        # vertices, in the same order for every set: the first solved set's are the layout's.
        offsets = f["directions/vertex_offsets"][...]
        first = next(s for s in range(len(offsets) - 1) if offsets[s + 1] > offsets[s])
        d = int(g["divisions"])
        return dict(dt=float(g["dt_s"]), c=float(g["c_m_s"]), radii=f["bank/radii_m"][...],
                    directions=f["directions/unit"][offsets[first]:offsets[first] + (d + 1) * (d + 2) // 2],
                    b=f["proxies/b_m"][...], c_m=f["proxies/c_m"][...])


def raw_solve(args, config, tmp, b, c, points, fields="[1, 2, 3, 4, 5, 6]"):
    """The FDTD signals at `points` for proxy (0.5, b, c) on the bank's cell size and step, on a grid
    that just holds the points (the bank hears its radii, out to 5 m, through a Kirchhoff surface)."""
    dx = float(toml_value(config, "grid", "dx_m"))
    reach = max(float(np.linalg.norm(p)) for p in points)
    out = os.path.join(tmp, "raw.h5")
    pts = "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in p) + "]" for p in points) + "]"
    cmd = shlex.split(args.mpiexec) + [args.bin, "solve", "-o", out, "--progress-interval", "0", "--log-level", "warn"]
    for key in ("medium.c_m_s", "medium.rho_kg_m3", "pulse.h_s", "grid.dx_m", "grid.pml_cells", "time.dt_s",
                "solver.cut_cell_samples"):
        s, k = key.split(".")
        cmd += ["--set", f"{key}={toml_value(config, s, k)}"]
    tail = float(toml_value(config, "time", "tail_s"))
    c_m_s = float(toml_value(config, "medium", "c_m_s"))
    try:
        scheme = toml_value(config, "solver", "scheme").strip('"')
    except KeyError:
        scheme = "me4"
    # 3 cells past the farthest point for its stencil, and 8 more for me4's blend into the PML.
    margin = 3 + (8 if scheme == "me4" else 0)
    cmd += ["--set", f"solver.scheme={scheme}"]
    cmd += ["--set", f"grid.half_width_m={reach + margin * dx!r}", "--set", "grid.octant=true",
            "--set", f"time.duration_s={reach / c_m_s + tail!r}", "--set", "object.a_m=0.5",
            "--set", f"object.b_m={b!r}", "--set", f"object.c_m={c!r}", "--set", f"solve.fields={fields}",
            "--set", f"listeners.points_m={pts}"]
    run(cmd)
    with h5py.File(out) as f:
        s = f["solve"].attrs
        t = s["t_first_s"] + s["dt_s"] * np.arange(f["fields/p1"].shape[1]) if "fields/p1" in f else None
        fields_data = {int(k[1:]): f["fields"][k][...] for k in f["fields"]}
        if t is None:
            n = next(iter(fields_data.values())).shape[1]
            t = s["t_first_s"] + s["dt_s"] * np.arange(n)
    return t, fields_data


def build_bank(args, config, out, epsilon, proxies=None):
    cmd = shlex.split(args.mpiexec) + [args.bin, "pan", "-c", config, "-o", out, "--progress-interval", "0",
                                       "--log-level", "warn", "--set", f"fit.epsilon={epsilon!r}"]
    if proxies is not None:
        cmd += ["--set", "proxies.list_m=[" + ", ".join(f"[{b!r}, {c!r}]" for b, c in proxies) + "]"]
    run(cmd)


def epsilon_study(args, tmp):
    rows = []
    full = os.path.join(tmp, "full.h5")
    build_bank(args, args.config, full, 0.01)
    info = bank_info(full)
    proxies = list(zip(info["b"], info["c_m"]))
    step = max(1, len(proxies) // args.proxies)
    chosen = proxies[::step][: args.proxies]
    points = []
    for r, d in HELD_OUT:
        d = np.array(d) / np.linalg.norm(d)
        points.append(r * d)
    raws = {(b, c): raw_solve(args, args.config, tmp, b, c, points) for b, c in chosen}
    for eps in EPSILONS:
        bank = os.path.join(tmp, f"bank_{eps}.h5")
        build_bank(args, args.config, bank, eps)
        size_mb = os.path.getsize(bank) / 1e6
        errors = []
        small = os.path.join(tmp, f"small_{eps}.h5")
        build_bank(args, args.config, small, eps, chosen)
        for (b, c), (t_raw, fields) in raws.items():
            for field, series in fields.items():
                for i, x in enumerate(points):
                    t, p = probe(args, small, b, c, field, x)
                    pan = np.interp(t_raw, t, p, left=0.0, right=0.0)
                    raw = series[i]
                    # A field the proxy does not radiate (a needle turning about its own axis) has
                    # no relative error to speak of.
                    if np.linalg.norm(raw) > 1e-9 * max(np.linalg.norm(s) for s in series):
                        errors.append(np.linalg.norm(pan - raw) / np.linalg.norm(raw))
        rows.append(dict(epsilon=eps, size_mb=size_mb, median_error=float(np.median(errors)),
                         max_error=float(np.max(errors))))
        print(f"epsilon {eps}: {size_mb:.3f} MB, held-out error median {rows[-1]['median_error']:.4f}, "
              f"max {rows[-1]['max_error']:.4f}", flush=True)
    with open(os.path.join(args.out, "epsilon.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    eps = [r["epsilon"] for r in rows]
    ax[0].loglog(eps, [r["size_mb"] for r in rows], "o-")
    ax[0].set(xlabel="epsilon", ylabel="bank size [MB]", title=f"{len(proxies)} proxies")
    ax[1].loglog(eps, [100 * r["median_error"] for r in rows], "o-", label="median")
    ax[1].loglog(eps, [100 * r["max_error"] for r in rows], "s--", label="max")
    ax[1].set(xlabel="epsilon", ylabel="relative L2 error [%]", title="held-out radii and directions vs FDTD")
    ax[1].legend()
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "epsilon.png"), dpi=110)
    return full


def proxies_figure(args, bank):
    info = bank_info(bank)
    x = np.array([0.0, 0.0, 1.2])
    fig, ax = plt.subplots(figsize=(7, 4))
    proxies = list(zip(info["b"], info["c_m"]))
    for b, c in proxies[:: max(1, len(proxies) // 8)]:
        t, p = probe(args, bank, b, c, 3, x)
        ax.plot(1e3 * t, p, label=f"B={b:.3f}, C={c:.3f}")
    ax.set(xlabel="t [ms]", ylabel="p3 [Pa per m/s^2]", title="p3 at (0, 0, 1.2) m across proxies (cf. Figure 4)")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "proxies_p3.png"), dpi=110)


def direction_figure(args, bank, tmp):
    info = bank_info(bank)
    d = info["directions"][20]
    b, c = info["b"][-1], info["c_m"][-1]
    radii = [r for r in info["radii"] if r <= 1.55]  # the near radii: a grid to 5 m would be huge
    points = [r * d for r in radii]
    t_raw, fields = raw_solve(args, args.config, tmp, b, c, points, fields="[3]")
    raw = fields[3]
    fig, ax = plt.subplots(1, 3, figsize=(13, 3.8), sharey=True)
    for i, r in enumerate(radii):
        ax[0].plot(1e3 * t_raw, raw[i], label=f"R = {r:.2f} m")
        ax[1].plot(1e3 * (t_raw - r / info["c"]), raw[i] * r)
        t, p = probe(args, bank, b, c, 3, points[i])
        ax[2].plot(1e3 * (t - r / info["c"]), p * r)
    ax[0].set(xlabel="t [ms]", ylabel="R p3", title=f"FDTD at {len(radii)} radii (p3)")
    ax[0].set_ylabel("p3 (left) / R p3 [Pa m per m/s^2]")
    ax[0].legend(fontsize=7)
    ax[1].set(xlabel="t - R/c [ms]", title="shifted by R/c, times R")
    ax[2].set(xlabel="t - R/c [ms]", title="bank (fit, epsilon = 0.01), times R")
    fig.suptitle(f"direction {np.round(d, 3)}, proxy B={b:.3f}, C={c:.3f} (cf. Figure 3)")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "direction_fit.png"), dpi=110)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--bin", default="build/release/bin/clatter-bank")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    ap.add_argument("--config", default="configs/pan.toml")
    ap.add_argument("--proxies", type=int, default=3)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        bank = epsilon_study(args, tmp)
        proxies_figure(args, bank)
        direction_figure(args, bank, tmp)
    print(f"wrote {args.out}/epsilon.png, epsilon.csv, proxies_p3.png, direction_fit.png")


if __name__ == "__main__":
    main()
