#!/usr/bin/env python3
"""analysis/pan_piece_dipoles.py on a piece whose answer is known: an ellipsoid with semi-axes
(4, 0.96, 0.2) cm given as a mesh (an icosphere of 5120 triangles stretched; its thin axis along x,
long along y, so the script must find the axis and combine fields 1-3 along it). Its equivalent
ellipsoid is itself (to the polyhedron's 0.1 %), so the script's own-PAN dipole at 2 cm cells must
match Lamb's (PanBank.ThinProxies* holds the proxies within 1.4 % there); the nearest proxy of the grid is (0.12, 0.025), the shape itself;
and a sphere of its volume carries 3V/2, a fifth of it. A scene with no piece: exit non-zero.
Usage: pan_piece_dipoles_check.py PYTHON SCRIPT BIN_DIR MPIEXEC WORKDIR"""
import csv, json, math, os, subprocess, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, start  # noqa: E402

python, script, bin_dir, mpiexec, work = sys.argv[1:6]
work = os.path.abspath(work)
start(work)

sphere = os.path.join(work, "sphere.obj")
subprocess.run([f"{bin_dir}/clatter-test-mesh", "sphere", "1", "4", sphere], check=True)
semi = (0.002, 0.04, 0.0096)  # x thin, y long, z middle
with open(os.path.join(work, "piece.obj"), "w") as out:
    for line in open(sphere):
        if line.startswith("v "):
            x, y, z = map(float, line.split()[1:4])
            out.write(f"v {x * semi[0]:.12g} {y * semi[1]:.12g} {z * semi[2]:.12g}\n")
        else:
            out.write(line)
volume = 4 / 3 * math.pi * semi[0] * semi[1] * semi[2]
scene = {"format": "clatter-scene", "format_version": 1,
         "materials": {"ceramic": {"youngs_modulus_pa": 7.2e10, "poisson_ratio": 0.19}}, "ground_material": "ceramic",
         "objects": [{"id": 1, "mesh": "piece.obj", "mass_kg": 2700 * volume, "material": "ceramic"}],
         "events": [], "listeners": [{"position_m": [0, 0, 1]}], "duration_s": 0.1}
json.dump(scene, open(os.path.join(work, "scene.json"), "w"))
out = os.path.join(work, "out")
r = subprocess.run([python, script, os.path.join(work, "scene.json"), "--out", out, "--dx", "0.04", "0.02", "--bin", bin_dir,
                    "--mpiexec", f"{mpiexec} -n 2"], capture_output=True, text=True)
print(r.stdout[-2500:], r.stderr[-1500:])
check(r.returncode == 0, "the script runs (exit 0)")
rows = list(csv.DictReader(open(os.path.join(out, "piece-dipoles.csv")))) if r.returncode == 0 else []
check(len(rows) == 1, f"one row ({len(rows)})")
if rows:
    row = rows[0]
    # Lamb's 2V / (2 - alpha) across the thin axis, by the closed form's own quadrature (not the script's R_D).
    from scipy.integrate import quad
    a, b, c = semi[1], semi[2], semi[0]
    alpha = a * b * c * quad(lambda l: 1 / ((c * c + l) * math.sqrt((a * a + l) * (b * b + l) * (c * c + l))), 0, math.inf, limit=400)[0]
    lamb_cm3 = 2 * volume / (2 - alpha) * 1e6
    check(abs(float(row["ellipsoid_cm3"]) / lamb_cm3 - 1) < 0.005,
          f"the equivalent ellipsoid's dipole is Lamb's for the shape ({float(row['ellipsoid_cm3']):.4f} against {lamb_cm3:.4f} cm^3)")
    # The rim is smooth: at 2 cm the own entry holds Lamb's like the proxies; the first-order
    # extrapolation the script makes for sharp-edged pieces overshoots a body that converges faster.
    own = float(row["own_dx0.02_cm3"])
    check(abs(own / lamb_cm3 - 1) < 0.02, f"the own PAN's dipole at 2 cm within 2 % of Lamb's ({own:.4f} cm^3, "
                                          f"{100 * (own / lamb_cm3 - 1):+.2f} %)")
    check(abs(float(row["B"]) - 0.12) < 1e-3 and abs(float(row["C"]) - 0.025) < 1e-3
          and float(row["proxy_B"]) == 0.12 and float(row["proxy_C"]) == 0.025,
          f"its shape (0.12, 0.025) and nearest proxy ({row['proxy_B']}, {row['proxy_C']})")
    check(abs(float(row["equal_volume_sphere_cm3"]) / (1.5 * volume * 1e6) - 1) < 0.005, "the sphere of its volume carries 3V/2")
check(os.path.exists(os.path.join(out, "piece-dipoles.png")), "the plot is written")

scene["objects"][0]["destroyed_s"] = 0.05
json.dump(scene, open(os.path.join(work, "broken.json"), "w"))
r = subprocess.run([python, script, os.path.join(work, "broken.json"), "--out", os.path.join(work, "out2"), "--bin", bin_dir],
                   capture_output=True, text=True)
check(r.returncode != 0 and "no piece" in r.stderr, f"a scene without pieces: exit {r.returncode}, named")

finish("pan piece dipole checks")
