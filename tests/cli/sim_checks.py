#!/usr/bin/env python3
"""clatter-sim end to end (docs/synth.md "Scenes from a rigid-body simulator"):
- determinism: the pre-fractured plate (scenes/plate.toml with plate.pieces=40, shortened to 0.6 s: it breaks at 0.31 s) and a
  shortened rock slide (scenes/rockslide.toml, 0.1 s), each run twice, give identical bytes, the
  scene (but for its mesh folder's name) and every mesh file;
- the scene is what the format promises, checked here on the JSON: the plate object destroyed at
  the fracture time and every piece created then (time-varying objects, 003 section 3.3), one
  fracture event per piece at that time, events in time order, momentum of the fracture impulses
  = m * kick per piece, masses summing to the plate's, the rock slide's >= 100 granite rocks;
- the plate renders through clatter-synth with a PAN, a modal and a ground bank: exit 0, and every
  object outside a bank's coverage is listed by id with its reason (docs/synth.md "Coverage");
- bad input, each exit 2 with one line naming the key and value, and a scene file already at the
  output path left untouched: an unknown material, one position for two meshes, a 2-vector, a
  zero time step, nothing to simulate, an unknown built-in body, a breakable body of a material without
  fracture data, a file where the scene's mesh folder goes.
Usage: sim_checks.py CLATTER_SIM CLATTER_SYNTH SOURCE_DIR PAN_BANK MODAL_BANK GROUND_BANK SCRATCH"""
import filecmp, json, math, os, re, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, run, start  # noqa: E402

sim, synth, src, pan_bank, modal_bank, ground_bank, scratch = sys.argv[1:8]
start(scratch)


plate_cfg = os.path.join(src, "scenes", "plate.toml")
rocks_cfg = os.path.join(src, "scenes", "rockslide.toml")
# The test ground bank holds steel and soil: the plate falls on steel here.
# The pre-fractured plate (plate.pieces > 0, the fast option); fracture by stress: fracture_checks.py.
plate_args = [sim, "-q", "-c", plate_cfg, "--set", "sim.duration_s=0.6", "--set", "ground.material=\"steel\"", "--set", "plate.pieces=40"]
for name in ("a", "b"):
    r = run(*plate_args, "-o", f"plate_{name}.json")
    check(r.returncode == 0, f"plate run {name} exits 0 ({r.returncode}: {r.stderr.strip()[-300:]})")


def same_scene(a, b):
    """The same bytes but for the mesh folder's name, and the same mesh files byte for byte."""
    text_a = open(f"{a}.json").read().replace(f'"{a}.meshes/', f'"{b}.meshes/')
    meshes = sorted(os.listdir(f"{a}.meshes"))
    return (text_a == open(f"{b}.json").read() and meshes == sorted(os.listdir(f"{b}.meshes"))
            and all(filecmp.cmp(f"{a}.meshes/{m}", f"{b}.meshes/{m}", shallow=False) for m in meshes))


check(same_scene("plate_a", "plate_b"), "two plate runs give identical scene and mesh bytes")
rock_args = [sim, "-q", "-c", rocks_cfg, "--set", "sim.duration_s=0.1"]
for name in ("a", "b"):
    r = run(*rock_args, "-o", f"rocks_{name}.json")
    check(r.returncode == 0, f"rock-slide run {name} exits 0 ({r.returncode}: {r.stderr.strip()[-300:]})")
check(same_scene("rocks_a", "rocks_b"), "two rock-slide runs give identical scene and mesh bytes")

scene = json.load(open("plate_a.json"))
objects = {o["id"]: o for o in scene["objects"]}
plate = objects[1]
pieces = [o for o in scene["objects"] if o["id"] != 1]
t_break = plate["destroyed_s"]
check(t_break is not None and 0.25 < t_break < 0.4, f"the plate (dropped from 0.5 m) breaks at its first impact, {t_break} s")
check(len(pieces) >= 30, f"{len(pieces)} pieces (>= 30)")
check(all(o["created_s"] == t_break for o in pieces), "every piece is created at the fracture time")
check(abs(sum(o["mass_kg"] for o in pieces) / plate["mass_kg"] - 1) < 1e-9, "the pieces' masses sum to the plate's")
check(all(os.path.isfile(o["mesh"]) and o["mesh"].startswith("plate_a.meshes/") for o in scene["objects"]),
      "every object names its mesh in plate_a.meshes/")
