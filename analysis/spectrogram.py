#!/usr/bin/env python3
"""Spectrogram of a clatter-synth render, with each sound source's share.

  spectrogram.py OUT.wav [-o PLOT.png] [--channel 0] [--fmax 20000] [--window-ms 20]
                 [--db-range 80] [--freq-scale log|linear]

Reads the mix OUT.wav and the stems `clatter-synth --stems` writes beside it (OUT.<name>.wav:
pan, modal, ground, ...) and draws, for one listener channel:
  top     the mix's spectrogram, dB SPL per frequency bin (re 20 uPa), up to --fmax;
  middle  (2+ stems) the dominant source of each time-frequency bin above the display floor;
  bottom  the short-time RMS level (dB SPL) of the mix and of each stem, with each source's
          energy share (% of the sum of the stems' energies) and its peak and RMS in Pa.
Why: to see which source makes which part of the sound, and how much of it, when a source model
changes. Default output OUT.spectrogram.png; prints per source peak, RMS and energy share %.
Float32 files are in pascals; PCM (--format pcm24, always --normalize) in full scale, dBFS.
Exit 2 on bad input: a missing or unreadable file, a stem whose rate, length, channel count or
sample format differs from the mix's. Needs numpy, scipy (io.wavfile), matplotlib.
"""
import argparse
import glob
import os
import re
import sys
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from scipy.io import wavfile  # noqa: E402

P_REF = 20e-6  # Pa


class BadInput(Exception):
    pass


def read_wav(path):
    """(rate, samples as float64 [frames, channels], is_pcm); PCM scaled to full scale +-1."""
    if not os.path.isfile(path):
        raise BadInput(f"{path}: no such file")
    try:
        with warnings.catch_warnings():  # libsndfile's PEAK chunk: "not understood, skipping"
            warnings.simplefilter("ignore", wavfile.WavFileWarning)
            rate, data = wavfile.read(path)
    except (ValueError, OSError, EOFError) as err:
        raise BadInput(f"{path}: not a readable WAV file: {err}") from None
    pcm = np.issubdtype(data.dtype, np.integer)
    x = data.astype(np.float64)
    if data.dtype == np.uint8:
        x = (x - 128.0) / 128.0
    elif pcm:  # scipy puts 24-bit samples in the top bits of an int32
        x /= 2.0 ** (8 * data.dtype.itemsize - 1)
    return rate, x.reshape(len(x), -1), pcm


def find_stems(mix_path):
    """{name: path} for every OUT.<name>.wav beside OUT.wav (name without dots)."""
    base = mix_path[:-4] if mix_path.lower().endswith(".wav") else mix_path
    pattern = re.compile(re.escape(os.path.basename(base)) + r"\.([^.]+)\.wav$", re.IGNORECASE)
    stems = {}
    for path in sorted(glob.glob(glob.escape(base) + ".*.wav")):
        m = pattern.match(os.path.basename(path))
        if m:
            stems[m.group(1)] = path
    return stems


def load(mix_path, channel):
    rate, mix, pcm = read_wav(mix_path)
    if not 0 <= channel < mix.shape[1]:
        raise BadInput(f"{mix_path}: --channel {channel}: the file has {mix.shape[1]} channel(s)")
    sources = {}
    for name, path in find_stems(mix_path).items():
        r, x, p = read_wav(path)
        for what, got, want in (("rate", r, rate), ("length", len(x), len(mix)),
                                ("channel count", x.shape[1], mix.shape[1]),
                                ("sample format", "PCM" if p else "float", "PCM" if pcm else "float")):
            if got != want:
                raise BadInput(f"{path}: {what} {got} differs from the mix's ({want}, {mix_path})")
        sources[name] = x[:, channel]
    return rate, mix[:, channel], sources, pcm


