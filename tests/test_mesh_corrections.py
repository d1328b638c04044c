"""Axisymmetric 3D corrections (corrections.py): exact Lamb values, capsule BEM, strips."""

import numpy as np
import pytest

from stripcoef.hull.corrections import body_of_revolution_added_mass, equivalent_profile, hull_corrections
from stripcoef.errors import InputError
from stripcoef.geometry.mesh import mesh_body, revolved_mesh
from stripcoef.hull.lamb import spheroid_added_mass

RHO = 1000.0


def lamb(a, b, rho=RHO):
    """Lamb (1932) sec. 373: stripcoef.hull.lamb.spheroid_added_mass (tested against Lamb's table
    in tests/test_hull_lamb.py)."""
    m = spheroid_added_mass(a, b, rho=rho)
    return m[0], m[1], m[4]

def spheroid_profile(a, b, n=400):
    t = np.linspace(0.0, np.pi, n)[::-1]
    return a * np.cos(t), b * np.sin(t)


def test_sphere_exact():
    x, r = spheroid_profile(0.5, 0.5)
    m = body_of_revolution_added_mass(x, r, rho=RHO)
    half = RHO * 2 / 3 * np.pi * 0.125
    np.testing.assert_allclose(np.diag(m)[:3], half, rtol=1e-3)
    assert abs(m[5, 5]) < 1e-6 * half * 0.25


@pytest.mark.parametrize("ld", [2, 4, 7.5, 12])
def test_spheroids_match_lamb(ld):
    a = 0.75
    b = a / ld
    m = body_of_revolution_added_mass(*spheroid_profile(a, b), rho=RHO)
    m11, m22, m55 = lamb(a, b)
    assert m[0, 0] == pytest.approx(m11, rel=1e-3)
    assert m[1, 1] == pytest.approx(m22, rel=1e-3) and m[2, 2] == m[1, 1]
    assert m[5, 5] == pytest.approx(m55, rel=2e-3) and m[4, 4] == m[5, 5]
    assert abs(m[1, 5]) < 1e-6 * m22 * a         # symmetric fore-aft: no coupling


def test_capsule_matches_converged_capytaine():
    """Capsule L = 1.5, D = 0.2: Capytaine direct, 12800 panels (shared/reference sec. 1c):
    m11 = 2.697, m22 = 41.05, m55 = 5.858 with ~0.2 % uncertainty."""
    th = np.linspace(0, np.pi / 2, 60)
    x = np.r_[-0.65 - 0.1 * np.cos(th), 0.65 + 0.1 * np.sin(th)]
    r = np.r_[0.1 * np.sin(th), 0.1 * np.cos(th)]
    m = body_of_revolution_added_mass(x, r, rho=RHO)
    assert m[0, 0] == pytest.approx(2.697, rel=3e-3)
    assert m[1, 1] == pytest.approx(41.05, rel=3e-3)
    assert m[5, 5] == pytest.approx(5.858, rel=3e-3)


def test_shift_of_reference_point():
    """Rotational terms about another point follow the rigid-body shift (coupling appears)."""
    x, r = spheroid_profile(0.6, 0.1)
    m0 = body_of_revolution_added_mass(x, r, rho=RHO)
    m1 = body_of_revolution_added_mass(x, r, rho=RHO, x_ref=0.2)
    # moving the point by +0.2 along x: m26' = -0.2 m22 (strip operator X = x - 0.2)
    assert m1[1, 5] == pytest.approx(-0.2 * m0[1, 1], rel=2e-3)
    assert m1[5, 5] == pytest.approx(m0[5, 5] + 0.04 * m0[1, 1], rel=2e-3)


def test_hull_corrections_on_spheroid_strips_give_lamb():
    t = np.linspace(0.0, np.pi, 161)[::-1]
    body = mesh_body(revolved_mesh(0.75 * np.cos(t), 0.1 * np.sin(t), sections=128))
    st = body.strips(200)
    c = hull_corrections(st, rho=RHO, center=(0.0, 0.0, 0.0))
    m11, m22, m55 = lamb(0.75, 0.1)
    strip22 = RHO * float(np.sum(st.parts[0].area * st.dx))
    strip66 = RHO * float(np.sum(st.parts[0].area * st.x ** 2 * st.dx))
    assert c.axial_added_mass == pytest.approx(m11, rel=1e-2)
    assert c.translation * strip22 == pytest.approx(m22, rel=5e-3)
    assert c.rotation * strip66 == pytest.approx(m55, rel=5e-3)


def test_equivalent_profile_blunt_and_pointed_ends():
    import trimesh
    box = mesh_body(trimesh.creation.box([1.0, 0.2, 0.2]))
    x, r = equivalent_profile(box.strips(20))
    assert r[0] == pytest.approx(np.sqrt(0.04 / np.pi)) and r[-1] == r[0]
    t = np.linspace(0.0, np.pi, 81)[::-1]
    sph = mesh_body(revolved_mesh(0.5 * np.cos(t), 0.1 * np.sin(t), sections=64))
    x, r = equivalent_profile(sph.strips(40))
    assert r[0] < 0.01 and r[-1] < 0.01


def test_bad_profile():
    with pytest.raises(InputError):
        body_of_revolution_added_mass([0.0, -1.0], [0.1, 0.1], rho=RHO)


