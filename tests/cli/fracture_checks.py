#!/usr/bin/env python3
"""Fracture by stress in clatter-sim (003 section 3; docs/fracture.md), end to end:
- threshold: a glass slab 20 x 10 x 1 cm dropped flat breaks from above about h* and not below it.
  h* by hand: landing flat it is a beam carried at its ends under its own inertia; all the kinetic
  energy m g h stored as bending energy E = F^2 L^3 / (240 E I) under the total force F gives the
  mid-span stress sigma = F L t / (16 I), hence sigma^2 = 11.25 E rho g h (independent of the size),
  and h* = sigma_t^2 / (11.25 E rho g) = 11 cm for glass (45 MPa, 62 GPa, 2600 kg/m^3). From h*/4
  it must not break, from 4 h* it must;
- conservation at every fracture, from the scene's records: the pieces' masses sum to the body's,
  G_c A_F <= eta E_S, E_F = G_c A_F, Delta E_K = E_S - E_F, the fracture impulses of one fracture sum
  to zero, the body destroyed and its pieces created at the fracture's time;
- without fracture impulses (Fig. 5's inset): no fracture events and Delta E_K = 0;
- the trend of 003 Fig. 4: the window at G_c = 50 J/m^2 breaks into more pieces than at 120 J/m^2
  under the same impact;
- determinism: the same config twice gives identical scene and mesh bytes.
Usage: fracture_checks.py CLATTER_SIM SOURCE_DIR SCRATCH"""
import filecmp, json, math, os, sys, tomllib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, run, start  # noqa: E402

sim, src, scratch = sys.argv[1:4]
start(scratch)
glass = tomllib.load(open(os.path.join(src, "configs", "materials.toml"), "rb"))["glass"]
h_star = glass["tensile_strength_pa"] ** 2 / (11.25 * glass["youngs_pa"] * glass["rho_kg_m3"] * 9.81)
print(f"hand estimate: h* = {h_star:.4f} m")


def drop(name, h_m, *extra):
    """The slab dropped flat from h_m (its lowest face), simulated until 15 ms after it lands."""
    t = math.sqrt(2 * h_m / 9.81) + 0.015
    r = run(sim, "-q", "-o", f"{name}.json", "--set", 'sim.bodies=["slab"]', "--set", 'bodies.material="glass"',
            "--set", "sim.dt_s=1e-4", "--set", "slab.size_m=[0.2, 0.1, 0.01]", "--set", f"slab.position_m=[0, 0, {h_m + 0.005}]",
            "--set", f"sim.duration_s={t:.4f}", "--set", "fracture.edge_m=0.006", "--set", "bodies.base_frequency=false", *extra)
    check(r.returncode == 0, f"{name}: exit 0 ({r.returncode}: {r.stderr.strip()[-300:]})")
    return json.load(open(f"{name}.json")) if r.returncode == 0 else {"objects": [], "events": []}


low, high = drop("low", h_star / 4), drop("high", 4 * h_star)
check(not low.get("fractures") and len(low["objects"]) == 1, f"dropped from h*/4 = {h_star / 4:.3f} m it stays whole")
check(len(high.get("fractures", [])) >= 1, f"dropped from 4 h* = {4 * h_star:.3f} m it breaks "
      f"({len(high.get('fractures', []))} fractures, {len(high['objects'])} objects)")

eta = 0.8  # fracture.eta's default
objects = {o["id"]: o for o in high["objects"]}
for f in high.get("fractures", []):
    name = f"fracture of body {f['body']} at {f['t_s']} s"
    body, pieces = objects[f["body"]], [objects[i] for i in f["pieces"]]
    check(abs(sum(p["mass_kg"] for p in pieces) / body["mass_kg"] - 1) < 1e-9, f"{name}: the pieces' masses sum to the body's")
    check(f["fracture_energy_j"] <= eta * f["strain_energy_j"] * (1 + 1e-12), f"{name}: G_c A_F <= eta E_S "
          f"({f['fracture_energy_j']:.4g} <= {eta * f['strain_energy_j']:.4g} J)")
    check(abs(f["fracture_energy_j"] - f["toughness_j_m2"] * f["fracture_area_m2"]) <= 1e-12 * f["fracture_energy_j"], f"{name}: E_F = G_c A_F")
    released = f["strain_energy_j"] - f["fracture_energy_j"]
    check(abs(f["kinetic_energy_gained_j"] - released) <= 0.01 * released, f"{name}: Delta E_K = E_S - E_F "
          f"({f['kinetic_energy_gained_j']:.6g} vs {released:.6g} J)")
    check(body["destroyed_s"] == f["t_s"] and all(p["created_s"] == f["t_s"] for p in pieces), f"{name}: body destroyed, pieces created then")
    kicks = [e for e in high["events"] if e["b"] == "fracture" and e["a"] in f["pieces"] and e["t_s"] == f["t_s"]]
    total = [sum(e["impulse_n_s"][k] for e in kicks) for k in range(3)]
    scale = sum(math.hypot(*e["impulse_n_s"]) for e in kicks)
    check(kicks and math.hypot(*total) <= 1e-9 * scale, f"{name}: its {len(kicks)} fracture impulses sum to zero "
          f"(|sum| {math.hypot(*total):.3g} of {scale:.3g} N s)")

quiet = drop("no_impulses", 4 * h_star, "--set", "fracture.impulses=false")
check(quiet.get("fractures") and all(f["kinetic_energy_gained_j"] == 0 for f in quiet["fractures"])
      and not any(e["b"] == "fracture" for e in quiet["events"]), "without fracture impulses: it breaks, no fracture events, no energy gained")

again = drop("high_again", 4 * h_star)
text = open("high.json").read().replace('"high.meshes/', '"high_again.meshes/')
meshes = sorted(os.listdir("high.meshes"))
check(text == open("high_again.json").read() and meshes == sorted(os.listdir("high_again.meshes"))
      and all(filecmp.cmp(f"high.meshes/{m}", f"high_again.meshes/{m}", shallow=False) for m in meshes),
      "the same config twice: identical scene and mesh bytes")

pieces = {}
for g in (50, 120):
    r = run(sim, "-q", "-c", os.path.join(src, "scenes", f"window-{g}.toml"), "-o", f"window{g}.json",
            "--set", "sim.duration_s=0.04", "--set", "bodies.base_frequency=false")
    check(r.returncode == 0, f"window G_c {g}: exit 0 ({r.returncode}: {r.stderr.strip()[-300:]})")
    scene = json.load(open(f"window{g}.json")) if r.returncode == 0 else {"objects": []}
    pieces[g] = sum(1 for o in scene["objects"] if o.get("destroyed_s") is None and o["material"] == "glass")
check(pieces[50] > pieces[120] >= 1, f"Fig. 4: the window at G_c 50 J/m^2 breaks into more pieces ({pieces[50]}) than at 120 ({pieces[120]})")
finish("fracture checks")
