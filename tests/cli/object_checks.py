#!/usr/bin/env python3
"""`clatter-bank object` and the synthesizer's own-model rule end to end (docs/modal.md "Objects with
their own models", docs/synth.md):
- a glass bar given as an OBJ mesh builds into an object bank whose lowest mode is the bar's first
  free-free bending mode: Euler-Bernoulli's (4.7300^2 / 2 pi L^2) sqrt(E I / rho A) with the
  Timoshenko correction of a bar this slender under 2 %, so within 4 %;
- a scene of that bar rings with its own model when the bank is given (-O) and its base frequency
  is below --proxy-above-hz; without the bank it rings with its proxy and the coverage report says it
  should have its own model; with the threshold below its base frequency the proxy voices it even
  with the bank; struck at the middle of its underside by an impulse J, its own model takes the
  energy Euler-Bernoulli gives its first bending mode, J^2 W(L/2)^2 / 2m (W the free-free shape
  normalized to mean square 1, |W(L/2)| = 1.2172), times the half-sine contact's spectral factor
  (<= 1, above 0.85 for a contact shorter than a third of the mode's period): between 0.85 and 1.01
  of it;
- the scene itself, given to `clatter-bank object` (objects.scene), makes the bank of exactly its
  objects below the threshold, which the synthesizer finds by key;
- bad meshes (open, inverted, a degenerate triangle, self-intersecting, in millimetres) exit 2
  naming the file and the reason, and leave no bank.
Usage: object_checks.py CLATTER_BANK CLATTER_SYNTH DEMO_MODAL_BANK SCRATCH"""
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, run, start  # noqa: E402

bank, synth, demo_modal, scratch = sys.argv[1:5]
start(scratch)

L, W, H = 0.20, 0.02, 0.01  # m: a glass bar, bending about its thin axis first
E, NU, RHO = 6.2e10, 0.20, 2600.0  # configs/materials.toml [glass]


def box(size, n):
    """The box [0, sx] x [0, sy] x [0, sz], each face n_i x n_j squares of two triangles, outward."""
    verts, index, faces = [], {}, []

    def vertex(i, j, k, steps):
        key = (i, j, k)
        if key not in index:
            index[key] = len(verts)
            verts.append(tuple(size[d] * key[d] / steps[d] for d in range(3)))
        return index[key]

    for axis in range(3):
        u, v = (axis + 1) % 3, (axis + 2) % 3
        for side in (0, 1):
            for a in range(n[u]):
                for b in range(n[v]):
                    quad = []
                    for da, db in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0, 0, 0]
                        p[axis] = side * n[axis]
                        p[u], p[v] = a + da, b + db
                        quad.append(vertex(*p, n))
                    if side == 0:
                        quad.reverse()
                    faces += [(quad[0], quad[1], quad[2]), (quad[0], quad[2], quad[3])]
    return verts, faces


def write_obj(path, verts, faces, scale=1.0):
    with open(path, "w") as f:
        for p in verts:
            f.write("v %.17g %.17g %.17g\n" % tuple(scale * c for c in p))
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))


verts, faces = box((L, W, H), (20, 2, 1))
write_obj("bar.obj", verts, faces)
with open("bar.toml", "w") as f:
    f.write('[objects]\nmeshes = ["bar.obj"]\nmaterials = ["glass"]\n[modes]\nf_max_hz = 6000\n')
r = run(bank, "object", "-c", "bar.toml", "-o", "bar.h5", "--progress-interval", "0")
check(r.returncode == 0 and os.path.exists("bar.h5"), f"clatter-bank object builds the bar (exit {r.returncode}) "
      f"{r.stderr.strip()[-400:]}")
info = run(bank, "info", "bar.h5", "--entry", "0")
rows = [l.split(",") for l in info.stdout.splitlines()[2:] if l and l[0].isdigit()]
f1 = float(rows[0][1]) if rows else float("nan")
inertia = W * H**3 / 12
f_eb = 4.7300**2 / (2 * math.pi * L**2) * math.sqrt(E * inertia / (RHO * W * H))
check(abs(f1 / f_eb - 1) < 0.04, f"the bar's lowest mode {f1:.2f} Hz is its first bending mode, Euler-Bernoulli "
      f"{f_eb:.2f} Hz (ratio {f1 / f_eb:.4f})")
key = re.search(r"entry 0: (\S+) from", info.stdout)

scene = {
    "format": "clatter-scene", "format_version": 1, "ground_material": "concrete",
    "materials": {"glass": {"youngs_modulus_pa": E, "poisson_ratio": NU, "density_kg_m3": RHO,
                            "rayleigh_alpha_1_s": 1.0, "rayleigh_beta_s": 1e-7},
                  "concrete": {"youngs_modulus_pa": 3e10, "poisson_ratio": 0.2}},
    "objects": [{"id": 1, "mesh": "bar.obj", "density_kg_m3": RHO, "material": "glass"}],
    "events": [{"t_s": 0.01, "a": 1, "b": "ground", "point_m": [0.0, 0.0, 0.0], "impulse_n_s": [0, 0, 0.01],
                "normal_speed_m_s": 1.0, "pose_a": {"position_m": [0, 0, H / 2], "orientation_wxyz": [1, 0, 0, 0]}}],
    "listeners": [{"position_m": [0.3, 1.0, 0.5]}], "duration_s": 0.3}
