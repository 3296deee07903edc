#!/usr/bin/env python3
"""clatter-synth's ground sound end to end (docs/synth.md "Ground sound"), on a small ground bank
made by `clatter-bank ground` (the ground_bank fixture's, tests/ground.cmake) and a PAN bank:
- PAN and ground together (--stems): OUT.ground.wav exists and is not silent, the mix is the sum of
  the stems, and the summary names the ground's peak and RMS and its counts line;
- the ground stem against the formula of docs/synth.md evaluated here on the bank's own series
  (h5py): contacts shorter than 4 samples put eta at one sample, c_s / (rate D), whatever the
  Hertz time, so every input of p_n = A (Pi(t_hat_n+1) - Pi(t_hat_n)) / dt_hat is known: the file
  reader, the bilinear interpolation between elevations and the scaling, end to end;
- the same drops as James-lab 'C' lines give the same ground stem;
- a pair event and a fracture event add nothing to the ground stem;
- bad input, each exit 2 with one line and no WAV: a ground material the bank lacks, a listener on
  the ground, a Young's modulus 5 % off the bank's.
The physics (scaling, delay, interpolation, box average) is checked in GroundSynth.* on banks
with known series; here the bank is a real one.
Usage: synth_ground_checks.py CLATTER_SYNTH GROUND_BANK PAN_BANK SCRATCH"""
import copy, json, math, os, subprocess, sys
import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, start  # noqa: E402
from synth_wav import wav  # noqa: E402

synth, ground_bank, pan_bank, scratch = sys.argv[1:5]
start(scratch)


with h5py.File(ground_bank, "r") as f:
    names = sorted(f["materials"].keys())
    # The stiffest ground: the shortest Hertz time, so the contact stays under 4 samples.
    name = max(names, key=lambda n: f["materials"][n].attrs["youngs_pa"])
    g = f["materials"][name]
    ground = {k: float(g.attrs[k]) for k in ("youngs_pa", "poisson", "rho_kg_m3", "shear_speed_m_s")}
    elevations, etas = g["elevation_rad"][()], g["eta"][()]
    series = [(start, dt, g["pi"][offset:offset + length], tail, etas[k % len(etas)]) for k, (offset, length, start, dt, tail) in
              enumerate(zip(g["series_offset"][()], g["series_length"][()], g["t_hat_start"][()], g["dt_hat"][()], g["tail"][()]))]
    rho0 = float(f["air"].attrs["rho0_kg_m3"])
print(f"ground bank {ground_bank}: materials {', '.join(names)}; using '{name}' {ground}")

# Small granite balls (r 5 mm, 3 m/s: a Hertz time near 40 us on concrete, under 4 samples) dropped
# on the bank's ground four times at different points; two listeners, one between the bank's first two
# elevations, one at 60 degrees.
radius, rate = 0.005, 44100
volume = 4 / 3 * math.pi * radius ** 3
mass, moment = 2700 * volume, 0.4 * 2700 * volume * radius ** 2
sphere = {"mass_kg": mass, "volume_m3": volume, "material": "granite",
          "inertia_kg_m2": [[moment, 0, 0], [0, moment, 0], [0, 0, moment]]}
points = [[0.0, 0.0], [0.3, -0.2], [-0.4, 0.5], [0.1, 0.9]]
drops = [{"t_s": 0.01 + 0.017 * k, "a": 1, "b": "ground", "point_m": [x, y, 0.0],
          "impulse_n_s": [0.0002, 0.0, 0.004 * (k + 1)], "normal_speed_m_s": 3.0,
          "pose_a": {"position_m": [x, y, radius], "orientation_wxyz": [1, 0, 0, 0]}}
         for k, (x, y) in enumerate(points)]
pose = drops[0]["pose_a"]
low = 0.5 * (elevations[0] + elevations[1])
listeners = [[2.0 * math.cos(low), 0.0, 2.0 * math.sin(low)], [0.0, 3.1 * math.cos(math.pi / 3), 3.1 * math.sin(math.pi / 3)]]
scene = {"format": "clatter-scene", "format_version": 1,
         "materials": {"granite": {"youngs_modulus_pa": 5e10, "poisson_ratio": 0.25},
                       name: {"youngs_modulus_pa": ground["youngs_pa"], "poisson_ratio": ground["poisson"],
                              "density_kg_m3": ground["rho_kg_m3"]}},
         "ground_material": name,
         "objects": [dict(sphere, id=1), dict(sphere, id=2)],
         "events": drops,
         "listeners": [{"position_m": x} for x in listeners],
         "duration_s": 0.2}


