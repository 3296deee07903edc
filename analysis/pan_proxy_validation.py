#!/usr/bin/env python3
"""000 section 5's proxy validation: fracture pieces' acceleration noise from their own PAN
(`clatter-bank pan-object`) against their nearest proxy's, scaled (docs/pan.md "Proxy
validation"). For the first K pieces of a fracture scene (its objects given by meshes):

1. their own PAN bank, `clatter-bank pan-object` with the proxy bank's physics (skipped when
   OUT/pieces-pan.h5 exists: a run resumes there);
2. a scene of those pieces alone, each hit once against the ground at its own time (at rest,
   unrotated, 0.1 m up; the impulse at its lowest vertex, so it both translates and turns), heard
   by six listeners 1.2-3.2 m away in different directions;
3. `clatter-synth` twice, PAN only: `-b PROXIES` (every piece its proxy) and `-b PROXIES -P OWN`
   (every piece its own PAN);
4. per piece and listener, the relative L2 of the proxy rendering against the piece's own over
   its window; the distribution as a table and a plot (OUT/proxy-validation.png).

  analysis/pan_proxy_validation.py SCENE.json PROXIES.h5 --out DIR [--pieces K] [--bin DIR]
      [--mpiexec "mpiexec -n 2"] [--contact-s TAU] [--set KEY=VALUE ...]

--set passes pan-object keys (e.g. the proxy bank's resolution: pulse.h_s, grid.dx_m, time.dt_s);
the pieces' bank must be built at the proxy bank's resolution for a fair comparison.

--contact-s gives every impact a half-sine of that length (the scene's contact_time_s) instead of
its Hertz duration. PAN renders an acceleration on the basis psi(t - k beta h; beta h) (eq. 15), which
holds it only well below 1 / (beta h), and a piece's own entry and its proxy have different beta
(bounding radius against the equivalent ellipsoid's a): with the demo's h = 0.5 ms and a 5 cm piece
(beta h = 50 us) a Hertz contact of 50 us differs between the two renderings above 2 kHz for that
reason alone. A contact of 1 ms keeps both to the band they render alike (docs/pan.md "Proxy
validation"); at the paper's h = 0.1 ms the Hertz contacts do.
"""
import argparse
import json
import math
import os
import shlex
import subprocess
import sys

import numpy as np

LISTENERS_M = [[1.5, 0.0, 0.3], [0.0, 2.0, 1.0], [-1.0, -1.0, 1.5], [0.5, -2.5, 0.5], [2.0, 2.0, 1.5], [0.0, 0.2, 3.0]]
SPACING_S = 0.1  # between the pieces' impacts: each one's sound has died down (PAN is short) before the next


def read_obj(path):
    v, f = [], []
    for line in open(path):
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:4]])
        elif line.startswith("f "):
            f.append([int(x.split("/")[0]) - 1 for x in line.split()[1:4]])
    return np.array(v), np.array(f)


def scene_pieces(path, k):
    """The scene, its first k pieces (objects given by meshes still there at the end, not a body
    that broke) and their mesh files; exits naming the scene when there is none."""
    src = json.load(open(path))
    base = os.path.dirname(os.path.abspath(path))
    pieces = [o for o in src["objects"] if o.get("mesh") and o.get("destroyed_s") is None][:k]
    if not pieces:
        sys.exit(f"{path}: no piece: no object given by a mesh is left at the end")
    return src, pieces, [os.path.join(base, o["mesh"]) for o in pieces]


