#!/usr/bin/env python3
"""A ground bank read with h5py alone (docs/bank-format.md "Ground bank"), as built by
ground_checks.sh from tests/cli/configs/ground_tiny.toml (steel and soil, elevations 45 and 90
deg, eta 0.05, 0.1, 0.2, 8 samples per eta):
- layout: format and version, /air, one group per material in config order (attribute index), the
  moduli and the wave speeds they imply, every dataset's type, shape and units, checksummed and
  compressed, contiguous series covering `pi` exactly, dt_hat = eta / 8, the tails' leading
  coefficient (1 - nu) / (2 pi);
- physics, for the overhead listener (elevation 90 deg), every material and eta, with
  p = dPi/dt_hat (finite differences of the stored Pi):
  * the pulse arrives with the direct sound: |p| peaks within 3 eta of t_hat = M = c_s / c0;
  * a rarefaction first: p is negative at its first extremum (the load pushes the surface away
    from the air, so the air above it is first pulled, not pushed);
  * the tail continues the series: Pi at the window's end minus the tail's closed form there is
    below 1e-3 of the peak |p| times the pulse width eta (Pi's end is not 0: the static field's
    share decays as t_hat^-2 after it, docs/ground.md);
  * the window holds the start of the pulse: Pi at its start is below 1e-3 of max |Pi|;
  * the peak scales as eta^-2 (the direct sound is a kink of phi smoothed over eta): peak * eta^2
    agrees over the etas to 25 %.
Usage: ground_checks.py BANK"""
import math
import sys

import h5py
import numpy as np

failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def dataset(g, name, dtype, shape, units):
    d = g[name]
    check(d.dtype == dtype and d.shape == shape and d.attrs["units"] == units,
          f"{d.name}: {d.dtype} {d.shape} '{d.attrs['units']}' (expected {dtype} {shape} '{units}')")
    check(d.fletcher32 and d.compression == "gzip" and d.shuffle, f"{d.name}: checksummed, shuffled and deflated")
    return d[...]


def first_extremum(p):
    """The first local extremum of p among the samples above 30 % of its peak (skips the tails)."""
    i = int(np.argmax(np.abs(p) > 0.3 * np.abs(p).max()))
    while i + 1 < len(p) and abs(p[i + 1]) >= abs(p[i]):
        i += 1
    return i


def check_layout(f):
    check(f.attrs["format"] == "clatter-ground-bank" and f.attrs["format_version"] == 2, "format clatter-ground-bank v2")
    check(math.isclose(f["air"].attrs["c0_m_s"], 343.2) and math.isclose(f["air"].attrs["rho0_kg_m3"], 1.2041),
          "/air: c0 = 343.2 m/s, rho0 = 1.2041 kg/m^3")
    names = sorted(f["materials"], key=lambda n: f["materials"][n].attrs["index"])
    check(names == ["steel", "soil"], f"materials in config order: {names}")
    check("sweep" in f and "provenance" in f and "config_toml" in f["provenance"].attrs, "/sweep and /provenance")
    return names


