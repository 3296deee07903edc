#!/usr/bin/env python3
"""Bad copies of a good ground bank (ground_checks.sh's a.h5: steel and soil, 2 elevations x 3
etas), one defect each, for the reader's checks (docs/bank-format.md "Ground bank"; the
bad_ground_bank_* tests read each with `clatter-bank info`). Usage: make_bad_ground_banks.py
GOOD_BANK OUTDIR"""
import os
import shutil
import sys

import h5py
import numpy as np

good, out = sys.argv[1:3]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)


def edit(name):
    path = os.path.join(out, name + ".h5")
    shutil.copy(good, path)
    return h5py.File(path, "r+")


def replace(f, name, values):
    units = f[name].attrs["units"]
    del f[name]
    f[name] = values
    f[name].attrs["units"] = units


steel, soil = "materials/steel", "materials/soil"
with edit("descending") as f:  # elevations 90, 45: not ascending
    f[steel + "/elevation_rad"][...] = f[steel + "/elevation_rad"][...][::-1]
with edit("zero_dt") as f:
    f[steel + "/dt_hat"][1] = 0.0
with edit("nan_pi") as f:
    f[steel + "/pi"][5] = np.nan
with edit("short_offsets") as f:  # one offset fewer than there are series
    replace(f, steel + "/series_offset", f[steel + "/series_offset"][:-1])
with edit("gap") as f:  # the second series starts one sample late
    f[steel + "/series_offset"][1] += 1
with edit("speed") as f:  # a shear speed the moduli do not give
    f[soil].attrs["shear_speed_m_s"] = f[soil].attrs["shear_speed_m_s"] * 1.01
with edit("poisson") as f:
    f[soil].attrs["poisson"] = 0.5
with edit("no_air") as f:
    del f["air"].attrs["c0_m_s"]
with edit("nan_tail") as f:
    f[steel + "/tail"][2, 3] = np.nan
with edit("version1") as f:  # a bank of version 1: no tails, Pi held after each series
    f.attrs["format_version"] = np.int32(1)
    for m in (steel, soil):
        del f[m + "/tail"]
print("bad ground banks in", out, ":", " ".join(sorted(os.listdir(out))))
