"""Mass properties from density zones (MARES Table I) and the thruster map (VideoRay Table I)."""

import numpy as np
import pytest

from stripcoef import estimate
from stripcoef.errors import ModelWarning
from stripcoef.geometry.vehicle import parse_vehicle
from stripcoef.thrusters import Thruster


def _cyl(**extra):
    data = {"name": "zones", "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "cylinder", "x": [-1.0, 1.0], "radius": 0.1}]}}
    data.update(extra)
    return parse_vehicle(data, file="<zones>")


def test_two_density_zones_give_mass_and_cg():
    v = _cyl(mass={"default_density": 1000.0,
                   "zones": [{"name": "dry", "x": [0.0, 1.0], "density": 500.0}]})
    with pytest.warns(ModelWarning, match=r"weight and buoyancy differ by -25.0 %"):
        m = estimate(v)
    area = np.pi * 0.01
    mass = area * (1000.0 + 500.0)
    assert m.mass == pytest.approx(mass, rel=1e-9)
    xg = (area * 1000 * -0.5 + area * 500 * 0.5) / mass
    assert m.center_of_gravity[0] == pytest.approx(xg, rel=1e-9)
    # inertia about the CG: each half a rod of length 1 m, parallel axis theorem
    m1, m2 = area * 1000, area * 500
    iyy = (m1 / 12 + m1 * (-0.5 - xg) ** 2 + m2 / 12 + m2 * (0.5 - xg) ** 2
           + mass * 0.01 / 4)
    assert m.rigid_body_mass[4, 4] == pytest.approx(
        iyy + mass * (m.center_of_gravity[0] - m.reference_point[0]) ** 2, rel=1e-6)


def test_given_mass_scales_the_distribution_and_keeps_given_cg():
    v = _cyl(mass={"mass": 50.0, "center_of_gravity": [0.0, 0.0, 0.02]})
    with pytest.warns(ModelWarning, match=r"weight and buoyancy differ by -20.4 %"):
        m = estimate(v)
    assert m.mass == 50.0
    assert np.allclose(m.center_of_gravity, [0, 0, 0.02])
    # restoring: CG below CB gives a righting roll moment
    g = m.restoring(np.array([0, 0, 0, 0.1, 0, 0]))
    assert g[3] > 0


def test_unknown_body_in_zone_is_an_error():
    from stripcoef.errors import InputError

    with pytest.raises(InputError, match="unknown body"):
        _cyl(mass={"zones": [{"x": [0, 1], "density": 900, "bodies": ["nope"]}]})


def test_videoray_thruster_map():
    t = Thruster("port", np.zeros(3), np.array([1.0, 0, 0]), ct_forward=2.5939e-4,
                 ct_backward=1.0086e-4, max_forward=12.554, max_backward=4.882)
    assert t.thrust(60) == pytest.approx(2.5939e-4 * 3600)
    assert t.thrust(-60) == pytest.approx(-1.0086e-4 * 3600)
    assert t.thrust(1000) == 12.554 and t.thrust(-1000) == -4.882
    assert t.command_for(t.thrust(100)) == pytest.approx(100)


def test_efficiency_and_deadband():
    t = Thruster("v", np.zeros(3), np.array([0, 0, 1.0]), ct_forward=1e-3, ct_backward=1e-3,
                 eta_backward=0.57, deadband=5.0)
    assert t.thrust(-100) == pytest.approx(-0.57 * 10.0)
    assert t.thrust(4.0) == 0.0


def test_allocation_moment_arm():
    t = Thruster("p", np.array([-0.5, -0.13, 0.0]), np.array([1.0, 0, 0]))
    col = t.wrench_column(np.zeros(3))
    assert col == pytest.approx([1, 0, 0, 0, 0, 0.13])   # port thruster pushing: yaw to starboard
