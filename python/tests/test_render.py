"""Rendering from Python against clatter-synth: the same scene, banks and options give the same
samples, bit for bit, for every source and listener (the WAV holds float32: the render's doubles
rounded once, so the arrays are compared after the same rounding); a scene built from numpy
arrays renders exactly as the file it stands for; the summary says what clatter-synth prints."""
import json
import os
import re
import subprocess
import threading
import warnings

import numpy as np
import pytest
from scipy.io import wavfile

import clatter

# The demo scene's ground made the tiny ground bank's steel (its moduli, configs/materials.toml),
# so the one scene sounds with PAN, modal and ground sources.
STEEL = {"youngs_modulus_pa": 2.0e11, "poisson_ratio": 0.29, "density_kg_m3": 7850.0}


def demo_scene(source_dir, folder):
    with open(f"{source_dir}/scenes/demo.json") as f:
        doc = json.load(f)
    # The demo's rocks ring above 20 kHz as their proxies (5-8 cm of E = 50 GPa): given base
    # frequencies inside the sphere bank's reach, every object's modes sound.
    for i, o in enumerate(doc["objects"]):
        o["base_frequency_hz"] = 2500.0 + 700.0 * i
    doc["materials"]["concrete"] = STEEL
    doc["materials"]["steel"] = doc["materials"].pop("concrete")
    doc["ground_material"] = "steel"
    path = folder / "demo.json"
    path.write_text(json.dumps(doc))
    return path, doc


def read_wav(path):
    with warnings.catch_warnings():  # libsndfile's PEAK chunk, which scipy does not read
        warnings.simplefilter("ignore", wavfile.WavFileWarning)
        rate, data = wavfile.read(path)
    return rate, data.T.reshape(-1, data.shape[0])  # (channels, samples)


