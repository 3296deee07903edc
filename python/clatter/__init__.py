"""Clatter from Python: soundbanks and the synthesizer (docs/python.md).

    import clatter
    scene = clatter.load_scene("scenes/demo.json")
    out = clatter.render(scene, pan="bank.h5", modal="modal.h5")
    out.mix          # (listeners, samples) float64 pascals, as clatter-synth's WAV
    out.stems["pan"] # one source

Everything runs in the compiled part, `clatter._clatter`, on the code clatter-synth runs: the same
scene reader, the same banks' readers and the same render, so the same options give the same
samples. Bad input raises clatter.InputError (a ValueError) naming the argument, with the message
clatter-synth would print.
"""
import math
import json
import os

import numpy as np

from clatter._clatter import (InputError, PanBank, ModalBank, ObjectBank, GroundBank, SceneData,
                              SynthOptions, fit_proxy, fit_proxy_to_mesh, read_mesh, stage_table, version)
from clatter import _clatter

__all__ = ["InputError", "open_bank", "PanBank", "ModalBank", "ObjectBank", "GroundBank", "Scene",
           "load_scene", "render", "Render", "fit_proxy", "fit_proxy_to_mesh", "read_mesh", "stage_table", "version"]

_BANK_NAMES = {"pan": "a PAN bank", "modal": "a modal bank", "object": "an object bank", "ground": "a ground bank"}


def open_bank(path, kind=None):
    """A bank file, read and checked as clatter-synth reads it: a PanBank, ModalBank, ObjectBank or
    GroundBank by its format; with kind ('pan', 'modal', 'object', 'ground') an InputError unless it
    is one. Its arrays are read-only views of the bank's memory."""
    return _clatter.open_bank(os.fspath(path), kind or "")


def load_scene(path, impulses=None):
    """A scene file (docs/scene-format.md) as clatter-synth -i reads it; with impulses, path is the
    side file of a James-lab impulse file (clatter-synth --impulses)."""
    return Scene._wrap(_clatter._load_scene(os.fspath(path), "" if impulses is None else os.fspath(impulses)))


def _column(events, key, n, width=None, dtype=float, required=True):
    """events[key] as an array of n rows (of `width`), checked: shape and finite."""
    if key not in events:
        if required:
            raise InputError(f"events: no '{key}' column")
        return None
    try:
        a = np.asarray(events[key], dtype=float)
    except (TypeError, ValueError) as e:
        raise InputError(f"events['{key}']: {e}") from None
    shape = (n,) if width is None else (n, width)
    if a.shape != shape:
        raise InputError(f"events['{key}']: shape {a.shape}, expected {shape}")
    if not np.all(np.isfinite(a)):
        row = int(np.argwhere(~np.isfinite(a))[0][0])
        raise InputError(f"events['{key}'][{row}]: {a[row]} is not finite")
    if dtype is not float:  # object ids: whole numbers, never silently truncated
        if not np.array_equal(a, np.round(a)):
            row = int(np.argwhere(a != np.round(a))[0][0])
            raise InputError(f"events['{key}'][{row}]: {a[row]} is not an object id")
        return a.astype(np.int64)
    return a


def _plain(value, where):
    """A JSON-ready copy of a dict/list/array value, refusing NaN and infinities by name."""
    if isinstance(value, dict):
        return {k: _plain(v, f"{where}['{k}']") for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v, f"{where}[{i}]") for i, v in enumerate(np.asarray(value, dtype=object).tolist()
                                                                   if isinstance(value, np.ndarray) else value)]
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        if not math.isfinite(value):
            raise InputError(f"{where}: {value} is not finite")
        return float(value)
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def _events_json(events):
    """The event columns as the scene format's event list (docs/python.md "Scenes")."""
    if not isinstance(events, dict):
        raise InputError("events: expected a dict of columns (t_s, a, b, point_m, impulse_n_s, ...)")
    n = np.asarray(events.get("t_s", [])).shape[0] if np.ndim(events.get("t_s", [])) == 1 else -1
    if n < 0:
        raise InputError("events['t_s']: expected a 1-D array of times")
    t = _column(events, "t_s", n)
    a = _column(events, "a", n, dtype=np.int64)
    b = _column(events, "b", n, dtype=np.int64)
    point = _column(events, "point_m", n, 3)
    impulse = _column(events, "impulse_n_s", n, 3)
    speed = _column(events, "normal_speed_m_s", n, required=False)
    contact = _column(events, "contact_time_s", n, required=False)
    pos_a = _column(events, "position_a_m", n, 3)
    rot_a = _column(events, "orientation_a_wxyz", n, 4, required=False)
    pos_b = _column(events, "position_b_m", n, 3, required=False)
    rot_b = _column(events, "orientation_b_wxyz", n, 4, required=False)
    kind = events.get("kind")
    if kind is not None:
        kind = list(kind)
        if len(kind) != n:
            raise InputError(f"events['kind']: {len(kind)} entries, expected {n}")
        for i, k in enumerate(kind):
            if k not in ("contact", "sustained", "fracture"):
                raise InputError(f"events['kind'][{i}]: '{k}': expected 'contact', 'sustained' or 'fracture'")
    identity = [1.0, 0.0, 0.0, 0.0]
    out = []
    for i in range(n):
        k = "contact" if kind is None else kind[i]
        if k == "contact" and speed is None:
            raise InputError("events: a contact needs the 'normal_speed_m_s' column")
        if k != "contact" and contact is None:
            raise InputError(f"events['kind'][{i}]: a {k} event needs the 'contact_time_s' column")
        e = {"t_s": float(t[i]), "a": int(a[i]),
             "b": "fracture" if k == "fracture" else ("ground" if b[i] == 0 else int(b[i])),
             "point_m": point[i].tolist(), "impulse_n_s": impulse[i].tolist(),
             "pose_a": {"position_m": pos_a[i].tolist(),
                        "orientation_wxyz": identity if rot_a is None else rot_a[i].tolist()}}
        if k == "contact":
            e["normal_speed_m_s"] = float(speed[i])
        else:
            e["contact_time_s"] = float(contact[i])
        if b[i] != 0 and k != "fracture":
            if pos_b is None:
                raise InputError(f"events['b'][{i}]: a pair needs the 'position_b_m' column")
            e["pose_b"] = {"position_m": pos_b[i].tolist(),
                           "orientation_wxyz": identity if rot_b is None else rot_b[i].tolist()}
        out.append(e)
    return out