def centroid(v, f):
    """The solid's centre of mass (uniform density), from the signed tetrahedra to the origin."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    vol = np.einsum("ij,ij->i", a, np.cross(b, c)) / 6
    return ((a + b + c) / 4 * vol[:, None]).sum(axis=0) / vol.sum()


def read_wav(path):
    import warnings
    from scipy.io import wavfile
    with warnings.catch_warnings():  # clatter-synth's provenance chunk
        warnings.simplefilter("ignore")
        rate, data = wavfile.read(path)
    return rate, data.reshape(len(data), -1).astype(float)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene")
    ap.add_argument("proxies")
    ap.add_argument("--out", required=True)
    ap.add_argument("--pieces", type=int, default=8)
    ap.add_argument("--bin", default="build/release/bin")
    ap.add_argument("--mpiexec", default="mpiexec -n 2")
    ap.add_argument("--set", action="append", default=[], help="a pan-object key for the pieces' bank, KEY=VALUE")
    ap.add_argument("--contact-s", type=float, default=None, help="every impact a half-sine this long instead of its Hertz contact")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    src, pieces, meshes = scene_pieces(a.scene, a.pieces)

    own = os.path.join(a.out, "pieces-pan.h5")
    if not os.path.exists(own):
        cmd = shlex.split(a.mpiexec) + [f"{a.bin}/clatter-bank", "pan-object", "-o", own, "--log-view",
                                        "--set", "objects.meshes=[" + ", ".join(json.dumps(m) for m in meshes) + "]"]
        for s in a.set:
            cmd += ["--set", s]
        print(" ".join(shlex.quote(c) for c in cmd), flush=True)
        subprocess.run(cmd, check=True)

    objects, events = [], []
    for i, (o, path) in enumerate(zip(pieces, meshes)):
        v, f = read_obj(path)
        low = v[np.argmin(v[:, 2])] - centroid(v, f)  # the lowest vertex, from the centre of mass
        position = [0.0, 0.0, 0.1]
        objects.append({"id": i + 1, "mesh": path, "mass_kg": o["mass_kg"], "material": o["material"]})
        events.append({"t_s": 0.01 + SPACING_S * i, "a": i + 1, "b": "ground",
                       "point_m": [position[k] + low[k] for k in range(3)],
                       "impulse_n_s": [0.1 * o["mass_kg"], 0.05 * o["mass_kg"], 2.0 * o["mass_kg"]],
                       **({"contact_time_s": a.contact_s} if a.contact_s else {"normal_speed_m_s": 1.0}),
                       "pose_a": {"position_m": position, "orientation_wxyz": [1, 0, 0, 0]}})
    scene = {"format": "clatter-scene", "format_version": 1, "materials": src["materials"],
             "ground_material": src["ground_material"], "objects": objects, "events": events,
             "listeners": [{"position_m": p} for p in LISTENERS_M], "duration_s": 0.01 + SPACING_S * len(pieces)}
    scene_path = os.path.join(a.out, "pieces.json")
    json.dump(scene, open(scene_path, "w"), indent=1)

    renders = {}
    for name, extra in (("proxy", []), ("own", ["-P", own])):
        wav = os.path.join(a.out, f"{name}.wav")
        r = subprocess.run([f"{a.bin}/clatter-synth", "-i", scene_path, "-b", a.proxies, *extra, "-o", wav, "--rate", "48000"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"clatter-synth ({name}): {r.stderr.strip()}")
        print(f"{name}: " + " | ".join(line for line in (r.stdout + r.stderr).splitlines() if "own PAN" in line or "PAN" in line)[:300])
        renders[name] = read_wav(wav)
    rate, proxy = renders["proxy"]
    _, reference = renders["own"]

    rows = []  # (piece, listener, error, reference L2)
    for i in range(len(pieces)):
        k0, k1 = int(rate * (0.01 + SPACING_S * i - 0.005)), int(rate * (0.01 + SPACING_S * (i + 1) - 0.005))
        for l in range(len(LISTENERS_M)):
            ref, got = reference[k0:k1, l], proxy[k0:k1, l]
            norm = math.sqrt(float((ref ** 2).sum()))
            rows.append((i, l, math.sqrt(float(((got - ref) ** 2).sum())) / norm if norm > 0 else float("nan"), norm))
    errors = np.array([r[2] for r in rows])
    print(f"{len(pieces)} pieces x {len(LISTENERS_M)} listeners: proxy against the piece's own PAN, relative L2: "
          f"median {100 * np.nanmedian(errors):.1f} %, 90th percentile {100 * np.nanpercentile(errors, 90):.1f} %, "
          f"worst {100 * np.nanmax(errors):.1f} %")
    for i in range(len(pieces)):
        e = [r[2] for r in rows if r[0] == i]
        print(f"  piece {i + 1} ({os.path.basename(meshes[i])}, {pieces[i]['mass_kg'] * 1e3:.2f} g): "
              + " ".join(f"{100 * x:5.1f}" for x in e) + " %")
    with open(os.path.join(a.out, "proxy-validation.csv"), "w") as f:
        f.write("piece,mesh,listener,relative_l2,own_l2_pa_s\n")
        for i, l, e, n in rows:
            f.write(f"{i + 1},{os.path.basename(meshes[i])},{l + 1},{e:.6g},{n / math.sqrt(rate):.6g}\n")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (h, c) = plt.subplots(1, 2, figsize=(10, 4))
    h.hist(100 * errors, bins=20, color="tab:blue")
    h.set_xlabel("proxy vs own PAN, relative L2 [%]")
    h.set_ylabel("piece x listener pairs")
    s = np.sort(100 * errors)
    c.plot(s, np.arange(1, len(s) + 1) / len(s), drawstyle="steps-post")
    c.set_xlabel("relative L2 [%]")
    c.set_ylabel("fraction of pairs at or below")
    c.grid(alpha=0.3)
    fig.suptitle(f"PAN proxies against the pieces' own PAN: {len(pieces)} pieces of {os.path.basename(a.scene)}, "
                 f"{len(LISTENERS_M)} listeners, " + (f"{a.contact_s * 1e3:g} ms contacts" if a.contact_s else "Hertz contacts"))
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "proxy-validation.png"), dpi=120)
    print(f"wrote {a.out}/proxy-validation.png and .csv")


if __name__ == "__main__":
    main()