with open("bar.json", "w") as f:
    json.dump(scene, f)


def render(*options):
    r = run(synth, "-i", "bar.json", "-o", "bar.wav", *options)
    own = re.search(r"own models \(objects below ([0-9.e+]+) Hz.*?\): (\d+) objects ring with their own model from an "
                    r"object bank, (\d+) below it ring with their proxy", r.stdout)
    energy = re.search(r"energy: ([0-9.e+-]+) J into", r.stdout)
    if r.returncode != 0 or not own or not energy:
        check(False, f"clatter-synth renders the bar with {options}: exit {r.returncode} {r.stderr.strip()[-300:]}")
        return None
    return int(own.group(2)), int(own.group(3)), float(energy.group(1)), r.stdout


with_own = render("-O", "bar.h5", "-m", demo_modal)
without = render("-m", demo_modal)
above = render("-O", "bar.h5", "-m", demo_modal, "--proxy-above-hz", f"{0.5 * f1:.6g}")
if with_own and without and above:
    check(with_own[:2] == (1, 0), f"with the object bank the bar rings with its own model ({with_own[0]} own, "
          f"{with_own[1]} wanting one)")
    check(without[:2] == (0, 1) and "should ring with its own model, but no object bank (-O) given" in without[3],
          "without it the bar rings with its proxy, and the coverage report says it should have its own model")
    check(above[:2] == (0, 0), f"with --proxy-above-hz below its base frequency the proxy voices it ({above[:2]})")
    bl = 4.730040744862704
    sigma = (math.cosh(bl) - math.cos(bl)) / (math.sinh(bl) - math.sin(bl))
    w_mid = abs(math.cosh(bl / 2) + math.cos(bl / 2) - sigma * (math.sinh(bl / 2) + math.sin(bl / 2)))
    impulse, mass = 0.01, RHO * L * W * H
    e_beam = impulse**2 * w_mid**2 / (2 * mass)
    ratio = with_own[2] / e_beam
    check(0.85 < ratio <= 1.01, f"struck at its middle, the own model takes {with_own[2]:.4g} J, {ratio:.3f} of Euler-Bernoulli's "
          f"impulsive {e_beam:.4g} J for the first bending mode (the proxy of the near-sphere demo bank: {without[2]:.3g} J)")
only_objects = render("-O", "bar.h5")
check(only_objects is not None and only_objects[:2] == (1, 0), "an object bank alone (no -m) voices the object it holds")

# The key is the point here, not the modes: the band to 2 kHz holds the first bending mode alone
# (half the check's time went to this second bank at 6 kHz).
with open("scene.toml", "w") as f:
    f.write('[objects]\nscene = "bar.json"\n[modes]\nf_max_hz = 2000\n')
r = run(bank, "object", "-c", "scene.toml", "-o", "scene.h5", "--progress-interval", "0")
listed = run(bank, "info", "scene.h5", "--entry", "0")
check(r.returncode == 0 and key is not None and key.group(1) in listed.stdout,
      f"the scene makes the bank of its objects below the threshold, keyed as the synthesizer finds them (exit "
      f"{r.returncode}) {r.stderr.strip()[-300:]}")
r = run(bank, "object", "-c", "scene.toml", "--set", "objects.proxy_above_hz=10", "-o", "none.h5")
check(r.returncode == 2 and "below objects.proxy_above_hz = 10 Hz" in r.stderr and not os.path.exists("none.h5"),
      f"a scene with no object below the threshold is refused (exit {r.returncode}) {r.stderr.strip()[-200:]}")

# Bad meshes: each is refused with its reason, naming the file, and leaves no bank.
small_v, small_f = box((0.05, 0.04, 0.03), (2, 2, 2))
bad = {
    "open": (small_v, small_f[:-1], "not closed"),
    "inverted": (small_v, [(a, c, b) for a, b, c in small_f], "inward"),
    "millimetres": ([tuple(1000 * c for c in p) for p in small_v], small_f, "millimetres"),
}
# A degenerate triangle: a vertex moved onto its neighbours' line, so one face has zero area.
deg_v = list(small_v)
for t in small_f:
    a, b, c = (deg_v[i] for i in t)
    deg_v[t[2]] = tuple((a[d] + b[d]) / 2 for d in range(3))
    break
bad["degenerate"] = (deg_v, small_f, "degenerate")
# Two boxes that overlap, as one mesh: every edge closed and oriented, but the surface crosses itself.
other_v = [(p[0] + 0.02, p[1] + 0.01, p[2] + 0.01) for p in small_v]
bad["self-intersecting"] = (small_v + other_v, small_f + [tuple(i + len(small_v) for i in t) for t in small_f],
                            "intersect")
for name, (v, f, reason) in bad.items():
    write_obj(f"{name}.obj", v, f)
    with open(f"{name}.toml", "w") as out:
        out.write(f'[objects]\nmeshes = ["{name}.obj"]\nmaterials = ["glass"]\n')
    r = run(bank, "object", "-c", f"{name}.toml", "-o", f"{name}.h5")
    check(r.returncode == 2 and f"{name}.obj" in r.stderr and reason in r.stderr and not os.path.exists(f"{name}.h5"),
          f"a {name} mesh: exit 2 naming the file and '{reason}', no bank (exit {r.returncode}: {r.stderr.strip()[-250:]})")
finish("object checks")