def run_synth(program, args):
    done = subprocess.run([program, *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


OPTION_SETS = {
    "defaults": ({}, []),
    "every option": (dict(rate_hz=48000, max_sustained_s=0.002, proxy_above_hz=0.0, max_mode_hz=9000.0,
                          nu_tolerance=0.02, energy_rule=False, normalize=True),
                     ["--rate", "48000", "--max-sustained-s", "0.002", "--proxy-above-hz", "0", "--max-mode-hz", "9000",
                      "--nu-tolerance", "0.02", "--no-energy-rule", "--normalize"]),
}


@pytest.mark.parametrize("options", OPTION_SETS.keys())
def test_demo_scene_equals_clatter_synth_sample_for_sample(banks, synth_program, source_dir, tmp_path, options):
    kwargs, flags = OPTION_SETS[options]
    scene_path, doc = demo_scene(source_dir, tmp_path)
    wav = tmp_path / "debris.wav"
    stdout = run_synth(synth_program, ["-i", str(scene_path), "-b", banks["pan"], "-m", banks["modal"], "-g",
                                       banks["ground"], "-o", str(wav), "--stems", *flags])
    out = clatter.render(clatter.load_scene(scene_path), pan=banks["pan"], modal=banks["modal"], ground=banks["ground"],
                         **kwargs)
    assert out.sources == ["pan", "modal", "ground"]
    rate, mix = read_wav(wav)
    assert rate == out.rate_hz and mix.dtype == np.float32
    assert mix.shape == out.mix.shape == (len(doc["listeners"]), mix.shape[1])
    assert np.array_equal(out.mix.astype(np.float32), mix)
    for name in out.sources:
        _, stem = read_wav(tmp_path / f"debris.{name}.wav")
        assert np.array_equal(out.stems[name].astype(np.float32), stem), name
        assert np.abs(stem).max() > 0, f"the {name} stem is silent: the comparison would prove nothing"
    # The summary is what clatter-synth printed.
    summary = out.summary()
    impacts = int(re.search(r"clatter-synth: (\d+) impacts", stdout).group(1))
    assert summary["impacts"] == impacts and summary["events"] == len(doc["events"])
    for name in out.sources:
        printed = float(re.search(rf"clatter-synth: {name}\s+peak (\S+) Pa", stdout).group(1))
        assert summary["levels"][name]["peak_pa"] == pytest.approx(printed, rel=1e-3)
    modes = int(re.search(r"modal: \d+ objects, (\d+) modes rendered", stdout).group(1))
    assert summary["modal"]["modes"] == modes
    grounds = int(re.search(r"ground: (\d+) impacts on 'steel'", stdout).group(1))
    assert summary["ground"]["impacts"] == grounds > 0
    if kwargs.get("normalize"):
        assert out.gain == pytest.approx(0.99 / out.peak_pa) and np.abs(out.mix).max() == pytest.approx(0.99)


def scene_from_columns(doc):
    """The demo scene's events as the columns clatter.Scene takes."""
    ev = doc["events"]
    pair = [e["b"] not in ("ground", "fracture") for e in ev]
    return dict(
        t_s=np.array([e["t_s"] for e in ev]), a=np.array([e["a"] for e in ev]),
        b=np.array([e["b"] if p else 0 for e, p in zip(ev, pair)]),
        point_m=np.array([e["point_m"] for e in ev]), impulse_n_s=np.array([e["impulse_n_s"] for e in ev]),
        normal_speed_m_s=np.array([e.get("normal_speed_m_s", 1.0) for e in ev]),
        position_a_m=np.array([e["pose_a"]["position_m"] for e in ev]),
        orientation_a_wxyz=np.array([e["pose_a"]["orientation_wxyz"] for e in ev]),
        position_b_m=np.array([e["pose_b"]["position_m"] if p else [0, 0, 0] for e, p in zip(ev, pair)]),
        orientation_b_wxyz=np.array([e["pose_b"]["orientation_wxyz"] if p else [1, 0, 0, 0] for e, p in zip(ev, pair)]))


def test_a_scene_built_from_numpy_renders_as_its_file(banks, source_dir, tmp_path):
    scene_path, doc = demo_scene(source_dir, tmp_path)
    built = clatter.Scene(doc["materials"], doc["objects"], scene_from_columns(doc),
                          listeners_m=[l["position_m"] for l in doc["listeners"]], ground_material="steel",
                          duration_s=doc.get("duration_s"))
    loaded = clatter.load_scene(scene_path)
    assert len(built) == len(loaded) == len(doc["events"])
    assert np.array_equal(built.events["impulse_n_s"], loaded.events["impulse_n_s"])
    a = clatter.render(built, pan=banks["pan"], modal=banks["modal"], ground=banks["ground"])
    b = clatter.render(loaded, pan=clatter.open_bank(banks["pan"]), modal=[banks["modal"]], ground=banks["ground"])
    for name in a.sources:
        assert np.array_equal(a.stems[name], b.stems[name]), name
    # Written as a file and read back (what clatter-synth -i would read), it renders the same.
    built.write(tmp_path / "built.json")
    assert np.array_equal(clatter.render(clatter.load_scene(tmp_path / "built.json"), pan=banks["pan"]).mix,
                          clatter.render(built, pan=banks["pan"]).mix)
    # Linearity of every source in the impulse (PAN eq. 15, the modes, Lamb's problem), with the
    # contact times held: the speeds stay, so Hertz's tau does; twice the impulse, twice the sound.
    columns = scene_from_columns(doc)
    columns["impulse_n_s"] = 2 * columns["impulse_n_s"]
    doubled = clatter.render(clatter.Scene(doc["materials"], doc["objects"], columns,
                                           listeners_m=[l["position_m"] for l in doc["listeners"]],
                                           ground_material="steel", duration_s=doc.get("duration_s")),
                             pan=banks["pan"], modal=banks["modal"], ground=banks["ground"])
    for name in a.sources:
        scale = np.abs(a.stems[name]).max()
        assert np.abs(doubled.stems[name] - 2 * a.stems[name]).max() < 1e-9 * scale, name


def icosahedron_obj(path, radius_m):
    """A regular icosahedron (outward-wound faces) as an OBJ file: a mesh object whose FEM is quick."""
    g = (1 + 5**0.5) / 2
    v = np.array([[-1, g, 0], [1, g, 0], [-1, -g, 0], [1, -g, 0], [0, -1, g], [0, 1, g], [0, -1, -g], [0, 1, -g],
                  [g, 0, -1], [g, 0, 1], [-g, 0, -1], [-g, 0, 1]], float)
    v *= radius_m / np.linalg.norm(v[0])
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7),
         (9, 8, 1)]
    path.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in v) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in f))
    return path