class Scene:
    """A scene for rendering: objects, materials, impulses and listeners.

    Scene(materials, objects, events, listeners_m, ground_material, duration_s=None) builds one
    from Python values; load_scene reads a file. materials and objects take the keys of the scene
    format (docs/scene-format.md); events are columns of numpy arrays (docs/python.md "Scenes"):
    t_s (n,), a and b (n,) object ids (b = 0: the ground), point_m and impulse_n_s (n, 3),
    normal_speed_m_s (n,), position_a_m (n, 3), and optionally orientation_a_wxyz (n, 4) (default
    identity), position_b_m / orientation_b_wxyz for pairs, kind (n,) of 'contact', 'sustained' or
    'fracture' with contact_time_s (n,). The scene is checked by clatter-synth's reader; its
    messages name the argument (objects[2].material, events[5], ...).
    """

    def __init__(self, materials, objects, events, listeners_m, ground_material, duration_s=None,
                 name="Scene"):
        listeners = np.asarray(listeners_m, dtype=float)
        if listeners.ndim != 2 or listeners.shape[1] != 3 or listeners.shape[0] < 1:
            raise InputError(f"listeners_m: shape {listeners.shape}, expected (n, 3) with n >= 1")
        if not np.all(np.isfinite(listeners)):
            raise InputError(f"listeners_m[{int(np.argwhere(~np.isfinite(listeners))[0][0])}]: not finite")
        if not isinstance(materials, dict):
            raise InputError("materials: expected a dict of named materials")
        if not isinstance(objects, (list, tuple)):
            raise InputError("objects: expected a list of dicts (one per object)")
        doc = {"format": "clatter-scene", "format_version": 1,
               "materials": _plain(materials, "materials"), "ground_material": ground_material,
               "objects": _plain(list(objects), "objects"), "events": _events_json(events),
               "listeners": [{"position_m": p} for p in listeners.tolist()]}
        if duration_s is not None:
            doc["duration_s"] = _plain(float(duration_s), "duration_s")
        # json writes floats shortest round-trip: the reader gets the very doubles given here.
        self._data = _clatter._parse_scene(json.dumps(doc), name)

    @classmethod
    def _wrap(cls, data):
        scene = cls.__new__(cls)
        scene._data = data
        return scene

    path = property(lambda self: self._data.path)
    duration_s = property(lambda self: self._data.duration_s, doc="0: until the last event plus 0.1 s")
    ground_material = property(lambda self: self._data.ground_material)
    materials = property(lambda self: self._data.materials)
    objects = property(lambda self: self._data.objects, doc="one dict per object, mass properties resolved")
    listeners_m = property(lambda self: self._data.listeners_m, doc="(listeners, 3), read-only")
    events = property(lambda self: self._data.events, doc="the events as columns (t_s, a, b, kind, ...)")

    def __len__(self):
        return len(self._data)

    def write(self, path):
        """The scene as a file clatter-synth -i reads (docs/scene-format.md): every number as read,
        objects given by meshes written with their OBJ beside it (PATH's .meshes folder)."""
        self._data.write(os.fspath(path))

    def __repr__(self):
        return (f"<clatter.Scene '{self.path}': {len(self.objects)} objects, {len(self)} events, "
                f"{len(self.listeners_m)} listeners>")


