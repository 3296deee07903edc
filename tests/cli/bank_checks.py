#!/usr/bin/env python3
"""Command-line checks of a PAN bank (argv: clatter-bank binary, bank file, scratch folder).

1. probe in each of the 8 octants equals +- the positive-octant probe exactly, with the signs of
   eqs. (16)-(21); 2. probe --scale beta equals eq. (10) applied to the unscaled probe, to float
   round-off; 3. bad banks and bad requests exit 2 with one clear line and print no CSV.
"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

binary, bank, scratch = sys.argv[1:4]
os.makedirs(scratch, exist_ok=True)
failures = []
passed = 0

PARITY = {1: (-1, 1, 1), 2: (1, -1, 1), 3: (1, 1, -1), 4: (1, -1, -1), 5: (-1, 1, -1), 6: (-1, -1, 1)}


def probe(*args, bank_path=bank):
    r = subprocess.run([binary, "probe", bank_path, *args], capture_output=True, text=True)
    return r


def csv(r):
    rows = [line.split(",") for line in r.stdout.strip().splitlines()[1:]]
    return np.array([[float(a), float(b)] for a, b in rows])


def check(name, ok, detail=""):
    global passed
    if ok:
        passed += 1
    else:
        failures.append(f"{name}: {detail}")


with h5py.File(bank) as f:
    b, c = f["proxies/b_m"][-1], f["proxies/c_m"][-1]
proxy = f"{b!r},{c!r}"

# 1. octant symmetry, every field
x = np.array([0.71, 0.43, 0.52])
for field in (1, 3, 4, 5, 6):  # field 2 is left out of the test bank on purpose
    base = csv(probe("--proxy", proxy, "--field", str(field), "--point", ",".join(map(repr, x))))
    for m in range(1, 8):
        flip = np.array([-1 if m & (1 << a) else 1 for a in range(3)])
        sign = np.prod([PARITY[field][a] for a in range(3) if flip[a] < 0])
        other = csv(probe("--proxy", proxy, "--field", str(field), "--point", ",".join(map(repr, x * flip))))
        check(f"symmetry field {field} octant {m}", np.array_equal(other[:, 1], sign * base[:, 1]),
              f"max diff {np.abs(other[:, 1] - sign * base[:, 1]).max()}")

# 2. scaling law: P(x, t) = beta^s p(x / beta, t / beta)
beta = 0.4
for field in (1, 6):
    y = x / beta
    scaled = csv(probe("--proxy", proxy, "--field", str(field), "--point", ",".join(map(repr, x)), "--scale", str(beta)))
    plain = csv(probe("--proxy", proxy, "--field", str(field), "--point", ",".join(map(repr, y))))
    power = beta if field <= 3 else beta * beta
    ok_t = np.allclose(scaled[:, 0], beta * plain[:, 0], rtol=1e-8, atol=1e-15)
    ok_p = np.allclose(scaled[:, 1], power * plain[:, 1], rtol=1e-7, atol=1e-12 * np.abs(plain[:, 1]).max())
    check(f"scaling field {field}", ok_t and ok_p, "times or pressures differ from eq. (10)")


# 3. bad input: exit 2, one line naming the problem, no CSV
def bad(name, expect, *args, bank_path=bank):
    r = probe(*args, bank_path=bank_path)
    lines = [l for l in r.stderr.splitlines() if l.startswith("clatter-bank:")]
    check(f"bad input: {name}", r.returncode == 2 and len(lines) == 1 and expect in lines[0] and "t_s,p_Pa" not in r.stdout,
          f"rc {r.returncode}, stderr {r.stderr.strip()!r}")


good = ["--proxy", proxy, "--field", "1", "--point", "1,0.5,0.5"]
version = os.path.join(scratch, "version.h5")
shutil.copy(bank, version)
with h5py.File(version, "r+") as f:
    f.attrs["format_version"] = np.int32(99)
bad("schema version", "version 99", *good, bank_path=version)

truncated = os.path.join(scratch, "truncated.h5")
with open(bank, "rb") as src, open(truncated, "wb") as dst:
    dst.write(src.read(os.path.getsize(bank) // 2))
bad("truncated file", "truncated.h5", *good, bank_path=truncated)

corrupt = os.path.join(scratch, "corrupt.h5")
shutil.copy(bank, corrupt)
with h5py.File(bank) as f:
    offset = f["coefficients/values"].id.get_chunk_info(0).byte_offset  # chunked: first chunk's bytes
with open(corrupt, "r+b") as g:  # flip bytes inside the first chunk of the deflated values
    g.seek(offset + 64)
    chunk = bytearray(g.read(16))
    g.seek(offset + 64)
    g.write(bytes(v ^ 0xFF for v in chunk))
bad("corrupted data (checksum)", "corrupt", *good, bank_path=corrupt)

bad("proxy not in bank", "no proxy", "--proxy", "0.123,0.1", "--field", "1", "--point", "1,0.5,0.5")
bad("field not in bank", "field", "--proxy", proxy, "--field", "2", "--point", "1,0.5,0.5")
bad("field out of range", "fields 1-6", "--proxy", proxy, "--field", "7", "--point", "1,0.5,0.5")
bad("point inside the bounding sphere", "bounding sphere", "--proxy", proxy, "--field", "1", "--point", "0.2,0.1,0.1")

for f in failures:
    print("FAIL:", f)
print(f"{passed} passed, {len(failures)} failed")
sys.exit(1 if failures else 0)