def mesh_scene(mesh, path):
    doc = {"format": "clatter-scene", "format_version": 1,
           "materials": {"rock": {"youngs_modulus_pa": 5e10, "poisson_ratio": 0.2,
                                  "rayleigh_alpha_1_s": 6.0, "rayleigh_beta_s": 1e-7}},
           "ground_material": "rock",
           "objects": [{"id": 1, "mesh": os.path.abspath(mesh), "density_kg_m3": 2600.0, "material": "rock"}],
           "events": [{"t_s": 0.01 + 0.02 * i, "a": 1, "b": "ground", "point_m": [0.0, 0.0, -0.08],
                       "impulse_n_s": [0.1 * i, 0.0, 1.0], "normal_speed_m_s": 1.5,
                       "pose_a": {"position_m": [0.0, 0.0, 0.0], "orientation_wxyz": [1, 0, 0, 0]}} for i in range(4)],
           "listeners": [{"position_m": [1.0, 0.5, 0.6]}, {"position_m": [-2.0, 0.0, 1.0]}]}
    path.write_text(json.dumps(doc))
    return path


def test_an_object_with_its_own_pan_equals_clatter_synth(banks, synth_program, tmp_path):
    """The pebble given by its mesh (mass properties from the mesh) with its own PAN entry (-P)."""
    path = mesh_scene(banks["pebble_obj"], tmp_path / "pebble.json")
    wav = tmp_path / "pebble.wav"
    stdout = run_synth(synth_program, ["-i", str(path), "-P", banks["pebble_pan"], "-o", str(wav)])
    assert "1 of 1 objects sound with their own PAN" in stdout
    out = clatter.render(clatter.load_scene(path), object_pan=[banks["pebble_pan"]])
    assert out.summary()["pan"]["own_entries"] == 1
    _, mix = read_wav(wav)
    assert np.abs(mix).max() > 0 and np.array_equal(out.mix.astype(np.float32), mix)


def test_a_mesh_object_rings_at_its_mesh_s_frequency_as_in_clatter_synth(banks, synth_program, tmp_path):
    """An icosahedron's modes scaled to the base frequency of its mesh's FEM, which clatter-synth
    computes at load for modal sound and the module at the first modal render."""
    path = mesh_scene(icosahedron_obj(tmp_path / "ico.obj", 0.1), tmp_path / "ico.json")
    wav = tmp_path / "ico.wav"
    run_synth(synth_program, ["-i", str(path), "-m", banks["modal"], "-o", str(wav)])
    scene = clatter.load_scene(path)
    assert scene.objects[0]["base_frequency_hz"] == 0  # not yet: no modal render so far
    out = clatter.render(scene, modal=banks["modal"])
    assert out.summary()["modal"]["base_frequency_from"]["mesh"] == 1
    f0 = scene.objects[0]["base_frequency_hz"]
    assert f0 > 0 and out.voices()[0]["base_frequency_hz"] == f0
    _, mix = read_wav(wav)
    assert np.abs(mix).max() > 0 and np.array_equal(out.mix.astype(np.float32), mix)
    again = clatter.render(scene, modal=banks["modal"])  # the frequency kept, the same samples
    assert np.array_equal(again.mix, out.mix)
    # Written out (its OBJ beside it, its base frequency now given), clatter-synth renders it alike.
    scene.write(tmp_path / "written.json")
    assert len(list((tmp_path / "written.meshes").glob("*.obj"))) == 1
    run_synth(synth_program, ["-i", str(tmp_path / "written.json"), "-m", banks["modal"], "-o", str(tmp_path / "written.wav")])
    assert np.array_equal(out.mix.astype(np.float32), read_wav(tmp_path / "written.wav")[1])


