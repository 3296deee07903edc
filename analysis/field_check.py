#!/usr/bin/env python3
"""Checks clatter-bank `field` outputs against the exact monopole field, computed here
independently with numpy from eq. (6) of Chadwick, Zheng & James 2012:

    p(r, t) = rho * psi(t - r/c; h) / (4 pi r)

and, when given several files (e.g. written on 1, 2 and 3 ranks), that their fields are
bit-identical. Usage: field_check.py FILE [FILE...]; exit status 0 when every check passes.
"""
import sys

import h5py
import numpy as np


def psi(t, h):
    a = np.abs(t) / h
    y = 1.0 - a
    inner = (-15 * y**3 + 18 * y**2 + 9 * y + 2) / 18
    outer = (5 * (1 + y) ** 3 - 3 * (1 + y) ** 2) / 18
    return np.where(a <= 1, inner, np.where(a <= 2, outer, 0.0))


def check(path):
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == "clatter-field", f"{path}: format {f.attrs['format']!r}"
        assert f.attrs["format_version"] == 2, f"{path}: format_version {f.attrs['format_version']}"
        p = f["field/p"]
        assert p.attrs["units"] == "Pa" and p.dtype == np.float32 and p.ndim == 3, f"{path}: /field/p"
        x = f["grid/x_m"][...]
        assert f["grid/x_m"].attrs["units"] == "m"
        n = p.shape[0]
        assert p.shape == (n, n, n) and x.shape == (n,)
        dx = f["grid"].attrs["dx_m"]
        assert np.allclose(x, (np.arange(n) + 0.5 - 0.5 * n) * dx, rtol=0, atol=1e-15)
        t, h, c, rho = (f["field"].attrs[k] for k in ("t_s", "h_s", "c_m_s", "rho_kg_m3"))
        p = p[...]
        assert "config_toml" in f["provenance"].attrs
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    r = np.sqrt(X**2 + Y**2 + Z**2)
    ref = rho * psi(t - r / c, h) / (4 * np.pi * r)
    scale = np.abs(ref).max()
    err = np.abs(p - ref).max() / scale
    # float32 storage: relative rounding 2^-24 of each value
    assert err < 1e-6, f"{path}: max error {err:.3g} of the peak"
    print(f"{path}: {n}^3 cells, peak {scale:.4g} Pa, max |p - exact| / peak = {err:.2e}")
    return p


def main(paths):
    if not paths:
        print(__doc__)
        return 2
    fields = [check(p) for p in paths]
    for path, field in zip(paths[1:], fields[1:]):
        assert np.array_equal(field.view(np.uint32), fields[0].view(np.uint32)), f"{path} differs from {paths[0]}"
    if len(paths) > 1:
        print(f"all {len(paths)} files bit-identical")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
