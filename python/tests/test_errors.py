"""Bad input from Python raises clatter.InputError (a ValueError) naming the argument, with the
words clatter-synth uses; nothing crashes the interpreter."""
import json

import numpy as np
import pytest

import clatter

MATERIALS = {"rock": {"youngs_modulus_pa": 5e10, "poisson_ratio": 0.2, "rayleigh_alpha_1_s": 6.0, "rayleigh_beta_s": 1e-7}}
OBJECTS = [{"id": 1, "mass_kg": 0.5, "volume_m3": 2e-4, "inertia_kg_m2": np.diag([1e-4, 1.2e-4, 1.5e-4]), "material": "rock"}]


def events(n=3, **change):
    e = dict(t_s=np.linspace(0.01, 0.1, n), a=np.ones(n, int), b=np.zeros(n, int), point_m=np.zeros((n, 3)),
             impulse_n_s=np.tile([0.0, 0.0, 0.5], (n, 1)), normal_speed_m_s=np.full(n, 2.0),
             position_a_m=np.tile([0.0, 0.0, 0.05], (n, 1)))
    e.update(change)
    return e


def scene(**change):
    args = dict(materials=MATERIALS, objects=OBJECTS, events=events(), listeners_m=[[0, 1, 0.5]], ground_material="rock")
    args.update(change)
    return clatter.Scene(**args)


def raises(match, call, *args, **kwargs):
    with pytest.raises(clatter.InputError, match=match):
        call(*args, **kwargs)


def test_input_error_is_a_value_error():
    assert issubclass(clatter.InputError, ValueError)


def test_scene_arguments_are_named():
    assert len(scene()) == 3
    raises(r"listeners_m: shape \(1, 2\)", scene, listeners_m=[[0, 1]])
    raises(r"listeners_m\[0\]: not finite", scene, listeners_m=[[0, np.nan, 1]])
    raises(r"events\['point_m'\]: shape \(3, 2\), expected \(3, 3\)", scene, events=events(point_m=np.zeros((3, 2))))
    bad = events()
    bad["impulse_n_s"][1, 2] = np.nan
    raises(r"events\['impulse_n_s'\]\[1\]", scene, events=bad)
    raises(r"events\['a'\]\[0\]: 1.5 is not an object id", scene, events=events(a=np.full(3, 1.5)))
    raises(r"events\['t_s'\]: could not convert", scene, events=events(t_s=["soon", "later", "never"]))
    raises(r"events: no 'position_a_m' column", scene, events={k: v for k, v in events().items() if k != "position_a_m"})
    raises(r"events\['kind'\]\[0\]: 'bounce'", scene, events=events(kind=["bounce"] * 3))
    raises(r"objects\[0\]\['mass_kg'\]: nan is not finite", scene, objects=[dict(OBJECTS[0], mass_kg=float("nan"))])
    # The scene reader's own checks, with its words and the argument's path in them.
    raises(r"Scene: objects\[0\]\.material: \"granite\" is not in materials", scene, objects=[dict(OBJECTS[0], material="granite")])
    raises(r"ground_material: \"lava\" is not in materials", scene, ground_material="lava")
    raises(r"events\[1\]: time .* before the previous event", scene, events=events(t_s=np.array([0.1, 0.05, 0.2])))


