"""Tubes (closed meridians off the axis) and the junction pieces' slenderness weights."""

import numpy as np
import pytest
from shapely.geometry import box as sbox

from stripcoef.hull.corrections import body_of_revolution_added_mass, ring_body_added_mass
from stripcoef.hull.lamb import lamb_k_factors
from stripcoef.hull.members import crossing_weights

RHO = 1000.0


def tube(length, ri, ro, **kw):
    return ring_body_added_mass([0, length, length, 0], [ri, ri, ro, ro], rho=RHO,
                                x_ref=0.5 * length, **kw)


def test_long_tube_tends_to_the_2d_annulus():
    """m22 / L -> rho pi (r_o^2 + r_i^2) (outer circle plus the bore's rigid water, Newman 1977
    sec. 4.13); the end deficit is O(r/L), so the Richardson value 2 f(2L) - f(L) is the 2D
    limit."""
    f = [tube(L, 0.3, 0.6)[1, 1] / (RHO * np.pi * (0.36 + 0.09) * L) for L in (10.0, 20.0)]
    assert 0.9 < f[0] < f[1] < 1.0
    assert (1.0 - f[0]) / (1.0 - f[1]) == pytest.approx(2.0, rel=0.05)
    assert 2 * f[1] - f[0] == pytest.approx(1.0, abs=0.005)


def test_tube_with_a_vanishing_bore_is_the_solid_cylinder():
    """r_i -> 0: the same body as the solid cylinder of body_of_revolution_added_mass."""
    t = tube(10.0, 1e-3, 0.6, panels=320)
    c = body_of_revolution_added_mass([0, 10.0], [0.6, 0.6], rho=RHO, x_ref=5.0, panels=320)
    for i in (0, 1, 2, 4, 5):
        assert t[i, i] == pytest.approx(c[i, i], rel=0.01), i


def test_tube_matrix_properties():
    """Orientation of the corners does not matter; symmetric about its centre (no sway-yaw
    coupling), m22 = m33, m55 = m66; a short tube keeps a small part of the 2D annulus."""
    a = tube(0.06, 0.24, 0.3)
    b = ring_body_added_mass([0, 0, 0.06, 0.06], [0.24, 0.3, 0.3, 0.24], rho=RHO, x_ref=0.03)
    np.testing.assert_allclose(a, b, rtol=1e-8, atol=1e-8 * np.abs(a).max())
    assert a[1, 1] == a[2, 2] and a[4, 4] == a[5, 5]
    assert abs(a[1, 5]) < 1e-6 * a[1, 1]
    assert 0 < a[1, 1] < 0.2 * RHO * np.pi * (0.3 ** 2 + 0.24 ** 2) * 0.06
    assert np.all(np.linalg.eigvalsh(np.delete(np.delete(a, 3, 0), 3, 1)) > 0)


def test_tube_needs_a_meridian_off_the_axis():
    from stripcoef.errors import InputError
    with pytest.raises(InputError, match="off the axis"):
        ring_body_added_mass([0, 1, 1, 0], [0.0, 0.0, 0.5, 0.5], rho=RHO)


def pieces(poly, n=12):
    return [[poly] for _ in range(n)]


def test_crossing_weights_of_a_vertical_post():
    """A post 0.06 x 0.06 (x, y) and 0.25 high (z): heave is along its axis."""
    w = crossing_weights(pieces(sbox(0.24, -0.125, 0.30, 0.125)), 0.06)
    lam = 0.25 / (2 * np.sqrt(0.06 * 0.06 / np.pi))
    k1, k2, _ = lamb_k_factors(lam)
    np.testing.assert_allclose(w, [1.0, k1 / k2], rtol=1e-9)


def test_crossing_weights_of_horizontal_tilted_and_stubby_pieces():
    hor = crossing_weights(pieces(sbox(-0.2, 0.0, 0.2, 0.05)), 0.05)
    assert hor[1] == pytest.approx(1.0) and hor[0] < 0.2
    from shapely import affinity
    tilted = crossing_weights(pieces(affinity.rotate(sbox(-0.2, 0.0, 0.2, 0.05), 45)), 0.05)
    assert tilted[0] == pytest.approx(tilted[1], rel=1e-6)
    assert tilted[0] == pytest.approx(0.5 * (1 + hor[0]), rel=1e-6)
    # a piece no longer in the section plane than across it: no axis, nothing changed
    np.testing.assert_allclose(crossing_weights(pieces(sbox(0, 0, 0.1, 0.1)), 0.2), [1, 1])


@pytest.mark.parametrize("length,ri,ro", [(1.0, 0.2, 0.3), (0.5, 0.24, 0.3)])
def test_a_duct_mesh_gets_its_tube_matrix(length, ri, ro):
    """A circular tube as a mesh (sections with a hole all along): the pipeline's hollow
    equivalent bodies (corrections.bore_area) make it its own 3D matrix; the solid bodies
    gave surge +55..+106 %, sway -11..-16 %, pitch/yaw -23..+119 % on these two."""
    import warnings

    import trimesh

    from stripcoef.assembly.added_mass import added_mass
    from stripcoef.assembly.estimate import displaced_volume
    from stripcoef.conventions import transform_matrix
    from stripcoef.geometry.mesh import mesh_body
    m = trimesh.creation.annulus(r_min=ri, r_max=ro, height=length, sections=256)
    m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        st = mesh_body(m, origin="file").strips(200)
    vol, cb = displaced_volume(st)
    got, _ = added_mass(st, RHO, about=cb, volume=vol, center=cb)
    # the mesh's tube is centred on the origin
    exact = transform_matrix(tube(length, ri, ro, panels=320), from_point=(0, 0, 0), to_point=cb)
    for i in (0, 1, 2, 4, 5):
        assert got[i, i] == pytest.approx(exact[i, i], rel=0.012), i


def test_bore_area_only_for_a_bore_all_along():
    import warnings

    import trimesh

    from stripcoef.hull.corrections import bore_area
    from stripcoef.geometry.mesh import mesh_body
    duct = trimesh.creation.annulus(r_min=0.2, r_max=0.3, height=1.0, sections=64)
    duct.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    cap = trimesh.creation.cylinder(radius=0.3, height=0.2, sections=64)
    cap.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [0, 1, 0]))
    cap.apply_translation([0.55, 0, 0])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        st = mesh_body(duct, origin="file").strips(50)
        closed = mesh_body(trimesh.util.concatenate([duct, cap]), origin="file").strips(60)
    a = bore_area(st)
    assert a is not None
    np.testing.assert_allclose(a, np.pi * 0.2 ** 2, rtol=0.01)
    assert bore_area(closed) is None          # closed at one end: solid equivalent bodies