def test_coupling_of_an_asymmetric_hull_about_its_centre_of_buoyancy():
    """Egg-shaped body (blunt nose, long tail): the corrected strip matrix of its own strips
    reproduces the axisymmetric 3D solution, including the sway-yaw coupling about the CB."""
    t = np.linspace(0.0, np.pi, 161)[::-1]
    x = np.where(np.cos(t) > 0, 0.3 * np.cos(t), 0.9 * np.cos(t))
    r = 0.1 * np.sin(t)
    body = mesh_body(revolved_mesh(x, r, sections=128))           # origin: centroid
    st = body.strips(200)
    c = hull_corrections(st, rho=RHO, center=(0.0, 0.0, 0.0))
    xs, rs = equivalent_profile(st)
    m3 = body_of_revolution_added_mass(xs, rs, rho=RHO, area_linear=True)
    a = np.pi * rs[1:-1] ** 2
    s26 = RHO * np.sum(a * st.x * st.dx)
    s22, s66 = RHO * np.sum(a * st.dx), RHO * np.sum(a * st.x ** 2 * st.dx)
    assert abs(m3[1, 5]) > 1e-3 * np.sqrt(m3[1, 1] * m3[5, 5])     # a real coupling
    assert np.sqrt(c.translation * c.rotation) * s26 + c.coupling == pytest.approx(m3[1, 5], rel=1e-9)
    assert c.translation * s22 == pytest.approx(m3[1, 1], rel=1e-9)
    assert c.rotation * s66 == pytest.approx(m3[5, 5], rel=1e-9)


def test_directional_bodies_of_a_body_of_revolution_reproduce_its_3d_matrix():
    """With the panel method's 2D added mass (circles: rho A), the corrected strip matrix of a
    body of revolution is its axisymmetric 3D matrix (both lateral directions alike)."""
    from stripcoef.assembly.added_mass import section_matrices
    from stripcoef.strips import strip_added_mass
    from stripcoef.hull.corrections import apply_corrections, strip_section_added_mass
    t = np.linspace(0.0, np.pi, 121)[::-1]
    x = np.where(np.cos(t) > 0, 0.3 * np.cos(t), 0.9 * np.cos(t))
    body = mesh_body(revolved_mesh(x, 0.1 * np.sin(t), sections=128))
    st = body.strips(120)
    m2d = strip_section_added_mass(st, RHO)
    c = hull_corrections(st, rho=RHO, center=(0.0, 0.0, 0.0), section_added_mass=m2d)
    m = apply_corrections(strip_added_mass(st, section_matrices(st, RHO), (0.0, 0.0, 0.0)), c)
    m3 = body_of_revolution_added_mass(*equivalent_profile(st), rho=RHO)
    for i in (0, 1, 2, 4, 5):
        assert m[i, i] == pytest.approx(m3[i, i], rel=2e-3)
    assert m[1, 5] == pytest.approx(m3[1, 5], rel=2e-2)
    assert m[2, 4] == pytest.approx(m3[2, 4], rel=2e-2)


def test_axial_added_mass_converges_with_strips_on_mares():
    """Appendages get their own equal-area bodies with their ends where the parts end, so
    the surge term does not depend on how the strips cut them (MARES, 400 vs 3200 strips)."""
    from pathlib import Path

    from stripcoef.assembly.estimate import displaced_volume
    from stripcoef.geometry.vehicle import load_vehicle
    v = load_vehicle(Path(__file__).resolve().parents[1] / "geometry" / "mares.yaml")
    vals = []
    for n in (400, 3200):
        st = v.cut(n)
        _, cb = displaced_volume(st)
        vals.append(hull_corrections(st, rho=RHO, center=cb).axial_added_mass)
    assert vals[0] == pytest.approx(vals[1], rel=1e-3)


def test_area_linear_equivalent_body_converges_with_few_strips():
    """A spheroid (L/D = 7.5, fine mesh) from only 40 strips: with the equivalent body's area
    interpolated linearly between strip centres every diagonal term is within 0.25 % of
    Lamb's exact values (a radius-linear meridian, cut by chords at the round ends, gave
    -0.58 % in pitch and yaw; docs/theory.md sec. 6)."""
    from stripcoef.assembly.added_mass import section_matrices
    from stripcoef.strips import strip_added_mass
    from stripcoef.hull.corrections import apply_corrections
    t = np.linspace(0.0, np.pi, 241)[::-1]
    body = mesh_body(revolved_mesh(0.75 * np.cos(t), 0.1 * np.sin(t), sections=128))
    lamb = np.asarray(spheroid_added_mass(0.75, 0.1, rho=RHO))
    st = body.strips(40)
    mats = section_matrices(st, RHO)
    corr = hull_corrections(st, rho=RHO, center=(0.0, 0.0, 0.0), section_added_mass=mats[0])
    m = apply_corrections(strip_added_mass(st, mats, (0.0, 0.0, 0.0)), corr)
    nz = [0, 1, 2, 4, 5]
    np.testing.assert_allclose(np.diag(m)[nz], lamb[nz], rtol=2.5e-3)


def test_area_linear_meridian_is_exact_for_a_cylinder_and_follows_sqrt_between_points():
    """The area-linear meridian keeps a cylinder exactly (constant area) and, between two
    profile points, puts r = sqrt of the linear interpolant of r^2 (never below the chord)."""
    from stripcoef.hull.axisymmetric import _meridian
    xn, rn = _meridian(np.array([0.0, 0.0, 1.0, 1.0]), np.array([0.0, 0.2, 0.2, 0.0]), 40,
                       area_linear=True)
    side = (xn > 0) & (xn < 1)
    np.testing.assert_allclose(rn[side], 0.2, rtol=1e-12)
    xn, rn = _meridian(np.array([0.0, 1.0]), np.array([0.0, 0.3]), 40, area_linear=True)
    inner = (xn > 0) & (xn < 1) & (rn > 0)
    np.testing.assert_allclose(rn[inner], 0.3 * np.sqrt(xn[inner]), rtol=1e-12)
