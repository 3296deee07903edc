"""The banks from Python: each kind opened by its format, its arrays the very values h5py reads
from the file (an independent reader of docs/bank-format.md), read-only views that share the
bank's memory; probes against physics: a translating sphere is a dipole (PAN), every mode's far
field falls as 1/r (modal); proxies against the closed forms of solid ellipsoids and boxes."""
import h5py
import numpy as np
import pytest

import clatter


def test_each_kind_opens_as_its_class(banks):
    kinds = {"pan": clatter.PanBank, "modal": clatter.ModalBank, "ground": clatter.GroundBank, "pebble_pan": clatter.PanBank,
             "object": clatter.ObjectBank}
    for key, cls in kinds.items():
        bank = clatter.open_bank(banks[key])
        assert isinstance(bank, cls) and bank.path == banks[key]
        assert bank.sweep["complete"]


def test_pan_bank_arrays_are_the_file_s(banks):
    bank = clatter.open_bank(banks["pan"], kind="pan")
    with h5py.File(banks["pan"], "r") as f:
        assert bank.header["a_m"] == f["bank"].attrs["a_m"]
        assert bank.header["epsilon"] == f["bank"].attrs["epsilon"]
        assert np.array_equal(bank.header["radii_m"], f["bank/radii_m"][...])
        assert [e.b_m for e in bank] == list(f["proxies/b_m"][...]) and [e.c_m for e in bank] == list(f["proxies/c_m"][...])
    sphere = bank[0]
    assert sphere.b_m == sphere.c_m == bank.header["a_m"] and not sphere.is_mesh
    assert [sphere.solved(k) for k in range(1, 7)] == [True, True, True, False, False, False]
    field = sphere.field(1)
    points = field.lattice_points
    assert points.dtype == np.int32 and points.shape[1] == 2 and not points.flags.writeable
    d = bank.directions(0, 1)
    assert np.allclose(np.linalg.norm(d, axis=1), 1) and np.all(d >= 0)  # the positive octant
    index, values = field.terms(0)
    assert values.shape == (index.size, len(bank.header["radii_m"]) + 1) and values.dtype == np.float32


def test_a_translating_sphere_is_a_dipole(banks):
    """Field 1 of the sphere proxy (A = B = C): p(x, t) = cos(theta) g(r, t), so at one radius the
    series at 60 degrees from the x axis is half the axis series; and the far term falls as 1/r,
    so R p, time-aligned by the retarded time, is the same at 3 m and 6 m up to the near field
    (1 / (k r) at the pulse's frequencies: a few per cent)."""
    bank = clatter.open_bank(banks["pan"])
    c = np.cos(np.pi / 3)
    s = np.sin(np.pi / 3)
    probe = bank.probe(0, 1, [[3, 0, 0], [3 * c, 3 * s, 0], [3 * c, 0, 3 * s], [6, 0, 0]])
    p = probe["p"]
    axis = np.abs(p[0]).max()
    assert axis > 0
    for k in (1, 2):
        assert np.abs(p[k] - c * p[0]).max() < 0.02 * axis
    assert probe["t0_s"][3] - probe["t0_s"][0] == pytest.approx(3 / bank.header["c_m_s"], abs=probe["dt_s"])
    far = 6 * p[3]
    near = 3 * p[0]
    assert np.abs(far).max() == pytest.approx(np.abs(near).max(), rel=0.05)


def test_modal_bank_arrays_are_views_of_the_file_s_values(banks):
    bank = clatter.open_bank(banks["modal"], kind="modal")
    e = bank[0]
    with h5py.File(banks["modal"], "r") as f:
        g = f["entries/0000"]
        assert np.array_equal(e.frequencies_hz, g["frequencies_hz"][...])
        assert np.array_equal(e.axes_m, g.attrs["axes_m"] if "axes_m" in g.attrs else g["axes_m"][...])
        coefficients = g["transfer/coefficients"][...]
        n0 = (e.transfer.order[0] + 1) ** 2
        assert np.array_equal(e.transfer.coefficients(0), coefficients[:n0, 0] + 1j * coefficients[:n0, 1])
    assert bank.header["material"]["name"] == "glass"
    assert e.shapes.shape == (e.modes, len(e.surface_nodes_m), 3)
    # No copies: two reads of one array are one memory, and it cannot be written.
    assert np.shares_memory(e.frequencies_hz, bank[0].frequencies_hz)
    assert np.shares_memory(e.shapes, e.shapes)
    with pytest.raises(ValueError):
        e.frequencies_hz[0] = 1.0
    # The views keep the bank alive.
    shapes = clatter.open_bank(banks["modal"])[0].shapes
    assert np.isfinite(shapes).all()


def test_every_radiating_mode_falls_as_1_over_r_far_away(banks):
    """|p| r is constant in the far field. Checked on the modes the transfer promises (normal
    fraction > 0.3, docs/transfer.md); a torsional mode of the sphere moves along its surface and
    radiates nothing, so its expansion is the mesh's noise at orders up to 27, whose near field
    (n^2 / 2k ~ 9 m) still reaches 20 m."""
    bank = clatter.open_bank(banks["modal"])
    e = bank[0]
    radiating = e.transfer.normal_fraction > 0.3
    assert radiating.sum() >= 10
    direction = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    p = bank.probe(0, [20 * direction, 40 * direction])
    assert p.shape == (2, e.modes) and np.all(p[0] > 0)
    assert np.allclose(40 * p[1][radiating], 20 * p[0][radiating], rtol=0.01)
    # Scaling by gamma (003 eq. 9, Appendix E: k -> k / gamma, M -> gamma^-5/2 M): the scaled
    # body's pressure at gamma x is gamma^-5/2 the body's at x.
    assert np.allclose(bank.probe(0, 2 * 20 * direction, scale=2.0)[0], 2**-2.5 * p[0], rtol=1e-9)


