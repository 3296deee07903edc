#!/usr/bin/env python3
"""analysis/table1_meshes.py (docs/pan.md "Table 1"): every mesh closed and outward (each edge in
exactly two triangles, once each way; positive volume), volumes against closed forms (the die
16^3 mm^3; the coin the 96-gon prism; the cup the difference of its two 96-gon prisms plus less
than the whole handle torus, 2 pi^2 R r^2; the rounded die between the sphere and the cube), and
`clatter-bank plan --kind pan-object` solving the die, rounded die and coin in one octant and the
plate and mug in eight. Usage: table1_meshes_check.py PYTHON SCRIPT BIN_DIR WORKDIR"""
import math, os, re, shutil, subprocess, sys
from collections import Counter

python, script, bin_dir, work = sys.argv[1:5]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
subprocess.run([python, script, work], check=True)
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def read(path):
    v, f = [], []
    for line in open(path):
        if line.startswith("v "):
            v.append(tuple(map(float, line.split()[1:4])))
        elif line.startswith("f "):
            f.append(tuple(int(x) - 1 for x in line.split()[1:4]))
    return v, f


def volume(v, f):
    s = 0.0
    for a, b, c in f:
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = v[a], v[b], v[c]
        s += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)
    return s / 6


def prism(r, h, n=96):
    return 0.5 * n * r * r * math.sin(2 * math.pi / n) * h


names = ["die", "rounded-die", "coin", "plate", "mug"]
vols = {}
for name in names:
    v, f = read(os.path.join(work, name + ".obj"))
    edges = Counter((a, b) for t in f for a, b in ((t[0], t[1]), (t[1], t[2]), (t[2], t[0])))
    closed = all(n == 1 and edges.get((b, a)) == 1 for (a, b), n in edges.items())
    # The mug is two closed components (cup, handle): still each edge once each way.
    check(closed, f"{name}: closed and consistently oriented ({len(f)} triangles)")
    vols[name] = volume(v, f)
    check(vols[name] > 0, f"{name}: outward (volume {vols[name] * 1e6:.4f} cm^3)")

check(abs(vols["die"] - 0.016 ** 3) < 1e-9 * 0.016 ** 3, f"die: {vols['die']:.6e} m^3 = 0.016^3")
check(4 / 3 * math.pi * 0.008 ** 3 < vols["rounded-die"] < 0.016 ** 3, "rounded die: between its inscribed ball and the cube")
check(abs(vols["coin"] - prism(0.01213, 0.00175)) < 1e-9 * vols["coin"], "coin: the 96-gon prism")
cup = prism(0.04, 0.095) - prism(0.036, 0.089)
torus = 2 * math.pi ** 2 * 0.022 * 0.005 ** 2
check(cup < vols["mug"] < cup + torus, f"mug: the cup {cup * 1e6:.3f} cm^3 plus at most the torus {torus * 1e6:.3f} cm^3 (the sum counts the overlap twice)")

env = dict(os.environ)
r = subprocess.run([f"{bin_dir}/clatter-bank", "plan", "--kind", "pan-object", "--rate", "1e8", "--set=grid.dx_m=0.04",
                    "--set=time.dt_s=4.1666666666666665e-05", "--set=pulse.h_s=0.0005",
                    "--set=objects.meshes=[" + ", ".join(f'"{work}/{n}.obj"' for n in names) + "]"],
                   capture_output=True, text=True, env=env)
# "(8 octants)" or "(8 octants, N heard: mirror planes)"; nothing for a one-octant entry.
tasks = re.findall(r"o(\d{3})-f1  mesh '[^']*/([a-z-]+)\.obj'  field 1 .*?(\(8 octants(?:, (\d) heard: mirror planes)?\))?$",
                   r.stdout, re.M)
octants = {name: (8, int(heard or 8)) if eight else 1 for _, name, eight, heard in tasks}
check(r.returncode == 0, f"plan --kind pan-object of the five exits 0 ({r.stderr.strip()[-300:]})")
# The plate is mirror-symmetric in x and y (2 of 8 octants heard), the mug across its handle (4).
check(octants == {"die": 1, "rounded-die": 1, "coin": 1, "plate": (8, 2), "mug": (8, 4)}, f"octants per mesh: {octants}")

print("table1 meshes checks: " + ("all passed" if not failures else f"{len(failures)} failed"))
sys.exit(1 if failures else 0)