def frames(x, n, hop):
    """Frames of n samples centred on 0, hop, 2 hop, ... through the end (zero-padded), [count, n]."""
    count = 1 + int(np.ceil(len(x) / hop))
    padded = np.zeros((count - 1) * hop + n)
    padded[n // 2:n // 2 + len(x)] = x
    return np.lib.stride_tricks.sliding_window_view(padded, n)[::hop]


def power_spectrogram(x, n, hop):
    """Mean-square pressure per one-sided bin, [bins, frames]; bins sum to the frame's mean square."""
    w = np.hanning(n)
    spec = np.abs(np.fft.rfft(frames(x, n, hop) * w, axis=1)) ** 2 / (n * np.sum(w ** 2))
    spec[:, 1:(n + 1) // 2] *= 2
    return spec.T


def db(power, ref):
    return 10 * np.log10(np.maximum(power, 1e-30) / ref ** 2)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("wav", help="the mix written by clatter-synth -o OUT.wav [--stems]")
    ap.add_argument("-o", "--output", help="plot file (default OUT.spectrogram.png)")
    ap.add_argument("--channel", type=int, default=0, help="listener channel (default 0)")
    ap.add_argument("--fmax", type=float, default=20000, help="top of the frequency axis, Hz")
    ap.add_argument("--window-ms", type=float, default=20, help="analysis window, ms")
    ap.add_argument("--db-range", type=float, default=80, help="dB shown below the maximum")
    ap.add_argument("--freq-scale", choices=("log", "linear"), default="log")
    a = ap.parse_args()
    try:
        rate, mix, sources, pcm = load(a.wav, a.channel)
    except BadInput as err:
        print(f"spectrogram.py: {err}", file=sys.stderr)
        return 2
    unit, ref, dbu = ("FS", 1.0, "dBFS") if pcm else ("Pa", P_REF, "dB SPL")
    n = max(16, int(round(a.window_ms * 1e-3 * rate)))
    hop = max(1, n // 4)
    fmax = min(a.fmax, rate / 2)
    freqs = np.fft.rfftfreq(n, 1 / rate)
    keep = (freqs <= fmax) & ((freqs > 0) | (a.freq_scale == "linear"))
    p_mix = power_spectrogram(mix, n, hop)[keep]
    t_spec = np.arange(p_mix.shape[1]) * hop / rate

    # Energies and the text summary.
    energy = {k: float(np.sum(x ** 2)) for k, x in sources.items()}
    total = sum(energy.values())
    share = {k: (100 * e / total if total > 0 else float("nan")) for k, e in energy.items()}
    stats = {k: (np.max(np.abs(x)), np.sqrt(np.mean(x ** 2))) for k, x in [("mix", mix), *sources.items()]}
    print(f"{a.wav}: {rate} Hz, {len(mix) / rate:.3f} s, channel {a.channel}, "
          f"{len(sources)} stem(s), units {unit}")
    print(f"{'source':<12}{'peak ' + unit:>12}{'RMS ' + unit:>12}{'share %':>10}")
    for k, (peak, rms) in stats.items():
        print(f"{k:<12}{peak:12.4g}{rms:12.4g}" + (f"{share[k]:10.2f}" if k in share else f"{'-':>10}"))
    if sources:
        resid = np.max(np.abs(mix - sum(sources.values())))
        e_mix = float(np.sum(mix ** 2))
        print(f"mix energy / sum of stem energies: {e_mix / total if total > 0 else float('nan'):.4f}; "
              f"max |mix - sum of stems| = {resid:.3g} {unit}")

    # The figure.
    names = list(sources)
    colors = [plt.cm.tab10(i % 10) for i in range(len(names))]
    ratios = [3] + ([1.6] if len(names) > 1 else []) + [2]
    fig, axes = plt.subplots(len(ratios), 1, figsize=(11, 1.3 * sum(ratios) + 1.5), sharex=True,
                             gridspec_kw={"height_ratios": ratios}, squeeze=False)
    axes = axes[:, 0]
    level = db(p_mix, ref)
    top = float(level.max())
    mesh = axes[0].pcolormesh(t_spec, freqs[keep], level, shading="nearest", cmap="magma",
                              vmin=top - a.db_range, vmax=top, rasterized=True)
    fig.colorbar(mesh, ax=axes[0], pad=0.01, label=f"{dbu} per {rate / n:.0f} Hz bin")
    axes[0].set_title(f"{os.path.basename(a.wav)}, channel {a.channel}: mix")
    if len(names) > 1:
        ax = axes[1]
        p = np.stack([power_spectrogram(sources[k], n, hop)[keep] for k in names])
        dominant = np.ma.masked_where(level < top - a.db_range, np.argmax(p, axis=0))
        m = ax.pcolormesh(t_spec, freqs[keep], dominant, shading="nearest", vmin=-0.5,
                          vmax=len(names) - 0.5, cmap=ListedColormap(colors), rasterized=True)
        cb = fig.colorbar(m, ax=ax, pad=0.01, ticks=range(len(names)))
        cb.ax.set_yticklabels(names)
        ax.set_title("dominant source per bin (above the display floor)", fontsize=9)
    for ax in axes[:-1]:
        ax.set_yscale(a.freq_scale)
        ax.set_ylim(freqs[keep][0], fmax)
        ax.set_ylabel("frequency, Hz")

    ax = axes[-1]
    blocks = lambda x: db(np.mean(frames(x, n, hop) ** 2, axis=1), ref)  # noqa: E731
    label = lambda k: f"peak {stats[k][0]:.3g} {unit}, RMS {stats[k][1]:.3g} {unit}"  # noqa: E731
    lmix = blocks(mix)
    ax.plot(t_spec, lmix, color="0.6", lw=2.5, label="mix: " + label("mix"))
    for k, c in zip(names, colors):
        ax.plot(t_spec, blocks(sources[k]), color=c, lw=1,
                label=f"{k}: {share[k]:.1f} % of the energy, " + label(k))
    ax.set_ylim(lmix.max() - a.db_range, lmix.max() + 5)
    ax.set_ylabel(f"RMS level, {dbu}")
    ax.set_xlabel("time, s")
    ax.set_title(f"short-time RMS ({a.window_ms:g} ms window)", fontsize=9)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0, -0.22), ncol=2, frameon=False)
    ax.grid(alpha=0.3)
    fig.colorbar(mesh, ax=ax, pad=0.01).ax.set_visible(False)  # align with the panels above
    ax.set_xlim(0, len(mix) / rate)
    out = a.output or (a.wav[:-4] if a.wav.lower().endswith(".wav") else a.wav) + ".spectrogram.png"
    try:
        fig.savefig(out, dpi=110, bbox_inches="tight")
    except OSError as err:
        print(f"spectrogram.py: {out}: cannot write: {err.strerror or err}", file=sys.stderr)
        return 2
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
