"""Properties of the assembled model: symmetry, invariance, scaling, closed-form mass properties."""

import numpy as np
import pytest

from stripcoef import estimate, load_vehicle
from stripcoef.conventions import transform_matrix
from stripcoef.geometry.vehicle import parse_vehicle

from conftest import GEOMETRY, cylinder_vehicle, spheroid_vehicle


@pytest.fixture(scope="module")
def mares():
    return estimate(load_vehicle(GEOMETRY / "mares.yaml"))


def test_added_mass_symmetric_positive_definite(mares):
    ma = mares.added_mass
    assert np.allclose(ma, ma.T, atol=1e-12 * np.abs(ma).max())
    assert np.all(np.linalg.eigvalsh(ma) > 0)
    assert np.all(np.linalg.eigvalsh(mares.rigid_body_mass) > 0)


def test_port_starboard_symmetry_kills_terms(mares):
    # xz-plane symmetry: no coupling between {u, w, q} and {v, p, r}
    lon, lat = [0, 2, 4], [1, 3, 5]
    for m in (mares.added_mass, mares.linear_damping, mares.quadratic_damping,
              mares.rigid_body_mass):
        assert np.all(m[np.ix_(lon, lat)] == 0.0) and np.all(m[np.ix_(lat, lon)] == 0.0)


def test_sonar_below_creates_roll_couplings(mares):
    # the sonar housing below the hull breaks the xy-plane symmetry (Ferreira et al. 2009, sec. III.C.1)
    c = mares.coefficients()
    assert c["K_vdot"] != 0.0 and c["K_vdot"] == pytest.approx(c["Y_pdot"])
    assert c["N_vdot"] == pytest.approx(c["Y_rdot"])


def test_reference_point_shift_is_a_rigid_body_transform():
    v = load_vehicle(GEOMETRY / "mares.yaml")
    a = estimate(v)
    point = np.array([0.3, 0.0, -0.05])
    b = estimate(v, reference_point=point)
    for ma, mb in ((a.added_mass, b.added_mass), (a.rigid_body_mass, b.rigid_body_mass),
                   (a.linear_damping, b.linear_damping)):
        moved = transform_matrix(ma, from_point=a.reference_point, to_point=point)
        assert np.allclose(moved, mb, atol=1e-9 * np.abs(ma).max())
    # quadratic damping: exact for the translation columns
    moved = transform_matrix(a.quadratic_damping, from_point=a.reference_point, to_point=point)
    assert np.allclose(moved[:, :3], b.quadratic_damping[:, :3],
                       atol=1e-9 * np.abs(a.quadratic_damping).max())


def test_doubling_size_scales_added_mass():
    a = estimate(spheroid_vehicle(1.5, 0.2))
    b = estimate(spheroid_vehicle(3.0, 0.4))
    ratio = np.diag(b.added_mass)[[0, 1, 2, 4, 5]] / np.diag(a.added_mass)[[0, 1, 2, 4, 5]]
    assert ratio == pytest.approx([8, 8, 8, 32, 32], rel=1e-9)


def test_density_scales_linearly():
    a = estimate(spheroid_vehicle(1.5, 0.2, rho=1000.0))
    b = estimate(spheroid_vehicle(1.5, 0.2, rho=1025.0))
    assert np.allclose(b.added_mass, 1.025 * a.added_mass, rtol=1e-12)
    assert np.allclose(b.rigid_body_mass, 1.025 * a.rigid_body_mass, rtol=1e-12)
    # damping: rho enters linearly at fixed nu (Reynolds numbers unchanged)
    assert np.allclose(b.quadratic_damping, 1.025 * a.quadratic_damping, rtol=1e-12)


def test_cylinder_volume_cb_and_inertia_closed_form():
    length, d = 2.0, 0.3
    model = estimate(cylinder_vehicle(length, d))
    r = 0.5 * d
    vol = np.pi * r**2 * length
    assert model.volume == pytest.approx(vol, rel=1e-12)
    assert np.allclose(model.center_of_buoyancy, 0.0, atol=1e-12)
    m = 1000.0 * vol                     # neutrally buoyant default
    assert model.mass == pytest.approx(m)
    ixx = 0.5 * m * r**2
    iyy = m * (3 * r**2 + length**2) / 12
    inertia = model.rigid_body_mass[3:, 3:]
    assert np.diag(inertia) == pytest.approx([ixx, iyy, iyy], rel=1e-6)


