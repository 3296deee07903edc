#!/usr/bin/env python3
"""Bad copies of a good PAN bank, one defect each, for the bad-input tests (docs/validation.md,
"Bad-input catalogue"). Usage: make_bad_banks.py GOOD_BANK OUTDIR"""
import os
import shutil
import sys

import h5py
import numpy as np

good, out = sys.argv[1:3]
shutil.rmtree(out, ignore_errors=True)
os.makedirs(out)


def copy(name):
    path = os.path.join(out, name)
    shutil.copy(good, path)
    return path


open(os.path.join(out, "not_hdf5.h5"), "w").write("format = clatter-pan-bank\n")
with open(good, "rb") as src, open(os.path.join(out, "truncated.h5"), "wb") as dst:
    dst.write(src.read(os.path.getsize(good) // 2))
with h5py.File(os.path.join(out, "no_format.h5"), "w") as f:
    f["data"] = np.zeros(3)
with h5py.File(copy("wrong_format.h5"), "r+") as f:
    f.attrs["format"] = "clatter-fdtd-raw"
with h5py.File(copy("wrong_version.h5"), "r+") as f:
    f.attrs["format_version"] = np.int32(1)
with h5py.File(copy("wrong_shape.h5"), "r+") as f:  # one C fewer than there are B
    c = f["proxies/c_m"]
    units = c.attrs["units"]
    values = c[:-1]
    del f["proxies/c_m"]
    f["proxies/c_m"] = values
    f["proxies/c_m"].attrs["units"] = units
with h5py.File(copy("index_out_of_range.h5"), "r+") as f:  # first coefficient index beyond the length T
    d = f["coefficients/index_delta"]
    d[0] = np.uint16(f["bank"].attrs["length"])
path = copy("corrupt.h5")
with h5py.File(path) as f:  # flip bytes inside the first chunk of the deflated, checksummed values
    offset = f["coefficients/values"].id.get_chunk_info(0).byte_offset
with open(path, "r+b") as g:
    g.seek(offset + 64)
    chunk = bytearray(g.read(16))
    g.seek(offset + 64)
    g.write(bytes(v ^ 0xFF for v in chunk))
print("bad banks in", out, ":", " ".join(sorted(os.listdir(out))))
