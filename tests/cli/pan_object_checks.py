#!/usr/bin/env python3
"""clatter-bank pan-object end to end (docs/pan.md "Objects with their own PAN"): a coin given as a
mesh (clatter-test-mesh disk, radius 12 mm, 2 mm thick, 32 segments: mirror-symmetric) at the demo
resolution on 2 ranks, field 3; then what the bank says of it, checked against the OBJ file read
here (independent of the code): its normalization (scale = A / the largest vertex distance from
the centre of mass, which symmetry puts at the box's centre), the key's length, `info`'s lines, `probe`
by the key's start at the mesh's own size (--scale 1/scale) and the held-out summary the sweep
logged; `plan --kind pan-object` on one and eight octants; then a scene's mesh objects
(objects.scene), each mesh once. Usage: pan_object_checks.py
BIN_DIR MPIEXEC WORKDIR"""
import math, os, re, shutil, subprocess, sys

import h5py

bin_dir, mpiexec, work = sys.argv[1:4]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
os.chdir(work)
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def run(*args):
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode != 0:
        print(r.stdout[-2000:], r.stderr[-2000:])
    return r


subprocess.run([f"{bin_dir}/clatter-test-mesh", "disk", "0.012", "0.002", "32", "3", "coin.obj"], check=True)
demo = ["--set=pulse.h_s=0.0005", "--set=grid.dx_m=0.04", "--set=time.dt_s=4.1666666666666665e-05",
        "--set=solve.fields=[3]", '--set=objects.meshes=["coin.obj"]']
r = run(mpiexec, "-n", "2", f"{bin_dir}/clatter-bank", "pan-object", *demo, "-o", "coin.h5", "--progress-interval", "0")
check(r.returncode == 0, "pan-object on 2 ranks exits 0")
log = r.stdout + r.stderr
check("1 meshes x 1 fields = 1 tasks" in log, "the sweep names 1 mesh x 1 field")
check("pan-object: held out: worst" in log, "the merge logs the held-out check")
check("cells wide at grid.dx_m" not in log, "no width warning for the coin (its equivalent ellipsoid about 25 cells across)")
# A strip 10 x 1 x 0.3 cm is about 3 cells across at the demo's 4 cm once scaled to A: its
# added mass would be far too small (docs/pan.md "Proxy validation"), so pan-object warns.
subprocess.run([f"{bin_dir}/clatter-test-mesh", "bar", "0.1", "0.01", "0.003", "20", "2", "1", "strip.obj"], check=True)
r = run(f"{bin_dir}/clatter-bank", "pan-object", *demo[:-1], '--set=objects.meshes=["strip.obj"]', "--set=fit.divisions=2",
        "--set=fit.direction_tolerance=0", "--set=check.held_out_directions=0", "-o", "strip.h5", "--progress-interval", "0")
m = re.search(r"mesh 'strip.obj' is ([0-9.]+) cells wide at grid.dx_m = 0.04", r.stdout + r.stderr)
check(r.returncode == 0 and m is not None and 2 < float(m.group(1)) < 5,
      f"pan-object warns that the strip is {m.group(1) if m else '?'} cells wide (2b of its equivalent ellipsoid)")

vertices = [tuple(map(float, line.split()[1:4])) for line in open("coin.obj") if line.startswith("v ")]
# A mirror-symmetric solid's centre of mass lies on its three mirror planes: the box's centre.
centre = [0.5 * (min(v[a] for v in vertices) + max(v[a] for v in vertices)) for a in range(3)]
radius = max(math.sqrt(sum((v[a] - centre[a]) ** 2 for a in range(3))) for v in vertices)
with h5py.File("coin.h5") as f:
    stored = f["meshes/centre_of_mass_m"][0]
    check(all(abs(stored[a] - centre[a]) < 1e-12 for a in range(3)), f"centre of mass {list(stored)} = the box's centre {centre}")
    check(f.attrs["format"] == "clatter-pan-bank" and f.attrs["format_version"] == 6, "a PAN bank, format 6")
    scale = float(f["meshes/scale"][0])
    key = f["meshes"].attrs["keys"]
    key = key.decode() if isinstance(key, bytes) else key
    check(abs(scale - 0.5 / radius) < 1e-9 * scale, f"scale {scale:.9g} = A / bounding radius = {0.5 / radius:.9g}")
    check(len(key) == 16 and " " not in key, f"one key, 16 hex digits: {key}")
    points = f["meshes/support_points_m"][:]
    far = max(math.sqrt(sum(c * c for c in p)) for p in points)
    check(abs(far - 0.5) < 1e-9, f"the farthest support point at A = 0.5 m ({far:.12f})")

info = run(f"{bin_dir}/clatter-bank", "info", "coin.h5").stdout
check("0 ellipsoids and 1 meshes" in info, "info counts 1 mesh entry")
check(f"mesh:        {key}: scaled by" in info, "info lists the mesh by its key")
check(f"mesh {key[:12]} field 3" in info, "info's held-out table names the entry by its key")