def tail_pi(tail, eta, t):
    """Pi past a series: sum_m tail[m - 2] (2 Re (t + i eta)^-m - Re (t + 2 i eta)^-m) (model/ground_bank.hpp)."""
    m = np.arange(2, 2 + len(tail))[:, None]
    t = np.asarray(t, dtype=float)[None, :]
    return np.sum(tail[:, None] * (2 * np.real((t + 1j * eta) ** -m) - np.real((t + 2j * eta) ** -m)), axis=0)


def pi_of(k, t_hat):
    """Series k at t_hat (the edges t_hat0 + n dt of one impact's samples): 0 before the first
    sample, cubic (4-point Lagrange) between samples, linear in the first and last interval; after
    the last, the tail up to 2 t_hat_last (kTailSpan of synth/ground_source.cpp), interpolated by
    the same cubic between nodes t_a / 16 apart (kTailNodes; t_a the first edge past the series),
    then held at its value at 2 t_hat_last."""
    start, dt, pi, tail, eta = series[k]
    x = (t_hat - start) / dt
    i = np.clip(np.floor(x).astype(int), 0, len(pi) - 2)
    u = x - i
    v = pi[i] + u * (pi[i + 1] - pi[i])
    inner = (x >= 1) & (x < len(pi) - 2)
    j = np.clip(i, 1, len(pi) - 3)
    a, b, c, d = pi[j - 1], pi[j], pi[j + 1], pi[j + 2]
    cubic = (-u * (u - 1) * (u - 2) / 6 * a + (u + 1) * (u - 1) * (u - 2) / 2 * b - (u + 1) * u * (u - 2) / 2 * c
             + (u + 1) * u * (u - 1) / 6 * d)
    v = np.where(inner, cubic, v)
    t_last = start + (len(pi) - 1) * dt
    t_cut = 2 * t_last
    after = np.full_like(t_hat, tail_pi(tail, eta, [t_cut])[0])
    past = np.nonzero(x >= len(pi) - 1)[0]
    if len(past):
        t_a = t_hat[past[0]]
        delta = max(t_hat[1] - t_hat[0], t_a / 16)
        y = (t_hat - t_a) / delta + 2
        nodes = tail_pi(tail, eta, t_a + (np.arange(int(y.max()) + 4) - 2) * delta)
        iy = np.clip(np.floor(y).astype(int), 1, len(nodes) - 3)
        w = y - iy
        a, b, c, d = nodes[iy - 1], nodes[iy], nodes[iy + 1], nodes[iy + 2]
        node_cubic = (-w * (w - 1) * (w - 2) / 6 * a + (w + 1) * (w - 1) * (w - 2) / 2 * b - (w + 1) * w * (w - 2) / 2 * c
                      + (w + 1) * w * (w - 1) / 6 * d)
        after = np.where(t_hat < t_cut, node_cubic, after)
    return np.where(x < 0, 0.0, np.where(x >= len(pi) - 1, after, v))


def bracket(grid, x):
    x = min(max(x, grid[0]), grid[-1])
    hi = min(int(np.searchsorted(grid, x, side="right")), len(grid) - 1)
    lo = max(hi - 1, 0)
    return lo, hi, 0.0 if hi == lo else (x - grid[lo]) / (grid[hi] - grid[lo])


def expected_ground(n_samples):
    """docs/synth.md "Ground sound", steps 1-7, for the drops at each listener."""
    c_s, mu = ground["shear_speed_m_s"], ground["youngs_pa"] / (2 * (1 + ground["poisson"]))
    out = np.zeros((n_samples, len(listeners)))
    edges = np.arange(n_samples + 1) / rate
    for e in drops:
        for l, x in enumerate(listeners):
            d = math.dist(x, [e["point_m"][0], e["point_m"][1], 0.0])
            dt_hat = c_s / (rate * d)  # eta at one sample: the contact is shorter than 4 samples
            (e0, e1, we), (t0, t1, wt) = bracket(elevations, math.asin(x[2] / d)), bracket(np.log(etas), math.log(dt_hat))
            t_hat = c_s * (edges - e["t_s"]) / d
            pi = sum(w * pi_of(i * len(etas) + j, t_hat) for i, j, w in
                     [(e0, t0, (1 - we) * (1 - wt)), (e0, t1, (1 - we) * wt), (e1, t0, we * (1 - wt)), (e1, t1, we * wt)] if w)
            a = rho0 * c_s ** 3 * e["impulse_n_s"][2] / (mu * d ** 3)
            out[:, l] += a * np.diff(pi) / dt_hat
    return out


def run(scene, out, extra=()):
    json.dump(scene, open(out + ".json", "w"))
    return subprocess.run([synth, "-i", out + ".json", "-g", ground_bank, "-o", out + ".wav", *extra],
                          capture_output=True, text=True)


