#!/usr/bin/env python3
"""The granite floor (one materials table for every program, docs/materials.md): a rock slide on a
granite ground made by clatter-sim (--set ground.material=granite, its granite read from
configs/materials.toml) rendered with a ground bank built by clatter-bank for granite alone
(--set 'ground.materials=["granite"]', its granite read from the same table):
- the bank holds granite at the table's values (54 GPa, nu 0.25, 2650 kg/m^3, entered here by hand)
  and its shear speed is sqrt(E / (2 rho (1 + nu))) of them;
- the scene's ground is granite with the same E, nu and density;
- clatter-synth -g renders it: exit 0 (once the two tables disagreed by 14.8 % in E and it exited
  2), and the ground stem is not silent.
The bank is one material, one elevation and a coarse eta grid (seconds); the slide a 20-rock pile
for 0.4 s (it lands at about 0.2 s).
Usage: granite_floor_checks.py CLATTER_BANK CLATTER_SIM CLATTER_SYNTH SOURCE_DIR SCRATCH"""
import json, math, os, sys
import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, failures, finish, run, start  # noqa: E402
from synth_wav import wav  # noqa: E402

bank, sim, synth, src, scratch = sys.argv[1:6]
start(scratch)


# configs/materials.toml [granite], by hand: the values the table's source justifies.
E_PA, NU, RHO = 5.4e10, 0.25, 2650.0
r = run(bank, "ground", "--progress-interval", "0", "--set", 'ground.materials=["granite"]', "--set", "ground.elevations_deg=[30]",
        "--set", "ground.eta_min=0.05", "--set", "ground.eta_max=0.2", "--set", "ground.etas_per_octave=1", "-o", "granite.h5")
check(r.returncode == 0, f"clatter-bank ground builds the granite bank ({r.returncode}: {r.stderr.strip()[-300:]})")
if r.returncode == 0:
    with h5py.File("granite.h5", "r") as f:
        g = f["materials"]["granite"]
        got = (float(g.attrs["youngs_pa"]), float(g.attrs["poisson"]), float(g.attrs["rho_kg_m3"]))
        cs = float(g.attrs["shear_speed_m_s"])
    check(got == (E_PA, NU, RHO), f"the bank's granite is the table's: E, nu, rho = {got}")
    want_cs = math.sqrt(E_PA / (2 * RHO * (1 + NU)))
    check(abs(cs / want_cs - 1) < 1e-12, f"its shear speed {cs:.3f} m/s = sqrt(E / (2 rho (1 + nu))) = {want_cs:.3f}")

r = run(sim, "-q", "-c", os.path.join(src, "scenes", "rockslide.toml"), "--set", 'ground.material="granite"',
        "--set", "pile.pieces=20", "--set", "sim.duration_s=0.4", "-o", "rocks.json")
check(r.returncode == 0, f"clatter-sim: the rock slide on granite ({r.returncode}: {r.stderr.strip()[-300:]})")
if r.returncode == 0:
    scene = json.load(open("rocks.json"))
    floor = scene["materials"].get(scene["ground_material"], {})
    check(scene["ground_material"] == "granite", f"the scene's ground is {scene['ground_material']}")
    check((floor.get("youngs_modulus_pa"), floor.get("poisson_ratio"), floor.get("density_kg_m3")) == (E_PA, NU, RHO),
          f"the scene's granite is the table's: {floor}")
    on_ground = sum(1 for e in scene["events"] if e["b"] == "ground")
    check(on_ground > 0, f"{on_ground} rock-ground events")

if not failures:
    r = run(synth, "-i", "rocks.json", "-g", "granite.h5", "-o", "rocks.wav", "--stems")
    check(r.returncode == 0, f"clatter-synth -g renders the granite floor ({r.returncode}: {r.stderr.strip()[-300:]})")
    if r.returncode == 0:
        peak = float(np.abs(wav("rocks.ground.wav")).max())
        check(peak > 0 and math.isfinite(peak), f"the ground stem is not silent (peak {peak:.3g} Pa)")

finish("granite floor checks")