probe = run(f"{bin_dir}/clatter-bank", "probe", "coin.h5", "--mesh", key[:6], "--field", "3", "--point", "0,0,1.2",
            "--scale", repr(1 / scale), "--rate", "44100")
rows = probe.stdout.strip().splitlines()
check(probe.returncode == 0 and rows[0] == "t_s,p_Pa" and len(rows) > 20, f"probe --mesh {key[:6]} prints a series ({len(rows) - 1} samples)")
peak = max(abs(float(l.split(",")[1])) for l in rows[1:]) if len(rows) > 1 else 0
check(peak > 0, f"probe's series is not silent (peak {peak:.3g} Pa per m/s^2)")
wrong = run(f"{bin_dir}/clatter-bank", "probe", "coin.h5", "--mesh", "zz", "--field", "3", "--point", "0,0,1.2")
check(wrong.returncode == 2 and "no mesh entry with a key starting 'zz'" in wrong.stderr, "probe --mesh of an unknown key: exit 2, named")

# plan --kind pan-object: the coin's task on the octant grid; with objects.all_octants its full
# domain, whose grid is the octant grid mirrored into the other seven (8x the cells, to within the
# cells the mirror planes share), and eight octants' hearing. Its time: the same calibrated rate
# times 8x the cell-updates plus 8x the series, so at least 8x the octant task's grid part.


def plan(*sets):
    r = run(f"{bin_dir}/clatter-bank", "plan", "--kind", "pan-object", *demo, *sets, "--ranks", "2", "--rate", "1e8")
    return r.returncode, r.stdout + r.stderr


def task_lines(text):  # (cells, cell-updates, series) of each "per task" line
    return [tuple(float(x) for x in m) for m in
            re.findall(r"= ([0-9.e+]+) M cells, \d+ steps: ([0-9.e+]+) cell-updates; (?:up to )?([0-9.e+]+) series", text)]


code, one = plan()
check(code == 0 and "1 meshes x 1 fields = 1 tasks" in one and "(8 octants)" not in one, "plan --kind pan-object: 1 mesh, octant grid")
code, eight = plan("--set=objects.all_octants=true")
lines = task_lines(one) + task_lines(eight)
check(code == 0 and len(lines) == 2 and "(8 octants)" in eight, f"plan of the entry as one and as eight octants: a grid line each ({len(lines)} lines)")
if len(lines) == 2:
    (cells_1, updates_1, series_1), (cells_8, updates_8, series_8) = lines
    check(7.5 < cells_8 / cells_1 <= 8.0, f"full domain / octant grid = {cells_8 / cells_1:.3f} cells (8, less the shared planes)")
    check(abs(series_8 / series_1 - 8) < 1e-9, f"eight octants hear 8x the series ({series_8:.0f} / {series_1:.0f})")
    # Both printed to 3 digits: equal to within their rounding.
    check(abs(updates_8 / updates_1 / (cells_8 / cells_1) - 1) < 0.01, "cell-updates scale with the cells (same steps)")

# A scene's objects (objects.scene): two coins of one mesh and a rock given by numbers make one
# entry, the same key; refused before any solve when the scene has no mesh at all (a plan-free check:
# --print-config would not read the scene, so a run that fails on input is used).
scene = {"format": "clatter-scene", "format_version": 1,
         "materials": {"steel": {"youngs_modulus_pa": 2e11, "poisson_ratio": 0.3}}, "ground_material": "steel",
         "objects": [{"id": 1, "mesh": "coin.obj", "density_kg_m3": 7800, "material": "steel"},
                     {"id": 2, "mesh": "coin.obj", "density_kg_m3": 7800, "material": "steel"},
                     {"id": 3, "mass_kg": 0.1, "volume_m3": 4e-5, "inertia_kg_m2": [[1e-5, 0, 0], [0, 1e-5, 0], [0, 0, 1e-5]],
                      "material": "steel"}],
         "events": [], "listeners": [{"position_m": [0, 0, 1]}], "duration_s": 0.1}
import json
json.dump(scene, open("coins.json", "w"))
r = run(mpiexec, "-n", "2", f"{bin_dir}/clatter-bank", "pan-object", *demo[:-1], "--set=objects.scene=coins.json", "-o", "scene.h5",
        "--progress-interval", "0")
check(r.returncode == 0 and "1 meshes x 1 fields = 1 tasks" in r.stdout + r.stderr, "a scene's two coins of one mesh make one entry")
with h5py.File("scene.h5") as f:
    k = f["meshes"].attrs["keys"]
    check((k.decode() if isinstance(k, bytes) else k) == key, "the scene's entry has the coin file's key")
scene["objects"] = scene["objects"][2:]
json.dump(scene, open("rock.json", "w"))
r = run(f"{bin_dir}/clatter-bank", "pan-object", *demo[:-1], "--set=objects.scene=rock.json", "-o", "rock.h5")
check(r.returncode == 2 and "none of its 1 objects is given by a mesh" in r.stderr and not os.path.exists("rock.h5"),
      "a scene without meshes: exit 2, named, no bank")

print("pan-object checks: " + ("all passed" if not failures else f"{len(failures)} failed"))
sys.exit(1 if failures else 0)
