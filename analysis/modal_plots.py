#!/usr/bin/env python3
"""Modal bank overview (Zheng & James 2010, section 5; docs/bank-format.md "Modal bank"), read
from the file alone.

  modal_plots.py BANK.h5 -o OUTDIR

Writes to OUTDIR:
  spectra.png   per entry one row of ticks at f_k / f_1 (the normalized spectrum, 1 ..
                f_max_multiple and the end of the last multiplet), coloured by the multiplicity of
                the mode's multiplet (`multiplet`, by symmetry), rows labelled with the axis ratios (a/c, b/c)
  patch.png     the entries on the ellipsoid patch in (a/c, b/c), coloured by f_1 [Hz] at the
                bank's normalized size (a^2 + b^2 + c^2 = 1 m^2), with the corners sphere (1, 1),
                cigar (r_c, r_c) and pancake (r, 1) of r = min_ratio, r_c = cigar_ratio marked
"""
import argparse
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def read_bank(path):
    with h5py.File(path, "r") as f:
        if text(f.attrs.get("format", "")) != "clatter-modal-bank":
            sys.exit(f"{path}: not a modal bank (format '{text(f.attrs.get('format', ''))}')")
        axes = f["entries/axes_m"][...]
        entries = []
        for i in range(axes.shape[0]):
            e = f[f"entries/{i:04d}"]
            entries.append(dict(axes=e["axes_m"][...], freq=e["frequencies_hz"][...], multiplet=e["multiplet"][...]))
        s, m, sw = f["settings"].attrs, f["material"].attrs, f["sweep"].attrs
        return dict(entries=entries, material=text(m["name"]), nu=float(m["poisson"]),
                    f_max_multiple=float(s["f_max_multiple"]), min_ratio=float(s["min_ratio"]),
                    cigar_ratio=float(s["cigar_ratio"] if "cigar_ratio" in s else s["min_ratio"]),
                    n_failed=int(sw["n_failed"]), n_missing=int(sw["n_missing"]), tasks=int(sw["tasks_total"]))


def multiplicities(multiplet):
    """Per mode: the size of its multiplet (degenerate by symmetry, docs/modal.md)."""
    _, inverse, counts = np.unique(multiplet, return_inverse=True, return_counts=True)
    return counts[inverse]


def colour_of(mult):
    return plt.get_cmap("tab10")((min(mult, 10) - 1) % 10)


def title_of(bank):
    done = len(bank["entries"])
    missing = f", {bank['n_failed']} failed, {bank['n_missing']} missing" if done < bank["tasks"] else ""
    return f"{bank['material']} (nu = {bank['nu']:g}), {done} of {bank['tasks']} ellipsoids{missing}"


def spectra_figure(bank, out):
    entries = bank["entries"]
    n = len(entries)
    fig, ax = plt.subplots(figsize=(9, min(2.2 + 0.32 * n, 30)))
    seen = set()
    for row, e in enumerate(entries):
        ratio = e["freq"] / e["freq"][0]
        mult = multiplicities(e["multiplet"])
        for m in np.unique(mult):
            ax.vlines(ratio[mult == m], row - 0.38, row + 0.38, colors=[colour_of(m)], linewidth=1.4)
            seen.add(min(int(m), 10))
    ax.axvline(bank["f_max_multiple"], color="0.5", linestyle="--", linewidth=0.8)
    step = max(1, int(np.ceil(n / 60)))
    rows = list(range(0, n, step))
    ax.set_yticks(rows)
    ax.set_yticklabels([f"{i:04d}  ({entries[i]['axes'][0] / entries[i]['axes'][2]:.3f}, "
                        f"{entries[i]['axes'][1] / entries[i]['axes'][2]:.3f})" for i in rows], fontsize=8)
    ax.set_ylim(n - 0.5, -0.5)
    ax.set(xlabel="f_k / f_1", ylabel="entry  (a/c, b/c)",
           title=f"normalized spectra to f_max = {bank['f_max_multiple']:g} f_1 (dashed)\n{title_of(bank)}")
    ax.title.set_fontsize(9)
    handles = [Line2D([], [], color=colour_of(m), linewidth=2, label=str(m) if m < 10 else "10+") for m in sorted(seen)]
    ax.legend(handles=handles, title="multiplicity", fontsize=8, title_fontsize=8, loc="center left",
              bbox_to_anchor=(1.01, 0.5), frameon=False)
    ax.grid(axis="x", color="0.9")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "spectra.png"), dpi=110)
    plt.close(fig)


def patch_figure(bank, out):
    entries, r, rc = bank["entries"], bank["min_ratio"], bank["cigar_ratio"]
    x = np.array([e["axes"][0] / e["axes"][2] for e in entries])
    y = np.array([e["axes"][1] / e["axes"][2] for e in entries])
    f1 = np.array([e["freq"][0] for e in entries])
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    corners = {"sphere": (1, 1), "cigar": (rc, rc), "pancake": (r, 1)}
    # The edge cigar -> pancake is straight in (ln b/c, ln a/b): b/c = r_c^(1-t), a/c = b/c r^t.
    t = np.linspace(0, 1, 65)
    edge_x, edge_y = rc ** (1 - t) * r ** t, rc ** (1 - t)
    bx, by = np.concatenate([[1], edge_x, [1]]), np.concatenate([[1], edge_y, [1]])
    ax.fill(bx, by, color="0.95", zorder=0)
    ax.plot(bx, by, color="0.4", linewidth=1, zorder=1)
    for name, (cx, cy), (dx, dy), ha in zip(corners, corners.values(), [(6, -12), (-6, -12), (-6, 6)],
                                            ["left", "right", "right"]):
        ax.plot(cx, cy, marker="s", markerfacecolor="none", markeredgecolor="0.2", markersize=11, zorder=2)
        ax.annotate(name, (cx, cy), xytext=(dx, dy), textcoords="offset points", ha=ha, fontsize=9)
    sc = ax.scatter(x, y, c=f1, cmap="viridis", s=40 if len(entries) <= 200 else 12, edgecolors="k",
                    linewidths=0.4, zorder=3)
    if len(entries) <= 30:
        for i, (px, py) in enumerate(zip(x, y)):
            ax.annotate(f"{i:04d}", (px, py), xytext=(5, 3), textcoords="offset points", fontsize=7, zorder=4)
    fig.colorbar(sc, ax=ax, label="f_1 [Hz] (a^2 + b^2 + c^2 = 1 m^2)")
    pad = 0.04 * (1 - r)
    ax.set(xlim=(r - 3 * pad, 1 + 3 * pad), ylim=(r - 3 * pad, 1 + 3 * pad), xlabel="a/c", ylabel="b/c",
           title=f"the patch a <= b <= c, a/c >= {r:g}, cigar b/c = {rc:g}\n{title_of(bank)}")
    ax.title.set_fontsize(9)
    ax.set_aspect("equal")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "patch.png"), dpi=110)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("bank", help="a clatter-modal-bank file")
    ap.add_argument("-o", "--out", required=True, help="output folder (created)")
    args = ap.parse_args()
    bank = read_bank(args.bank)
    if not bank["entries"]:
        sys.exit(f"{args.bank}: no entries to plot ({title_of(bank)}; see /sweep/failed)")
    os.makedirs(args.out, exist_ok=True)
    spectra_figure(bank, args.out)
    patch_figure(bank, args.out)
    print(f"wrote {args.out}/spectra.png, patch.png")


if __name__ == "__main__":
    main()
