"""The MARES paradox (Ferreira et al. 2009 sec. V.D) with the shipped geometry/mares.yaml.

With the Munk moment the horizontal thrusters' differential moment opposes the rotation;
without it the outer thruster (P1, port, in a starboard turn) saturates first.
"""

from pathlib import Path

import numpy as np
import pytest

from stripcoef.limits.solver import LimitOptions, solve_limits, turning_curve

MARES = Path(__file__).resolve().parent.parent / "geometry" / "mares.yaml"
RADII = [2.0, 4.0, 8.0, 16.0, 32.0]


@pytest.fixture(scope="module")
def model():
    from conftest import shipped_model     # the default estimate, shared with other tests

    return shipped_model(MARES.name)


def _yaw_moment(model, point):
    b = model.allocation()
    return float(b[5] @ np.array([point.thrust[t.name] for t in model.thrusters]))


def test_with_munk_the_thrusters_oppose_the_rotation(model):
    for p in turning_curve(model, RADII, options=LimitOptions(munk=True)):
        assert p.yaw_rate > 0.0
        assert _yaw_moment(model, p) < 0.0, p.radius


def test_without_munk_the_outer_thruster_saturates_first(model):
    for p in turning_curve(model, RADII, options=LimitOptions(munk=False)):
        assert _yaw_moment(model, p) > 0.0
        assert p.saturated == "P1", p.radius
        assert p.thrust["P1"] == pytest.approx(model.thruster("P1").max_forward, rel=1e-6)
        assert p.thrust["P2"] < p.thrust["P1"]


def test_u_max_rises_to_the_straight_line_without_munk(model):
    res = solve_limits(model, radii=[1.0, 3.0, 10.0, 30.0, 100.0, 1000.0], munk=False)
    u = np.array([p.u_max for p in res.turning])
    assert np.all(np.diff(u) > 0.0)
    assert u[-1] < res.surge_speed_max
    assert u[-1] == pytest.approx(res.surge_speed_max, rel=0.01)


def test_nose_points_to_the_centre(model):
    # Ferreira et al. 2009 eq. 60: v = 0 cannot balance sway
    for munk in (True, False):
        for p in turning_curve(model, RADII, options=LimitOptions(munk=munk)):
            assert p.v < 0.0 and p.drift_angle > 0.0


def test_munk_slows_the_turn(model):
    on = turning_curve(model, RADII, options=LimitOptions(munk=True))
    off = turning_curve(model, RADII, options=LimitOptions(munk=False))
    for a, b in zip(on, off):
        assert a.u_max < b.u_max
