#!/usr/bin/env python3
"""clatter-synth end to end (docs/synth.md), on the demo scene and a PAN bank:
- linearity: a scene with two events renders to the sum of the scenes with each alone;
- fracture debris: an object created at t0 is silent before t0 (its earlier event is skipped);
- the James-lab impulse text format gives the same sound as the equivalent native scene;
- an object given by a closed mesh sounds as one given by the mesh's closed-form mass properties
  (contact times given), and with Hertz times its contacts come from the mesh;
- bad input: exit 2, one error line naming the field, and no output file.
Usage: synth_checks.py CLATTER_SYNTH BANK DEMO_SCENE SCRATCH"""
import copy, json, math, os, shutil, subprocess, sys
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from synth_wav import wav  # noqa: E402

synth, bank, demo_path, scratch = sys.argv[1:5]
shutil.rmtree(scratch, ignore_errors=True)
os.makedirs(scratch)
os.chdir(scratch)
demo = json.load(open(demo_path))
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def run(scene, out, extra=()):
    path = out + ".json"
    json.dump(scene, open(path, "w"))
    r = subprocess.run([synth, "-i", path, "-b", bank, "-o", out + ".wav", *extra], capture_output=True, text=True)
    return r, path


def render(scene, name):
    r, _ = run(scene, name)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit(f"{name}: exit {r.returncode}")
    return wav(name + ".wav")


# Linearity: event 0 of the demo and a weaker hit on the same object 1.3 ms later (they overlap).
second = copy.deepcopy(demo["events"][0])
second["t_s"] += 0.0013
second["impulse_n_s"] = [0.7 * c for c in second["impulse_n_s"]]
base = copy.deepcopy(demo)
base["events"] = [demo["events"][0]]
one = render(base, "one")
base["events"] = [second]
two = render(base, "two")
base["events"] = [demo["events"][0], second]
both = render(base, "both")
peak = np.abs(both).max()
err = np.abs(both - (one + two)).max() / peak
overlap = np.abs(one * two).max() > 0
check(peak > 0 and overlap and err < 1e-6, f"linearity: two impulses = the sum of each alone, max deviation {err:.2e} of the peak (float32 storage)")

# Debris: object 5 exists from 0.5 s; an event at 0.3 s is skipped, one at 0.6 s sounds.
deb = copy.deepcopy(demo)
early = copy.deepcopy([e for e in demo["events"] if e["a"] == 5][0])
early["t_s"] = 0.3
late = copy.deepcopy(early)
late["t_s"] = 0.6
deb["events"] = [early, late]
d = render(deb, "debris")
rate = 44100
first = np.nonzero(np.abs(d).max(axis=1))[0]
check(len(first) > 0 and first[0] / rate >= 0.6, f"debris created at 0.5 s: silent before its first live impact "
      f"(first non-zero sample at {first[0] / rate if len(first) else float('nan'):.4f} s)")
check(np.all(d[: int(0.5 * rate)] == 0), "debris: every sample before t0 = 0.5 s is exactly zero")

# The James-lab impulse format against the same events written natively.
def quat_mul(a, b):
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return [w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2]


def rest_point(point, pose):  # world -> body: q^-1 (p - x) q
    q = pose["orientation_wxyz"]
    v = [0.0] + [point[k] - pose["position_m"][k] for k in range(3)]
    qi = [q[0], -q[1], -q[2], -q[3]]
    return quat_mul(quat_mul(qi, v), q)[1:]


lines = ["# hand-written from the native scene: C t id pA xA qA vn J n, P ... for pairs"]
for e in demo["events"]:
    j = math.sqrt(sum(c * c for c in e["impulse_n_s"]))
    n = [c / j for c in e["impulse_n_s"]]
    def body(pose, point):
        q = pose["orientation_wxyz"]
        inv = [q[0], -q[1], -q[2], -q[3]]  # James: the inverse rotation
        p = rest_point(point, pose)
        return " ".join(f"{v:.17g}" for v in [*p, *pose["position_m"], *inv])
    if e["b"] == "ground":
        lines.append(f"C {e['t_s']:.17g} {e['a']} {body(e['pose_a'], e['point_m'])} {e['normal_speed_m_s']:.17g} {j:.17g} "
                     + " ".join(f"{v:.17g}" for v in n))
    else:
        lines.append(f"P {e['t_s']:.17g} {e['a']} {body(e['pose_a'], e['point_m'])} {e['b']} {body(e['pose_b'], e['point_m'])} "
                     f"{e['normal_speed_m_s']:.17g} {j:.17g} " + " ".join(f"{v:.17g}" for v in n))


