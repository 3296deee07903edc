#!/usr/bin/env python3
"""003 Table 2 on a Clatter scene: how much the ellipsoid proxies save, and what they cost in accuracy.

  proxy_table.py SCENE.json OBJECTS.h5 [OBJECTS2.h5 ...] --synth CLATTER_SYNTH -m MODAL.h5 [-m ...] [-o DIR]
                 [--thresholds 0,2000,5000,10000,20000,inf]

OBJECTS.h5 are object banks (`clatter-bank object --set objects.scene=SCENE.json --set
objects.proxy_above_hz=1e9`, or several of parts of the scene) holding every object of the scene:
the direct path's models. Objects no bank holds (a failed task) are left out of the tables and
counted. The
script renders the scene's modal sound twice with `clatter-synth --voices`: every object with its
own model (--proxy-above-hz 1e9 -O OBJECTS.h5) and every object with its proxy (--proxy-above-hz 0),
and reads each object's voice (own entry or proxy, its first rendered frequencies, its impacts and
the energy its modes radiated). Then, per threshold omega_proxy (Hz), as 003 Table 2:
  - modes replaced: the share of the direct path's modes in [20 Hz, 20 kHz] (those of the objects
    at or above the threshold, which proxies voice instead);
  - model generation: the object bank's core-seconds (FEM + transfer, /provenance/run/entries) of
    the objects below the threshold, against all objects' (the proxies' bank is shared and built
    once, so it is not charged to a scene);
and per object the proxy's accuracy against the object's own model: the ratios f_k(proxy) /
f_k(own) of the first rendered frequencies (k = 1..3), and the level difference of the energy its
modes radiate per impact, 10 log10(proxy / own) dB. Writes DIR/proxy_table.md (the tables),
DIR/proxy_table.csv (per object) and DIR/proxy_threshold.png (modes replaced and cost against
omega_proxy; frequency ratios and level differences against each object's base frequency).
Exit 2 on bad input (a missing file, a bank that is not an object bank, a render that fails).
"""
import argparse
import csv
import math
import os
import subprocess
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(message):
    print(f"proxy_table.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_bank(path):
    """key -> (modes in [20 Hz, 20 kHz], core-seconds of the entry)."""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail(f"{path}: {e}")
    with f:
        if f.attrs.get("format") not in ("clatter-object-bank", b"clatter-object-bank"):
            fail(f"{path}: not an object bank (format {f.attrs.get('format')!r})")
        out = {}
        for name, e in f["entries"].items():
            freqs = e["frequencies_hz"][...]
            cost = f[f"provenance/run/entries/{name}"].attrs
            core_s = cost["total_s"] * cost["ranks"] - cost["transfer_s"] * cost["ranks"] + cost["transfer_core_s"]
            key = e.attrs["key"]
            out[key.decode() if isinstance(key, bytes) else key] = (int(((freqs >= 20) & (freqs <= 20000)).sum()), core_s)
        return out


def voices(synth, scene, banks, out_csv, *options):
    cmd = [synth, "-i", scene, "-o", os.path.splitext(out_csv)[0] + ".wav", "--voices", out_csv, *options]
    for b in banks:
        cmd += ["-m", b]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"{' '.join(cmd)}: exit {r.returncode}: {r.stderr.strip()[-400:]}")
    with open(out_csv) as f:
        return {int(row["object"]): row for row in csv.DictReader(f)}


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("scene")
    p.add_argument("objects", nargs="+")
    p.add_argument("--synth", required=True)
    p.add_argument("-m", "--modal-bank", action="append", required=True)
    p.add_argument("-o", "--out", default=".")
    p.add_argument("--thresholds", default="0,1000,2000,5000,10000,20000,inf")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    bank = {}
    for path in a.objects:
        bank.update(read_bank(path))
    with_banks = [x for path in a.objects for x in ("-O", path)]
    own = voices(a.synth, a.scene, a.modal_bank, os.path.join(a.out, "own.csv"), *with_banks, "--proxy-above-hz", "1e9")
    proxy = voices(a.synth, a.scene, a.modal_bank, os.path.join(a.out, "proxy.csv"), "--proxy-above-hz", "0")
    rows, missing = [], []
    for oid, o in sorted(own.items()):
        if o["voiced_by"] != "own":
            missing.append(oid)
            continue
        q = proxy[oid]
        modes, core_s = bank[o["entry"]]
        row = {"object": oid, "base_frequency_hz": float(o["base_frequency_hz"]), "own_modes": modes, "core_s": core_s,
               "proxy_modes": int(q["modes_rendered"]), "impacts": int(o["impacts"])}
        for k in (1, 2, 3):
            fo, fp = o[f"f{k}_hz"], q[f"f{k}_hz"]
            row[f"f{k}_ratio"] = float(fp) / float(fo) if fo and fp else float("nan")
        ro, rp = float(o["radiated_j"]), float(q["radiated_j"])
        row["level_db"] = 10 * math.log10(rp / ro) if ro > 0 and rp > 0 else float("nan")
        rows.append(row)
    with open(os.path.join(a.out, "proxy_table.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    total_modes = sum(r["own_modes"] for r in rows)
    total_core_s = sum(r["core_s"] for r in rows)
    lines = ["| omega_proxy / 2 pi | objects with their own model | modes replaced by proxies | model generation "
             "(core-s) | of the direct path's |", "|---|---|---|---|---|"]
    thresholds = [float(t) for t in a.thresholds.split(",")]
    table = []
    for t in thresholds:
        below = [r for r in rows if r["base_frequency_hz"] < t]
        replaced = total_modes - sum(r["own_modes"] for r in below)
        cost = sum(r["core_s"] for r in below)
        table.append((t, len(below), replaced / total_modes if total_modes else 0, cost))
        lines.append(f"| {t:g} Hz | {len(below)} of {len(rows)} | {100 * replaced / max(total_modes, 1):.1f} % "
                     f"({replaced} of {total_modes}) | {cost:.1f} | {100 * cost / max(total_core_s, 1e-12):.1f} % |")
    ratios = [r["f2_ratio"] for r in rows if not math.isnan(r["f2_ratio"])]
    levels = [r["level_db"] for r in rows if not math.isnan(r["level_db"])]
    if missing:
        lines += ["", f"Left out: objects {', '.join(map(str, missing))}, which no object bank given holds."]
    lines += ["", f"Proxies against own models, {len(rows)} objects: f_2 ratio median "
              f"{sorted(ratios)[len(ratios) // 2] if ratios else float('nan'):.3f} (range {min(ratios, default=float('nan')):.3f}-"
              f"{max(ratios, default=float('nan')):.3f}); radiated level per impact, proxy - own: median "
              f"{sorted(levels)[len(levels) // 2] if levels else float('nan'):+.1f} dB (range "
              f"{min(levels, default=float('nan')):+.1f} to {max(levels, default=float('nan')):+.1f} dB)."]
    with open(os.path.join(a.out, "proxy_table.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    finite = [x for x in table if math.isfinite(x[0])]
    xs = [max(x[0], 1) for x in finite]
    ax[0].semilogx(xs, [100 * x[2] for x in finite], "o-", label="modes replaced (%)")
    ax[0].semilogx(xs, [100 * x[3] / max(total_core_s, 1e-12) for x in finite], "s-", label="model generation (% of direct)")
    ax[0].set_xlabel("omega_proxy / 2 pi [Hz] (0 plotted at 1)")
    ax[0].set_ylabel("%")
    ax[0].legend()
    ax[0].set_title("003 Table 2 on this scene")
    f0 = [r["base_frequency_hz"] for r in rows]
    for k, marker in ((1, "o"), (2, "s"), (3, "^")):
        ax[1].semilogx(f0, [r[f"f{k}_ratio"] for r in rows], marker, label=f"f_{k}(proxy) / f_{k}(own)")
    ax[1].axhline(1, color="k", lw=0.5)
    ax[1].set_xlabel("object's base frequency [Hz]")
    ax[1].set_ylabel("ratio")
    ax[1].legend()
    ax[1].set_title("frequencies")
    ax[2].semilogx(f0, [r["level_db"] for r in rows], "o")
    ax[2].axhline(0, color="k", lw=0.5)
    ax[2].set_xlabel("object's base frequency [Hz]")
    ax[2].set_ylabel("proxy - own [dB]")
    ax[2].set_title("radiated energy per impact")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "proxy_threshold.png"), dpi=110)


if __name__ == "__main__":
    main()