def test_spheroid_volume_and_inertia():
    a, b = 0.75, 0.1
    model = estimate(spheroid_vehicle(2 * a, 2 * b, strips=800))
    vol = 4 / 3 * np.pi * a * b**2
    assert model.volume == pytest.approx(vol, rel=1e-5)
    m = 1000.0 * vol
    assert np.diag(model.rigid_body_mass[3:, 3:]) == pytest.approx(
        [0.4 * m * b**2, 0.2 * m * (a**2 + b**2), 0.2 * m * (a**2 + b**2)], rel=1e-4)


def test_hole_removes_volume_and_heave_added_mass():
    base = {"name": "h", "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "cylinder", "x": [-0.5, 0.5], "radius": 0.1}]}}
    plain = estimate(parse_vehicle(dict(base), file="<t>"), corrections=False)
    holed = estimate(parse_vehicle(dict(base, holes=[{"axis": "z", "x": 0.0, "diameter": 0.06}]),
                                   file="<t>"), corrections=False)
    # hole water: pi r_h^2 * (hull height 0.2 m through the axis)
    v_hole = np.pi * 0.03**2 * 0.2
    assert plain.volume - holed.volume == pytest.approx(v_hole, rel=2e-3)
    assert holed.added_mass[2, 2] < plain.added_mass[2, 2]            # heave passes through
    # sway: the hull's 2D added mass plus the carried water of the hole
    assert holed.added_mass[1, 1] == pytest.approx(plain.added_mass[1, 1] + 1000 * v_hole,
                                                   rel=2e-3)


def test_default_strip_count_converged_to_0p1_percent():
    v = load_vehicle(GEOMETRY / "mares.yaml")
    a = estimate(v)
    b = estimate(v, strips=3200)
    for ma, mb in ((a.added_mass, b.added_mass), (a.quadratic_damping, b.quadratic_damping)):
        d = np.diag(mb)
        mask = d != 0
        assert np.max(np.abs(np.diag(ma)[mask] / d[mask] - 1)) < 1e-3


def test_fin_pair_on_a_circle_uses_the_finned_section():
    r, a, length = 0.1, 0.2, 0.4
    span = a - r
    base = {"name": "finned", "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "cylinder", "x": [-1.0, 1.0], "radius": r}]},
            "appendages": [
                {"name": "top", "type": "fin", "center": [0.0, 0.0, -(r + span / 2)],
                 "span_axis": "z", "span": span, "chord": length, "thickness": 0.002},
                {"name": "bottom", "type": "fin", "center": [0.0, 0.0, r + span / 2],
                 "span_axis": "z", "span": span, "chord": length, "thickness": 0.002}]}
    model = estimate(parse_vehicle(base, file="<finned>"), corrections=False)
    plain = estimate(parse_vehicle(dict(base, appendages=[]), file="<plain>"), corrections=False)
    extra = model.added_mass[1, 1] - plain.added_mass[1, 1]
    # the thin finned circle's share times the fins' thickness factor C_A(span / (t/2))
    from stripcoef.assembly.added_mass import _fin_thickness_factor
    expected = 1000 * np.pi * (a**2 - r**2 + r**4 / a**2 - r**2) * length \
        * _fin_thickness_factor(span, 0.001)
    assert extra == pytest.approx(expected, rel=1e-6)
    # one pair rolls as the exact finned circle with two fins (Newman 1977 sec. 4.13), not as
    # the cruciform's 2/pi rho a^4 (tests/test_fin_sections.py checks the closed form)
    from stripcoef.sections.added_mass import finned_circle_roll
    assert model.added_mass[3, 3] == pytest.approx(
        finned_circle_roll(r, a, fins=2, rho=1000.0) * length, rel=1e-6)