def read_material(g):
    a = g.attrs
    mu = a["youngs_pa"] / (2 * (1 + a["poisson"]))
    cs = math.sqrt(mu / a["rho_kg_m3"])
    cp = cs * math.sqrt(2 * (1 - a["poisson"]) / (1 - 2 * a["poisson"]))
    check(math.isclose(a["shear_speed_m_s"], cs, rel_tol=1e-12) and math.isclose(a["pressure_speed_m_s"], cp, rel_tol=1e-12),
          f"{g.name}: c_s = {cs:.2f}, c_p = {cp:.2f} m/s from E, nu, rho")
    check(len(a["source"]) > 0 and 0 < a["poisson"] < 0.5, f"{g.name}: a source and nu in (0, 0.5)")
    el = dataset(g, "elevation_rad", np.float64, (2,), "rad")
    eta = dataset(g, "eta", np.float64, (3,), "1")
    check(np.allclose(el, np.radians([45, 90]), rtol=1e-15) and np.allclose(eta, [0.05, 0.1, 0.2], rtol=1e-12),
          f"{g.name}: elevations {np.degrees(el)} deg, eta {eta}")
    n = len(el) * len(eta)
    off = dataset(g, "series_offset", np.int64, (n,), "1")
    length = dataset(g, "series_length", np.int64, (n,), "1")
    t0 = dataset(g, "t_hat_start", np.float64, (n,), "1")
    dt = dataset(g, "dt_hat", np.float64, (n,), "1")
    pi = dataset(g, "pi", np.float64, (int(length.sum()),), "1")
    check(off[0] == 0 and np.array_equal(off[1:], np.cumsum(length)[:-1]) and np.all(length >= 2),
          f"{g.name}: {n} contiguous series of {length.min()}-{length.max()} samples cover pi ({len(pi)})")
    check(np.allclose(dt, np.tile(eta / 8, len(el)), rtol=1e-15) and np.all(np.isfinite(pi)), f"{g.name}: dt_hat = eta / 8")
    tail = dataset(g, "tail", np.float64, (n, 9), "1")
    static = (1 - a["poisson"]) / (2 * math.pi)
    check(np.allclose(tail[:, 0], static, rtol=1e-12) and np.all(np.isfinite(tail)),
          f"{g.name}: tail[:, 0] = (1 - nu) / (2 pi) = {static:.6f}: the static field's t_hat^-2")
    series = [(t0[k], dt[k], pi[off[k]:off[k] + length[k]], tail[k]) for k in range(n)]
    return cs, el, eta, series


def tail_pi(coefficients, t, eta):
    """Pi past a series (model/ground_bank.hpp): sum_m c[m - 2] (2 Re (t + i eta)^-m - Re (t + 2 i eta)^-m)."""
    m = np.arange(2, 2 + len(coefficients))
    return float(np.sum(coefficients * (2 * np.real((t + 1j * eta) ** -m) - np.real((t + 2j * eta) ** -m))))


def check_overhead(name, mach, eta, row):
    peaks = []
    for e, (t0, dt, pi, tail) in zip(eta, row):
        p = np.diff(pi) / dt
        t = t0 + dt * (np.arange(len(p)) + 0.5)
        k = int(np.argmax(np.abs(p)))
        i = first_extremum(p)
        # Pi's end is not 0: the static field's share decays as t_hat^-2 after it (the tail).
        dc = (pi[-1] - tail_pi(tail, t0 + dt * (len(pi) - 1), e)) / (np.abs(p).max() * e)
        ends = abs(pi[0]) / np.abs(pi).max()
        peaks.append(np.abs(p).max() * e * e)
        check(abs(t[k] - mach) < 3 * e, f"{name} 90 deg eta {e:.3g}: |p| peaks at t_hat {t[k]:.3f}, M = {mach:.3f}")
        check(p[i] < 0, f"{name} 90 deg eta {e:.3g}: first extremum p = {p[i]:.4g} at t_hat {t[i]:.3f} (peak {p[k]:.4g}): "
                        "a rarefaction first")
        check(abs(dc) < 1e-3, f"{name} 90 deg eta {e:.3g}: (Pi_end - tail(t_end)) / (max|p| eta) = {dc:.2e}: the tail continues the series")
        check(ends < 1e-3, f"{name} 90 deg eta {e:.3g}: |Pi| at the window's start is {ends:.1e} of its maximum")
    spread = max(peaks) / min(peaks) - 1
    check(spread < 0.25, f"{name} 90 deg: max|p| eta^2 = {', '.join(f'{x:.4g}' for x in peaks)} (spread {spread:.1%})")


def main(path):
    with h5py.File(path, "r") as f:
        c0 = f["air"].attrs["c0_m_s"]
        for name in check_layout(f):
            cs, el, eta, series = read_material(f["materials"][name])
            overhead = int(np.argmin(abs(el - math.pi / 2)))
            check_overhead(name, cs / c0, eta, series[overhead * len(eta):(overhead + 1) * len(eta)])
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