check(len(os.listdir("plate_a.meshes")) == len(scene["objects"]), "one mesh file per object, no other")
fractures = [e for e in scene["events"] if e["b"] == "fracture"]
check(len(fractures) == len(pieces) and all(e["t_s"] == t_break for e in fractures), "one fracture event per piece, at the break")
kick = 0.5  # plate.kick_m_s's default
check(all(abs(math.hypot(*e["impulse_n_s"]) / (objects[e["a"]]["mass_kg"] * kick) - 1) < 1e-9 for e in fractures),
      "each fracture impulse is the piece's mass times the kick speed")
times = [e["t_s"] for e in scene["events"]]
check(times == sorted(times), "events in time order")
plate_events = [e for e in scene["events"] if 1 in (e["a"], e["b"])]
check(len(plate_events) >= 2 and all(e["t_s"] <= t_break for e in plate_events) and plate_events[0]["t_s"] < t_break - 0.01,
      "the plate lands whole on its rim more than 10 ms before the impact that breaks it (plate.break_speed_m_s)")
check(scene["generator"]["program"] == "clatter-sim" and scene["generator"]["time_step_s"] == 2e-4, "generator names the program and its step")
rocks = json.load(open("rocks_a.json"))
check(len(rocks["objects"]) >= 100 and all(o["material"] == "granite" for o in rocks["objects"]), f"{len(rocks['objects'])} granite rocks")
check(rocks["ground_material"] == "concrete", "the rock slide lands on concrete")

r = run(synth, "-i", "plate_a.json", "-b", pan_bank, "-m", modal_bank, "-g", ground_bank, "-o", "plate.wav", "--stems")
check(r.returncode == 0 and os.path.getsize("plate.wav") > 1000, f"the plate renders with PAN, modal and ground banks ({r.returncode}: {r.stderr.strip()[-300:]})")
for source in ("pan", "modal"):
    m = re.search(rf"clatter-synth: {source}: note: (\d+) of (\d+) objects outside", r.stdout)
    listed = set(int(x) for x in re.findall(rf"clatter-synth: {source}:   object (\d+): .+", r.stdout))
    if m:
        check(int(m.group(1)) == len(listed) and listed <= set(objects), f"{source}: the {m.group(1)} uncovered objects are each listed with a reason")
    else:
        check(f"clatter-synth: {source}: every object within the bank's coverage" in r.stdout, f"{source}: coverage reported")
print(r.stdout)

# Bad input: exit 2, one line naming key and value, and the file already at the output untouched.
with open("kept.json", "w") as f:
    f.write("a scene the user had\n")
bad = [(["--set", "bodies.material=\"unobtainium\""], "unobtainium"),
       (["--set", "meshes.files=[\"a.obj\", \"b.obj\"]", "--set", "meshes.positions_m=[[0, 0, 1]]"], "meshes.positions_m"),
       (["--set", "plate.position_m=[0, 1]"], "plate.position_m"),
       (["--set", "sim.dt_s=0"], "sim.dt_s"),
       (["--set", "sim.bodies=[]"], "nothing to simulate"),
       (["--set", "sim.bodies=[\"cube\"]"], "sim.bodies"),
       (["--set", "bodies.material=\"steel\""], "tensile_strength_pa")]
for extra, word in bad:
    r = run(sim, "-c", plate_cfg, *extra, "-o", "kept.json")
    lines = r.stderr.strip().splitlines()
    check(r.returncode == 2 and len(lines) == 1 and word in lines[0], f"{' '.join(extra)}: exit 2 naming {word} ({r.returncode}: {r.stderr.strip()})")
    check(open("kept.json").read() == "a scene the user had\n" and not os.path.exists("kept.json.partial")
          and not os.path.exists("kept.meshes"), f"{word}: the existing output is untouched, no mesh folder")
with open("kept.meshes", "w") as f:
    f.write("not a folder\n")
r = run(sim, "-c", plate_cfg, "-o", "kept.json")
check(r.returncode == 2 and "kept.meshes" in r.stderr and open("kept.json").read() == "a scene the user had\n",
      f"a file where the mesh folder goes: exit 2 before simulating, naming it ({r.returncode}: {r.stderr.strip()})")

finish("sim checks")