def test_render_arguments_are_named(banks, tmp_path):
    s = scene()
    raises(r"scene: expected a clatter.Scene", clatter.render, "scenes/demo.json", pan=banks["pan"])
    raises(r"pan: .* is a modal bank, expected a PAN bank", clatter.render, s, pan=banks["modal"])
    raises(r"modal: .* is a ground bank, expected a modal bank", clatter.render, s, modal=[banks["ground"]])
    raises(r"ground: .* is a PAN bank, expected a ground bank", clatter.render, s, ground=banks["pan"])
    raises(r"objects: .* is a modal bank, expected an object bank", clatter.render, s, objects=banks["modal"])
    raises(r"pan: .*nowhere.h5: no such file", clatter.render, s, pan=tmp_path / "nowhere.h5")
    text = tmp_path / "text.h5"
    text.write_text("not HDF5")
    raises(r"pan: .*text.h5", clatter.render, s, pan=text)
    raises(r"rate_hz: 100: must be in \[8000, 384000\] Hz", clatter.render, s, pan=banks["pan"], rate_hz=100)
    raises(r"rate_hz: 44100.5", clatter.render, s, pan=banks["pan"], rate_hz=44100.5)
    raises(r"max_mode_hz: nan is not finite", clatter.render, s, pan=banks["pan"], max_mode_hz=float("nan"))
    raises(r"max_sustained_s: -1.0: must be >= 0", clatter.render, s, pan=banks["pan"], max_sustained_s=-1)
    raises(r"give a PAN bank", clatter.render, s)
    # A material modal sound cannot ring (no damping): clatter-synth's message, naming the material.
    no_damping = {"rock": {"youngs_modulus_pa": 5e10, "poisson_ratio": 0.2}}
    raises(r"Scene: materials\.rock: modal sound needs rayleigh_alpha_1_s", clatter.render, scene(materials=no_damping),
           modal=banks["modal"])
    # An inertia no rigid body has (5e-4 > 1e-4 + 1e-4): the render's check, naming the object.
    raises(r"Scene: object 1: inertia_kg_m2: inertia violates", clatter.render, scene(objects=[dict(OBJECTS[0], inertia_kg_m2=np.diag([1e-4, 1e-4, 5e-4]))]),
           pan=banks["pan"])
    # A listener inside an object: the render's own check, naming the scene's listener.
    raises(r"listener", clatter.render, scene(listeners_m=[[0, 0, 0.05]]), pan=banks["pan"])


def test_bank_arguments_are_named(banks, tmp_path):
    pan = clatter.open_bank(banks["pan"])
    raises(r"a modal bank \('clatter-modal-bank'\), expected a pan bank", clatter.open_bank, banks["modal"], kind="pan")
    text = tmp_path / "scene.json"
    text.write_text(json.dumps({"format": "clatter-scene"}))
    with pytest.raises((clatter.InputError, RuntimeError), match="scene.json"):
        clatter.open_bank(text)
    raises(r"points: shape \(2, 2\)", pan.probe, 0, 1, np.zeros((2, 2)))
    raises(r"points\[1\]: nan is not a finite coordinate", pan.probe, 0, 1, [[3, 0, 0], [np.nan, 0, 0]])
    raises(r"points\[0\]: .* inside the entry's bounding sphere", pan.probe, 0, 1, [[0.1, 0, 0]])
    raises(r"field: 5 was not solved", pan.probe, 0, 5, [[3, 0, 0]])
    raises(r"field: 7 is not in 1-6", pan.probe, 0, 7, [[3, 0, 0]])
    raises(r"scale: -1: must be > 0", pan.probe, 0, 1, [[3, 0, 0]], scale=-1)
    raises(r"interpolation: 'cubic'", pan.probe, 0, 1, [[3, 0, 0]], interpolation="cubic")
    with pytest.raises(IndexError, match="entry 9"):
        pan[9]
    modal = clatter.open_bank(banks["modal"])
    raises(r"points\[0\]: .* the transfer holds from", modal.probe, 0, [[0.1, 0, 0]])
    raises(r"inertia_kg_m2: expected a 3x3 matrix", clatter.fit_proxy, np.eye(2), 1.0, 1.0)
    raises(r"mass_kg: -1: must be > 0", clatter.fit_proxy, np.eye(3), -1.0, 1.0)
    raises(r"inertia_kg_m2: .*", clatter.fit_proxy, np.diag([1.0, 1.0, 5.0]), 1.0, 1.0)
    raises(r"triangles\[0\]\[2\]: 9 is not a vertex index", clatter.fit_proxy_to_mesh, np.zeros((4, 3)),
           [[0, 1, 9], [0, 1, 2], [0, 2, 3], [1, 2, 3]], 1000.0)
