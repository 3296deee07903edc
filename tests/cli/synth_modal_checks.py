#!/usr/bin/env python3
"""clatter-synth's modal sound end to end (docs/synth.md "Modal sound"), on a modal bank of the
sphere alone (the synth_modal_bank fixture) and a PAN bank:
- a glass sphere (the bank's material) struck a few times rings at the bank's frequencies scaled
  by gamma = a_object / a_bank: every spectral peak of 1 s of its sound lies within one FFT bin
  (1 Hz) of one of them, and the peaks cover the spheroidal multiplets a normal force excites;
- PAN and modal together: the mix is the sum of the stems OUT.pan.wav and OUT.modal.wav, and the
  summary names each source's peak and RMS;
- a modal bank of the wrong version: exit 2, one line naming the file and version, no WAV.
Usage: synth_modal_checks.py CLATTER_SYNTH MODAL_BANK PAN_BANK SCRATCH"""
import json, math, os, shutil, subprocess, sys
import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, start  # noqa: E402
from synth_wav import wav  # noqa: E402

synth, modal_bank, pan_bank, scratch = sys.argv[1:5]
start(scratch)


def sphere_scene(radius, directions, duration, beta_s=1e-7):
    volume = 4 / 3 * math.pi * radius ** 3
    mass = 2600 * volume
    moment = 0.4 * mass * radius ** 2
    events = []
    for k, d in enumerate(directions):
        n = np.array(d) / np.linalg.norm(d)
        events.append({"t_s": 0.01 + 0.005 * k, "a": 1, "b": "fracture", "contact_time_s": 1e-4,
                       "point_m": list(-radius * n), "impulse_n_s": list(0.01 * n),
                       "pose_a": {"position_m": [0, 0, 0], "orientation_wxyz": [1, 0, 0, 0]}})
    return {"format": "clatter-scene", "format_version": 1,
            "materials": {"glass": {"youngs_modulus_pa": 6.2e10, "poisson_ratio": 0.2,
                                    "rayleigh_alpha_1_s": 1.0, "rayleigh_beta_s": beta_s}},
            "ground_material": "glass",
            "objects": [{"id": 1, "mass_kg": mass, "volume_m3": volume, "material": "glass",
                         "inertia_kg_m2": [[moment, 0, 0], [0, moment, 0], [0, 0, moment]]}],
            "events": events, "listeners": [{"position_m": [1.0, 2.0, 2.0]}], "duration_s": duration}


# ---- the sphere's spectrum
with h5py.File(modal_bank, "r") as f:
    entry = f["entries"][sorted(f["entries"].keys())[0]]
    f_bank = entry["frequencies_hz"][()]
    cluster = entry["cluster"][()]
    a_bank = entry["axes_m"][()][0]
radius, rate = 0.3, 44100
gamma = radius / a_bank  # same material, so the proxy scale is the size ratio
expected = f_bank / gamma  # every mode: the mesh splits a multiplet by a few Hz, more than a bin
# Glass's beta would damp the modes in 30 ms (a 6 Hz wide line); 100x less keeps them ringing
# through the second, so each line is one bin wide. A Blackman-Harris window (sidelobes -92 dB)
# keeps the -60 dB threshold clear of leakage; a peak is a maximum over +-5 bins.
scene = sphere_scene(radius, [[0, 0, 1]], 1.04, beta_s=1e-9)
json.dump(scene, open("sphere.json", "w"))
r = subprocess.run([synth, "-i", "sphere.json", "-m", modal_bank, "-o", "sphere.wav"], capture_output=True, text=True)
check(r.returncode == 0, f"sphere rendered ({r.stderr.strip()})")
x = wav("sphere.wav")[:, 0]
seg = x[int(0.03 * rate):int(0.03 * rate) + rate]  # 1 s after the last strike: 1 Hz bins
u = np.arange(len(seg)) / len(seg)
window = 0.35875 - 0.48829 * np.cos(2 * np.pi * u) + 0.14128 * np.cos(4 * np.pi * u) - 0.01168 * np.cos(6 * np.pi * u)
spectrum = np.abs(np.fft.rfft(seg * window))
top = spectrum.max()
peaks = [k for k in range(5, len(spectrum) - 5)
         if spectrum[k] == spectrum[k - 5:k + 6].max() and spectrum[k] > 1e-3 * top]
bin_hz = rate / len(seg)
off = [min(abs(k * bin_hz - expected)) / bin_hz for k in peaks]
found = sorted({int(cluster[np.argmin(abs(k * bin_hz - expected))]) for k in peaks})
print(f"sphere (r = {radius} m, gamma = {gamma:.4f}): {len(peaks)} spectral peaks above -60 dB; scaled bank "
      f"frequencies (Hz): {', '.join(f'{f:.1f}' for f in expected)}")