# ---- PAN and ground together
r = run(scene, "both", ["-b", pan_bank, "--stems"])
check(r.returncode == 0, f"PAN and ground rendered ({r.stderr.strip()})")
print(r.stdout.strip())
mix, pan, grd = wav("both.wav"), wav("both.pan.wav"), wav("both.ground.wav")
dev = np.abs(mix - pan - grd).max() / np.abs(mix).max()
check(np.abs(grd).max() > 0 and np.abs(pan).max() > 0, f"the ground stem is not silent (peak {np.abs(grd).max():.3g} Pa)")
check(dev < 1e-6, f"mix = pan + ground stems (deviation {dev:.2g} of the peak)")
check("ground peak" in r.stdout and "ground: 4 impacts on" in r.stdout and "eta raised to one sample 8," in r.stdout,
      "summary: the ground's peak and RMS, and its counts line: 4 ground impacts, eta at one sample at both listeners")
ref = expected_ground(len(grd))
err = np.abs(grd - ref).max() / np.abs(ref).max()
check(err < 1e-6, f"the ground stem against the formula on the bank's series: {err:.2g} of the peak {np.abs(ref).max():.4g} Pa "
      "(float32 storage)")

# ---- the same drops as James-lab 'C' lines (docs/scene-format.md): C t id pA xA qA vn J n, with
# pA in the body frame (the poses here are unrotated, so pA = point - position) and n the unit impulse.
lines = []
for e in drops:
    j = math.sqrt(sum(c * c for c in e["impulse_n_s"]))
    body = [e["point_m"][k] - e["pose_a"]["position_m"][k] for k in range(3)]
    fields = [e["t_s"], e["a"], *body, *e["pose_a"]["position_m"], 1, 0, 0, 0, e["normal_speed_m_s"], j,
              *[c / j for c in e["impulse_n_s"]]]
    lines.append("C " + " ".join(f"{v:.17g}" for v in fields))
side = copy.deepcopy(scene)
side["events"] = []
json.dump(side, open("james-side.json", "w"))
open("james.txt", "w").write("\n".join(lines) + "\n")
r = subprocess.run([synth, "-i", "james-side.json", "--impulses", "james.txt", "-g", ground_bank, "-o", "james.wav", "--stems"],
                   capture_output=True, text=True)
dev = np.abs(wav("james.ground.wav") - grd).max() / np.abs(grd).max() if r.returncode == 0 else float("inf")
check(r.returncode == 0 and dev < 1e-6, f"James-lab 'C' lines give the native scene's ground stem ({dev:.2g} of the peak) {r.stderr.strip()}")

# ---- a pair and a fracture event are not the ground's
more = copy.deepcopy(scene)
more["events"] = drops + [
    {"t_s": 0.1, "a": 1, "b": 2, "point_m": [0.0, 0.0, 2 * radius], "impulse_n_s": [0.0, 0.0, -0.004], "normal_speed_m_s": 1.0,
     "pose_a": pose, "pose_b": {"position_m": [0.0, 0.0, 3 * radius], "orientation_wxyz": [1, 0, 0, 0]}},
    {"t_s": 0.12, "a": 2, "b": "fracture", "point_m": [0.0, 0.0, 2 * radius], "impulse_n_s": [0.0, 0.0, 0.004],
     "contact_time_s": 1e-4, "pose_a": {"position_m": [0.0, 0.0, 3 * radius], "orientation_wxyz": [1, 0, 0, 0]}}]
r = run(more, "more", ["--stems"])
check(r.returncode == 0 and np.array_equal(wav("more.ground.wav"), grd),
      f"a pair and a fracture event leave the ground stem as it was ({r.stderr.strip()})")

# ---- bad input
def refused(scene, out, needles, what):
    r = run(scene, out)
    lines = r.stderr.strip().splitlines()
    ok = r.returncode == 2 and len(lines) == 1 and all(n in r.stderr for n in needles) and not os.path.exists(out + ".wav")
    check(ok, f"{what}: exit 2, one line, no WAV ({r.stderr.strip()})")


bad = copy.deepcopy(scene)
bad["materials"]["lava"] = bad["materials"].pop(name)
bad["ground_material"] = "lava"
refused(bad, "unknown", ["ground_material: 'lava'", os.path.basename(ground_bank), f"'{name}'"], "a ground material the bank lacks")
bad = copy.deepcopy(scene)
bad["listeners"].append({"position_m": [1.0, 1.0, 0.0]})
refused(bad, "below", ["listeners[2].position_m", "not above the ground"], "a listener on the ground")
bad = copy.deepcopy(scene)
bad["materials"][name]["youngs_modulus_pa"] = 1.05 * ground["youngs_pa"]
refused(bad, "modulus", [f"materials.{name}.youngs_modulus_pa", "differs from the ground bank's"], "a modulus 5 % off")

finish("synth ground checks")