def render_james(scene, impulse_lines, name, reference, what):
    """Renders impulse_lines with scene as the side file (its events dropped) against reference."""
    side = copy.deepcopy(scene)
    side["events"] = []
    json.dump(side, open(name + "-side.json", "w"))
    open(name + ".txt", "w").write("\n".join(impulse_lines) + "\n")
    r = subprocess.run([synth, "-i", name + "-side.json", "--impulses", name + ".txt", "-b", bank, "-o", name + ".wav"],
                       capture_output=True, text=True)
    check(r.returncode == 0, f"{what}: renders (exit {r.returncode}) {r.stderr.strip()}")
    if r.returncode == 0:
        err = np.abs(wav(name + ".wav") - reference).max() / np.abs(reference).max()
        check(err < 1e-6, f"{what} = the native scene, max deviation {err:.2e} of the peak")


native = render(demo, "native")
render_james(demo, lines, "james", native, "James-lab impulse file")


def mutate(f):  # a changed copy of the demo scene
    s = copy.deepcopy(demo)
    f(s)
    return s


def mesh_object(**fields):  # object 1 given by a mesh and fields instead of its numbers
    def f(s):
        o = s["objects"][0]
        for k in ("mass_kg", "volume_m3", "inertia_kg_m2"):
            del o[k]
        o.update(fields)
    return f