print(f"  peaks (Hz): {', '.join(f'{k * bin_hz:.0f}' for k in peaks)}; largest distance to a bank frequency "
      f"{max(off):.2f} bins")
check(len(peaks) >= 4 and max(off) <= 1.0, "every spectral peak within one FFT bin of a scaled bank frequency")
check(len(found) >= 4, f"{len(found)} of the {len(np.unique(cluster))} multiplets found among the peaks")

# ---- PAN and modal together, stems
demo = dict(scene)
demo["events"] = [dict(e, b="ground", normal_speed_m_s=1.0) for e in scene["events"]]
for e in demo["events"]:
    del e["contact_time_s"]
demo["duration_s"] = 0.2
json.dump(demo, open("both.json", "w"))
r = subprocess.run([synth, "-i", "both.json", "-b", pan_bank, "-m", modal_bank, "-o", "both.wav", "--stems"],
                   capture_output=True, text=True)
check(r.returncode == 0, f"PAN and modal rendered ({r.stderr.strip()})")
mix, pan, mod = wav("both.wav"), wav("both.pan.wav"), wav("both.modal.wav")
dev = np.abs(mix - pan - mod).max() / np.abs(mix).max()
check(dev < 1e-6 and np.abs(pan).max() > 0 and np.abs(mod).max() > 0, f"mix = pan + modal stems (deviation {dev:.2g} of the peak)")
check("pan    peak" in r.stdout and "modal  peak" in r.stdout and "modes rendered" in r.stdout,
      "summary names each source's peak and RMS and the modes rendered")

# ---- where the base frequency comes from: a mesh object (a 0.4 x 0.3 x 0.25 m box OBJ), the same
# with base_frequency_hz given, and one given by numbers
with open("box.obj", "w") as f:
    a, b, c = 0.4, 0.3, 0.25
    for i in range(8):
        f.write(f"v {a if i & 1 else 0} {b if i & 2 else 0} {c if i & 4 else 0}\n")
    for t in [(0, 2, 3), (0, 3, 1), (4, 5, 7), (4, 7, 6), (0, 1, 5), (0, 5, 4), (2, 6, 7), (2, 7, 3), (0, 4, 6),
              (0, 6, 2), (1, 3, 7), (1, 7, 5)]:
        f.write("f " + " ".join(str(k + 1) for k in t) + "\n")
mesh_scene = json.loads(json.dumps(scene))
mesh_scene["objects"] = [{"id": 1, "mesh": "box.obj", "density_kg_m3": 2600, "material": "glass"},
                         {"id": 2, "mesh": "box.obj", "density_kg_m3": 2600, "material": "glass", "base_frequency_hz": 3000},
                         dict(scene["objects"][0], id=3)]
mesh_scene["events"] = [dict(e, a=k + 1) for k, e in enumerate(scene["events"] * 3)]
for e in mesh_scene["events"]:
    e["pose_a"] = {"position_m": [0, 0, 0], "orientation_wxyz": [1, 0, 0, 0]}
    if e["a"] != 3:  # on the boxes' bottom face: a mesh's contact is taken on its surface (docs/synth.md "Contact")
        e["point_m"] = [0, 0, -c / 2]
mesh_scene["listeners"] = [{"position_m": [2.0, 4.0, 4.0]}]
json.dump(mesh_scene, open("mesh.json", "w"))
r = subprocess.run([synth, "-i", "mesh.json", "-m", modal_bank, "-o", "mesh.wav"], capture_output=True, text=True)
check(r.returncode == 0 and "base frequency from the scene 1, the mesh 1, the proxy 1" in r.stdout,
      f"base frequencies: one from the scene, one from the mesh's FEM, one from the proxy ({r.stderr.strip()})")

# ---- a modal bank of another version
shutil.copy(modal_bank, "v1.h5")
with h5py.File("v1.h5", "r+") as f:
    f.attrs["format_version"] = np.int32(1)
r = subprocess.run([synth, "-i", "sphere.json", "-m", "v1.h5", "-o", "v1.wav"], capture_output=True, text=True)
check(r.returncode == 2 and "v1.h5" in r.stderr and "version" in r.stderr and len(r.stderr.strip().splitlines()) == 1
      and not os.path.exists("v1.wav"), f"a version-1 modal bank: exit 2, one line, no WAV ({r.stderr.strip()})")

finish("synth modal checks")