def _bank_paths(value, kind, argument, many):
    """Paths of the banks given as paths or opened banks, each checked to be of `kind`."""
    if value is None:
        return [] if many else ""
    items = list(value) if many and isinstance(value, (list, tuple)) else [value]
    if not many and len(items) != 1:
        raise InputError(f"{argument}: one bank expected")
    paths = []
    for item in items:
        path = item.path if hasattr(item, "path") and hasattr(item, "kind") else item
        try:
            path = os.fspath(path)
        except TypeError:
            raise InputError(f"{argument}: {item!r} is neither a path nor an opened bank") from None
        if not os.path.isfile(path):
            raise InputError(f"{argument}: {path}: no such file")
        try:
            found = _clatter._bank_kind(path)
        except InputError as e:
            raise InputError(f"{argument}: {e}") from None
        if found != kind:
            what = _BANK_NAMES.get(found, "not a Clatter bank")
            raise InputError(f"{argument}: {path} is {what}, expected {_BANK_NAMES[kind]}")
        paths.append(path)
    return paths if many else paths[0]


def _number(value, argument, low=None, above=None):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{argument}: {value!r} is not a number") from None
    if not math.isfinite(v):
        raise InputError(f"{argument}: {v} is not finite")
    if low is not None and v < low:
        raise InputError(f"{argument}: {v}: must be >= {low}")
    if above is not None and not v > above:
        raise InputError(f"{argument}: {v}: must be > {above}")
    return v


class Render:
    """A finished render: mix and stems as (listeners, samples) float64 arrays in pascals (times
    gain with normalize), the summary and coverage clatter-synth prints, and write_wav."""

    def __init__(self, data, scene):
        self._data = data
        self._scene = scene
        self.mix = data.mix()
        self.stems = {name: data.stem(i) for i, name in enumerate(data.sources)}

    rate_hz = property(lambda self: self._data.rate_hz)
    gain = property(lambda self: self._data.gain, doc="the factor on every sample (normalize: 0.99 / peak)")
    peak_pa = property(lambda self: self._data.peak_pa, doc="the mix's peak before the gain")
    sources = property(lambda self: self._data.sources)
    stages_s = property(lambda self: self._data.stages_s,
                        doc="this render's wall time per stage (banks, render, render/event), as --log-view's rows")
    coverage = property(lambda self: self._data.coverage,
                        doc="per source, one line per object outside its bank's coverage (docs/synth.md)")

    def summary(self):
        """clatter-synth's summary as a dict (impacts, levels, modal, ground, ...)."""
        return self._data.summary()

    def voices(self):
        """One dict per object: how the modal source voiced it (clatter-synth --voices)."""
        return self._data.voices(self._scene._data)

    def write_wav(self, path, format="float", stems=False):
        """The mix (and with stems, PATH.SOURCE.wav per source) as clatter-synth writes them."""
        return self._data.write_wav(os.fspath(path), format, stems)


def render(scene, pan=None, object_pan=None, modal=None, objects=None, ground=None, rate_hz=44100,
           max_sustained_s=0.01, proxy_above_hz=2000.0, max_mode_hz=20000.0, nu_tolerance=0.015,
           energy_rule=True, normalize=False):
    """Renders a scene with any set of banks, as clatter-synth does with the same options:

    pan (-b), object_pan (-P, a list), modal (-m, a list: one per nu class), objects (-O, a list),
    ground (-g): paths or opened banks; rate_hz (--rate), max_sustained_s (--max-sustained-s),
    proxy_above_hz (--proxy-above-hz), max_mode_hz (--max-mode-hz), nu_tolerance (--nu-tolerance),
    energy_rule (False: --no-energy-rule), normalize (--normalize). Returns a Render.
    """
    if not isinstance(scene, Scene):
        raise InputError(f"scene: expected a clatter.Scene (clatter.Scene(...) or clatter.load_scene), "
                         f"not {type(scene).__name__}")
    o = SynthOptions()
    o.pan_bank = _bank_paths(pan, "pan", "pan", False)
    o.object_pans = _bank_paths(object_pan, "pan", "object_pan", True)
    o.modal_banks = _bank_paths(modal, "modal", "modal", True)
    o.object_banks = _bank_paths(objects, "object", "objects", True)
    o.ground_bank = _bank_paths(ground, "ground", "ground", False)
    if isinstance(rate_hz, bool) or not float(rate_hz).is_integer():
        raise InputError(f"rate_hz: {rate_hz!r}: expected a whole number of Hz")
    rate = int(_number(rate_hz, "rate_hz"))
    if not 8000 <= rate <= 384000:
        raise InputError(f"rate_hz: {rate}: must be in [8000, 384000] Hz")
    o.rate_hz = rate
    o.max_sustained_s = _number(max_sustained_s, "max_sustained_s", low=0)
    o.proxy_above_hz = _number(proxy_above_hz, "proxy_above_hz", low=0)
    o.max_mode_hz = _number(max_mode_hz, "max_mode_hz", above=0)
    o.nu_tolerance = _number(nu_tolerance, "nu_tolerance", low=0)
    o.energy_rule = bool(energy_rule)
    return Render(_clatter._render(scene._data, o, bool(normalize)), scene)