def test_write_wav_writes_what_clatter_synth_writes(banks, synth_program, source_dir, tmp_path):
    scene_path, _ = demo_scene(source_dir, tmp_path)
    run_synth(synth_program, ["-i", str(scene_path), "-b", banks["pan"], "-o", str(tmp_path / "cli.wav"),
                              "--format", "pcm24", "--normalize"])
    out = clatter.render(clatter.load_scene(scene_path), pan=banks["pan"], normalize=True)
    assert out.write_wav(tmp_path / "py.wav", format="pcm24") == [str(tmp_path / "py.wav")]
    cli = read_wav(tmp_path / "cli.wav")[1]
    py = read_wav(tmp_path / "py.wav")[1]
    assert cli.dtype == py.dtype and np.array_equal(cli, py) and np.abs(py).max() > 0


def test_an_object_with_its_own_modal_model_equals_clatter_synth(banks, synth_program, tmp_path):
    """The glass bar of the object bank (-O) rings with its own model (its base frequency is below
    --proxy-above-hz), struck at the middle of its underside."""
    doc = {"format": "clatter-scene", "format_version": 1,
           "materials": {"glass": {"youngs_modulus_pa": 6.2e10, "poisson_ratio": 0.2,
                                   "rayleigh_alpha_1_s": 1.0, "rayleigh_beta_s": 1e-7}},
           "ground_material": "glass",
           "objects": [{"id": 1, "mesh": os.path.abspath(banks["object_obj"]), "density_kg_m3": 2600.0, "material": "glass"}],
           "events": [{"t_s": 0.01, "a": 1, "b": "ground", "point_m": [0.0, 0.0, 0.0], "impulse_n_s": [0.0, 0.0, 0.01],
                       "normal_speed_m_s": 1.0,
                       "pose_a": {"position_m": [0.0, 0.0, 0.005], "orientation_wxyz": [1, 0, 0, 0]}}],
           "listeners": [{"position_m": [0.0, 0.5, 0.5]}], "duration_s": 0.3}
    path = tmp_path / "bar.json"
    path.write_text(json.dumps(doc))
    wav = tmp_path / "bar.wav"
    stdout = run_synth(synth_program, ["-i", str(path), "-O", banks["object"], "-m", banks["modal"], "-o", str(wav)])
    assert "1 objects ring with their own model" in stdout
    out = clatter.render(clatter.load_scene(path), objects=[clatter.open_bank(banks["object"])], modal=banks["modal"])
    assert out.summary()["modal"]["own_models"] == 1 and out.voices()[0]["voiced_by"] == "own"
    _, mix = read_wav(wav)
    assert np.abs(mix).max() > 0 and np.array_equal(out.mix.astype(np.float32), mix)


def test_renders_in_threads_agree_with_one_alone(banks, source_dir, tmp_path):
    """Python threads may render at once: the module runs one render (or bank read) at a time with
    the GIL released (the stage log and the serial HDF5 serve one thread), so nothing races and
    every thread gets the samples of a render alone."""
    scene_path, _ = demo_scene(source_dir, tmp_path)
    sources = dict(pan=banks["pan"], modal=banks["modal"], ground=banks["ground"])
    alone = clatter.render(clatter.load_scene(scene_path), **sources).mix
    results, errors = [], []

    def work():
        try:
            scene = clatter.load_scene(scene_path)
            for _ in range(3):
                results.append(clatter.render(scene, **sources).mix)
                assert len(clatter.open_bank(banks["modal"])) == 1 and scene.objects[0]["id"] == 1
        except Exception as e:  # reported below: an exception in a thread does not fail the test itself
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    assert len(results) == 12 and all(np.array_equal(r, alone) for r in results)