def test_object_bank_entry_is_the_glass_bar(banks):
    """The bar of object_checks: its mass and centre are the box's (0.20 x 0.02 x 0.01 m of glass from
    the origin), its arrays the file's, and its radiating modes fall as 1/r."""
    bank = clatter.open_bank(banks["object"], kind="object")
    e = bank[0]
    assert e.material["name"] == "glass"
    assert e.mass_kg == pytest.approx(2600 * 0.20 * 0.02 * 0.01, rel=1e-9)
    assert np.allclose(e.centre_m, [0.10, 0.01, 0.005], rtol=1e-9)
    with h5py.File(banks["object"], "r") as f:
        g = f["entries/0000"]
        assert np.array_equal(e.modal.frequencies_hz, g["frequencies_hz"][...])
    radiating = e.modal.transfer.normal_fraction > 0.3
    assert radiating.any()
    d = np.array([0.2, 0.6, -0.77]) / np.linalg.norm([0.2, 0.6, -0.77])
    p = bank.probe(0, [20 * d, 40 * d])
    assert np.allclose(40 * p[1][radiating], 20 * p[0][radiating], rtol=0.01)


def test_ground_bank_grid_is_the_file_s(banks):
    bank = clatter.open_bank(banks["ground"], kind="ground")
    names = sorted(m.name for m in bank)
    assert names == ["soil", "steel"]
    with h5py.File(banks["ground"], "r") as f:
        for m in bank:
            g = f[f"materials/{m.name}"]
            assert np.array_equal(m.elevation_rad, g["elevation_rad"][...]) and np.array_equal(m.eta, g["eta"][...])
            k = len(m.eta) + 1  # (elevation 1, eta 1)
            s = m.series(1, 1)
            start = g["series_offset"][k]
            assert np.array_equal(s["pi"], g["pi"][start:start + g["series_length"][k]])
            assert s["dt_hat"] == g["dt_hat"][k]
            assert m.material["youngs_pa"] == g.attrs["youngs_pa"]


def test_fit_proxy_recovers_a_solid_ellipsoid():
    a, b, c, m = 0.3, 0.2, 0.1, 2.5
    inertia = np.diag([m * (b * b + c * c) / 5, m * (a * a + c * c) / 5, m * (a * a + b * b) / 5])
    fit = clatter.fit_proxy(inertia, m, 4 / 3 * np.pi * a * b * c)
    assert np.allclose(fit["semi_axes_m"], [a, b, c], rtol=1e-12)
    unit = np.array(fit["modal_unit_axes"])
    assert np.allclose(unit, np.array([c, b, a]) / np.linalg.norm([a, b, c]), rtol=1e-12)


def box_mesh(hx, hy, hz):
    v = np.array([[x, y, z] for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)])
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    return v, np.array([t for q in quads for t in ((q[0], q[1], q[2]), (q[0], q[2], q[3]))])


def test_fit_proxy_to_mesh_of_a_box():
    hx, hy, hz, rho = 0.2, 0.1, 0.05, 1000.0
    v, t = box_mesh(hx, hy, hz)
    shift = np.array([1.0, -2.0, 0.5])
    fit = clatter.fit_proxy_to_mesh(v + shift, t, rho)
    m = rho * 8 * hx * hy * hz
    assert fit["mass_kg"] == pytest.approx(m, rel=1e-12) and np.allclose(fit["centre_of_mass_m"], shift, rtol=1e-12)
    expected = m / 3 * np.array([hy * hy + hz * hz, hx * hx + hz * hz, hx * hx + hy * hy])
    assert np.allclose(np.diag(fit["inertia_kg_m2"]), expected, rtol=1e-12)
    assert fit["surface_area_m2"] == pytest.approx(8 * (hx * hy + hy * hz + hx * hz), rel=1e-12)
    a, b, c = fit["semi_axes_m"]  # the ellipsoid of the same moments and volume
    assert 4 / 3 * np.pi * a * b * c == pytest.approx(fit["volume_m3"], rel=1e-12)
    assert (b * b + c * c) / (a * a + c * c) == pytest.approx(expected[0] / expected[1], rel=1e-12)


def test_the_pebble_mesh_is_a_sphere_of_its_radius(banks):
    """The icosphere of the fixture (r = 0.1 m): its solid's volume lies below 4/3 pi r^3 by the
    facets' share, and its proxy is a sphere (all semi-axes equal to 1e-9 by its symmetry)."""
    v, t = clatter.read_mesh(banks["pebble_obj"])
    assert v.shape[1] == 3 and t.shape[1] == 3 and t.max() < len(v)
    assert np.allclose(np.linalg.norm(v, axis=1), 0.1, rtol=1e-9)
    fit = clatter.fit_proxy_to_mesh(v, t, 2600.0)
    assert 0.97 < fit["volume_m3"] / (4 / 3 * np.pi * 0.1**3) < 1
    a, b, c = fit["semi_axes_m"]
    assert a == pytest.approx(c, rel=1e-9)