# An object given by a closed mesh: a box, off the origin, wound counter-clockwise seen from
# outside (its quads split by the reader), with a density. The reference object carries the box's
# closed-form mass properties: V = a b c, I = m diag(b^2 + c^2, a^2 + c^2, a^2 + b^2) / 12.
box_a, box_b, rho = 0.12, 0.08, 2600.0
box_c = demo["objects"][0]["volume_m3"] / (box_a * box_b)
off = [0.3, -0.2, 0.1]
corners = [[off[0] + (k & 1) * box_a, off[1] + ((k >> 1) & 1) * box_b, off[2] + ((k >> 2) & 1) * box_c] for k in range(8)]
centre = [off[0] + box_a / 2, off[1] + box_b / 2, off[2] + box_c / 2]
quads = ["1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"]
obj_text = "".join(f"v {x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in corners)
open("box.obj", "w").write(obj_text + "".join(f"f {q}\n" for q in quads))
vol = box_a * box_b * box_c
mass = rho * vol
closed_form = copy.deepcopy(demo)
closed_form["objects"][0].update(mass_kg=mass, volume_m3=vol, inertia_kg_m2=[
    [mass * (box_b**2 + box_c**2) / 12, 0, 0], [0, mass * (box_a**2 + box_c**2) / 12, 0], [0, 0, mass * (box_a**2 + box_b**2) / 12]])
meshed = mutate(mesh_object(mesh="box.obj", density_kg_m3=rho))


def given_times(scene):  # every event a contact of given duration: no Hertz time, no contact geometry
    s = copy.deepcopy(scene)
    for e in s["events"]:
        if "normal_speed_m_s" in e:
            del e["normal_speed_m_s"]
            e["contact_time_s"] = 3e-4
    return s


ref = render(given_times(closed_form), "closed_form")
got = render(given_times(meshed), "meshed")
err = np.abs(got - ref).max() / np.abs(ref).max()
check(err < 1e-6, f"an object given by its closed mesh = the box's closed-form mass properties (contact times given), "
      f"max deviation {err:.2e} of the peak")
# With Hertz times, the meshed box's contacts take its own surface's curvature (flat faces, edges,
# corners: docs/synth.md "Contact") where the closed-form box has only its proxy ellipsoid's.
hertz_mesh = render(meshed, "meshed-hertz")
hertz_proxy = render(closed_form, "closed-form-hertz")
dev = np.abs(hertz_mesh - hertz_proxy).max() / np.abs(hertz_proxy).max()
check(np.all(np.isfinite(hertz_mesh)) and np.abs(hertz_mesh).max() > 0 and dev > 1e-3,
      f"the meshed box's Hertz contacts come from its mesh, not the proxy: renders, and differs from the proxy's by {dev:.2e} of the peak")
# Its first ground hit moved onto a corner, and its hit by object 2 (both unrotated) onto the
# vertical edge x = +a/2, y = +b/2: the summary counts 3 face, 1 edge and 1 corner contact.
featured = copy.deepcopy(meshed)
first = featured["events"][0]
pair = [e for e in featured["events"] if e["a"] == 1 and e["b"] == 2][0]
assert first["pose_a"]["orientation_wxyz"] == [1.0, 0, 0, 0.0] and pair["pose_a"]["orientation_wxyz"] == [1, 0, 0, 0]
first["point_m"] = [first["pose_a"]["position_m"][0] - box_a / 2, -box_b / 2, first["pose_a"]["position_m"][2] - box_c / 2]
pair["point_m"] = [pair["pose_a"]["position_m"][0] + box_a / 2, box_b / 2, pair["pose_a"]["position_m"][2]]
r, _ = run(featured, "featured")
check(r.returncode == 0 and "Hertz contacts on objects' own meshes: 3 on smooth or flat surface, 1 on sharp edges, 1 on corners" in r.stdout,
      "the meshed box hit on faces, an edge and a corner: contacts counted by feature ("
      + " ".join([l for l in r.stdout.splitlines() if "own meshes" in l] or [r.stderr.strip()]) + ")")
# The James-lab format with that mesh: rest-pose contact points are in the mesh's coordinates,
# i.e. shifted by the box's centre of mass.
shifted = []
for line in lines[1:]:  # the demo's events as above
    f = line.split()
    if f[2] == "1":  # object 1 is always A in the demo
        f[3:6] = [f"{float(f[3 + k]) + centre[k]:.17g}" for k in range(3)]
    shifted.append(" ".join(f))
render_james(meshed, shifted, "james-mesh", hertz_mesh, "James-lab file, contact points in mesh coordinates (contact on the mesh)")
open("open.obj", "w").write(obj_text + "".join(f"f {q}\n" for q in quads[:5]))
open("inward.obj", "w").write(obj_text + "".join(f"f {' '.join(reversed(q.split()))}\n" for q in quads))

# Bad input: (mutation, fragments the error line must contain).
cases = [
    ("unknown object id", mutate(lambda s: s["events"][2].update(a=42)), ["events[2]", "object 42"]),
    ("non-symmetric inertia", mutate(lambda s: s["objects"][1]["inertia_kg_m2"][0].__setitem__(1, 1e-3)), ["object 2", "not symmetric"]),
    ("non-positive-definite inertia", mutate(lambda s: s["objects"][0]["inertia_kg_m2"][2].__setitem__(2, -1e-4)), ["object 1", "positive definite"]),
    ("negative mass", mutate(lambda s: s["objects"][0].update(mass_kg=-1)), ["objects[0].mass_kg", "-1"]),
    ("listener inside an object", mutate(lambda s: s["listeners"][0].update(position_m=s["events"][0]["pose_a"]["position_m"])), ["listener", "inside"]),
    ("events out of time order", mutate(lambda s: s["events"][5].update(t_s=0.0)), ["events[5]", "time order"]),
    ("wrong scene version", mutate(lambda s: s.update(format_version=7)), ["format_version", "7"]),
    ("unknown material", mutate(lambda s: s["objects"][2].update(material="unobtainium")), ["objects[2].material", "unobtainium"]),
    ("open mesh", mutate(mesh_object(mesh="open.obj", density_kg_m3=rho)), ["open.obj:", "not closed"]),
    ("mesh turned inside out", mutate(mesh_object(mesh="inward.obj", mass_kg=1.0)), ["objects[0].mesh", "counter-clockwise"]),
    ("missing mesh file", mutate(mesh_object(mesh="nowhere.obj", mass_kg=1.0)), ["nowhere.obj", "cannot open"]),
    ("mesh and inertia both", mutate(lambda s: s["objects"][0].update(mesh="box.obj")), ["objects[0].volume_m3", "not both"]),
    ("mesh without mass or density", mutate(mesh_object(mesh="box.obj")), ["objects[0]", "density_kg_m3"]),
    ("contact far from the mesh", mutate(lambda s: (mesh_object(mesh="box.obj", density_kg_m3=rho)(s),
                                                    s["events"][0].update(point_m=[-0.6, 0.0, -0.5]))),
     ["events[0]", "object 1", "from the mesh's surface"]),
]
for name, scene, fragments in cases:
    r, _ = run(scene, "bad")
    lines = [l for l in r.stderr.splitlines() if l.startswith("clatter-")]
    ok = r.returncode == 2 and len(lines) == 1 and all(f in lines[0] for f in fragments) and not os.path.exists("bad.wav")
    check(ok, f"bad input, {name}: exit {r.returncode}, {lines[0] if lines else r.stderr.strip()}")
# NaN in the text format, a bank of another version.
open("nan.txt", "w").write("C 0.1 1 0 0 0 0 0 0.1 1 0 0 0 nan 0.01 0 0 1\n")
r = subprocess.run([synth, "-i", "james-side.json", "--impulses", "nan.txt", "-b", bank, "-o", "nan.wav"], capture_output=True, text=True)
check(r.returncode == 2 and "nan.txt:1" in r.stderr and "nan: must be finite" in r.stderr and not os.path.exists("nan.wav"), f"bad input, NaN: exit {r.returncode}, {r.stderr.strip()}")
import h5py
shutil.copy(bank, "old.h5")
with h5py.File("old.h5", "r+") as f:
    f.attrs["format_version"] = np.int32(1)
r = subprocess.run([synth, "-i", demo_path, "-b", "old.h5", "-o", "old.wav"], capture_output=True, text=True)
check(r.returncode == 2 and "version 1" in r.stderr and not os.path.exists("old.wav"), f"bad input, bank version: exit {r.returncode}, {r.stderr.strip()}")

print("synth checks: " + ("all passed" if not failures else f"{len(failures)} FAILED"))
sys.exit(1 if failures else 0)
