"""2D panel method against exact solutions and properties (closed-form / properties)."""

import numpy as np
import pytest

from stripcoef.conventions import transform_matrix
from stripcoef.errors import InputError
from stripcoef.sections.panel import added_mass_contours, added_mass_sections, orient_contours

RHO = 1025.0


def ellipse(a, b, n=800, y0=0.0, z0=0.0):
    th = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.column_stack([y0 + a * np.cos(th), z0 + b * np.sin(th)])


def test_circle_exact():
    """Newman (1977) sec. 4.13: m22 = m33 = rho pi a^2, roll 0, no coupling."""
    a = 0.37
    m = added_mass_contours([ellipse(a, a)], rho=RHO)
    ref = RHO * np.pi * a * a
    assert m[0, 0] == pytest.approx(ref, rel=1e-3)
    assert m[1, 1] == pytest.approx(ref, rel=1e-3)
    assert abs(m[2, 2]) < 1e-6 * ref * a * a
    assert abs(m[0, 1]) < 1e-6 * ref


@pytest.mark.parametrize("a,b", [(1.0, 0.4), (0.3, 0.9), (1.0, 0.1)])
def test_ellipse_exact(a, b):
    """Ellipse semi-axes a (y), b (z): m22 = rho pi b^2, m33 = rho pi a^2,
    m44 = rho pi (a^2 - b^2)^2 / 8 (Newman 1977, sec. 4.13 table)."""
    m = added_mass_contours([ellipse(a, b)], rho=RHO)
    assert m[0, 0] == pytest.approx(RHO * np.pi * b * b, rel=1e-3)
    assert m[1, 1] == pytest.approx(RHO * np.pi * a * a, rel=1e-3)
    assert m[2, 2] == pytest.approx(RHO * np.pi * (a * a - b * b) ** 2 / 8, rel=1e-3)


def test_orientation_and_closure_do_not_matter():
    c = ellipse(1.0, 0.5, 300)
    m1 = added_mass_contours([c], rho=RHO)
    m2 = added_mass_contours([np.vstack([c[::-1], c[-1:]])], rho=RHO)
    np.testing.assert_allclose(m1, m2, rtol=1e-9, atol=1e-9)


def test_about_point_matches_conventions_shift():
    """Roll about (y0, z0) equals the rigid-body shift of the 6x6 matrix (Fossen 2011, eq. 7.248)."""
    sec = [ellipse(1.0, 0.4, 400, y0=0.2, z0=-0.1), ellipse(0.2, 0.2, 200, y0=0.0, z0=0.9)]
    m0 = added_mass_contours(sec, rho=RHO, about=(0.0, 0.0))
    p = (0.3, -0.5)
    m1 = added_mass_contours(sec, rho=RHO, about=p)
    big = np.zeros((6, 6))
    big[1:4, 1:4] = m0
    shifted = transform_matrix(big, from_point=(0, 0, 0), to_point=(0.0, p[0], p[1]))
    np.testing.assert_allclose(m1, shifted[1:4, 1:4], rtol=1e-9, atol=1e-9 * m0.max())


def test_translation_invariance_and_mirror():
    sec = [ellipse(1.0, 0.3, 400), ellipse(0.2, 0.5, 200, y0=1.6)]
    m = added_mass_contours(sec, rho=RHO, about=(0.8, 0.0))
    moved = [c + [3.0, -2.0] for c in sec]
    np.testing.assert_allclose(added_mass_contours(moved, rho=RHO, about=(3.8, -2.0)), m,
                               rtol=1e-9, atol=1e-6)
    mirrored = [c * [-1.0, 1.0] for c in sec]           # mirror y -> -y
    mm = added_mass_contours(mirrored, rho=RHO, about=(-0.8, 0.0))
    sign = np.array([-1.0, 1.0, -1.0])                   # sway and roll change sign
    # panel nodes start elsewhere on the mirrored rings: equal to the discretisation error
    np.testing.assert_allclose(mm, m * np.outer(sign, sign), rtol=1e-4, atol=1e-4 * abs(m).max())


def test_two_far_apart_parts_add_up():
    c = ellipse(0.3, 0.3, 400)
    one = added_mass_contours([c], rho=RHO)
    two = added_mass_contours([c, c + [40.0, 0.0]], rho=RHO, panels=256)
    assert two[0, 0] == pytest.approx(2 * one[0, 0], rel=2e-3)
    assert two[1, 1] == pytest.approx(2 * one[1, 1], rel=2e-3)


def test_close_parts_interact():
    """Two touching-close circles side by side have more heave added mass than twice one."""
    c = ellipse(0.3, 0.3, 400)
    one = added_mass_contours([c], rho=RHO)
    two = added_mass_contours([c, c + [0.65, 0.0]], rho=RHO, panels=256)
    assert two[1, 1] > 2.05 * one[1, 1]


def test_ring_entrains_its_water_and_not_its_rotation():
    """Annulus (duct ring): translation = rho pi (Ro^2 + Ri^2) (outer flow + entrained hole
    water), rotation 0 (potential flow inside a rotating circle stays at rest)."""
    ro, ri = 0.5, 0.4
    ring = [ellipse(ro, ro, 600), ellipse(ri, ri, 600)]
    m = added_mass_contours(ring, rho=RHO, panels=256)
    ref = RHO * np.pi * (ro ** 2 + ri ** 2)
    assert m[0, 0] == pytest.approx(ref, rel=2e-3)
    assert m[1, 1] == pytest.approx(ref, rel=2e-3)
    assert abs(m[2, 2]) < 1e-4 * ref * ro * ro


def test_hole_orientation_is_normalised():
    outer, inner = ellipse(0.5, 0.5, 300), ellipse(0.3, 0.3, 300)
    rings = orient_contours([outer[::-1], inner])
    from stripcoef.geometry.polygons import signed_area
    assert signed_area(rings[0]) > 0 and signed_area(rings[1]) < 0


def test_batched_equals_single_and_empty_section():
    secs = [[ellipse(1.0, 0.4, 300)], [], [ellipse(0.3, 0.3, 300), ellipse(0.2, 0.1, 100, 1.0)]]
    about = np.array([[0.0, 0.0], [0.0, 0.0], [0.5, 0.1]])
    batch = added_mass_sections(secs, rho=RHO, about=about)
    np.testing.assert_allclose(batch[0], added_mass_contours(secs[0], rho=RHO), rtol=1e-12)
    assert np.all(batch[1] == 0.0)
    np.testing.assert_allclose(batch[2], added_mass_contours(secs[2], rho=RHO, about=(0.5, 0.1)),
                               rtol=1e-12)


def test_scaling_with_size_and_density():
    c = ellipse(1.0, 0.3, 400)
    m = added_mass_contours([c], rho=1000.0)
    m2 = added_mass_contours([2.0 * c], rho=2000.0)
    scale = np.array([[4, 4, 8], [4, 4, 8], [8, 8, 16]]) * 2.0
    np.testing.assert_allclose(m2, m * scale, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("bad", [np.zeros((2, 2)), np.zeros((5, 3)), [[0, 0], [1, 0], [2, 0]],
                                 [[0, 0], [1, np.nan], [0, 1]]])
def test_bad_contours(bad):
    with pytest.raises(InputError):
        added_mass_contours([np.asarray(bad, float)], rho=RHO)


def test_bad_density():
    with pytest.raises(InputError, match="rho"):
        added_mass_contours([ellipse(1, 1)], rho=-1.0)
