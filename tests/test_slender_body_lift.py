"""Slender-body lift ahead of the separation station (stripcoef.hull.lift.slender_body_lift_matrix,
separation_station): exact integrals of an analytic body, the limits, the rotary terms from the
local cross-flow, invariance under a change of reference point, and the vehicle option."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stripcoef import estimate
from stripcoef.conventions import transform_matrix
from stripcoef.errors import InputError
from stripcoef.geometry.vehicle import parse_vehicle
from stripcoef.hull.lift import separation_station, slender_body_lift_matrix

RHO = 1000.0
A, R = 2.0, 0.25           # a spheroid of half-length 2 m, radius 0.25 m
X = np.linspace(-A, A, 20001)
S = math.pi * R ** 2 * (1.0 - (X / A) ** 2)


def spheroid_integrals(x0):
    """int_{-a}^{x0} S dx and int S x dx of the spheroid, in closed form."""
    k = math.pi * R ** 2
    i0 = k * ((x0 - x0 ** 3 / (3 * A * A)) - (-A + A / 3))
    i1 = k * ((x0 ** 2 / 2 - x0 ** 4 / (4 * A * A)) - (A * A / 2 - A * A / 4))
    return i0, i1


@pytest.mark.parametrize("x0", [-1.5, -0.5, 0.0, 1.0])
def test_spheroid_derivatives_in_closed_form(x0):
    L = slender_body_lift_matrix(X, S, x0, rho=RHO)
    s0 = math.pi * R ** 2 * (1 - (x0 / A) ** 2)
    i0, i1 = spheroid_integrals(x0)
    # force -u L nu: Y_uv = -L[1,1] = -rho S0, Y_ur = -rho S0 x0,
    # N_uv = -rho (S0 x0 - int S), N_ur = -rho (S0 x0^2 - int S x)
    assert L[1, 1] == pytest.approx(RHO * s0, rel=1e-9)
    assert L[1, 5] == pytest.approx(RHO * s0 * x0, rel=1e-9, abs=1e-12)
    assert L[5, 1] == pytest.approx(RHO * (s0 * x0 - i0), rel=1e-6)
    assert L[5, 5] == pytest.approx(RHO * (s0 * x0 ** 2 - i1), rel=1e-6)
    # heave and pitch mirror sway and yaw (w - x q, M = -x Z)
    assert L[2, 2] == pytest.approx(L[1, 1])
    assert L[2, 4] == pytest.approx(-L[1, 5], abs=1e-12)
    assert L[4, 2] == pytest.approx(-L[5, 1])
    assert L[4, 4] == pytest.approx(L[5, 5])


def test_no_separation_no_lift_and_full_separation_is_the_munk_moment():
    # separation at the tail: the whole body is potential, its lift is in C_A (none here)
    assert np.abs(slender_body_lift_matrix(X, S, -A, rho=RHO)).max() < 1e-9
    # separation at the nose: the whole potential force is taken away: N_uv = +rho V
    L = slender_body_lift_matrix(X, S, A, rho=RHO)
    volume = 4.0 / 3.0 * math.pi * R ** 2 * A
    assert -L[5, 1] == pytest.approx(RHO * volume, rel=1e-6)
    assert L[1, 1] == pytest.approx(0.0, abs=1e-9)


def test_yaw_rate_gives_rotary_terms_of_an_aft_force():
    """Separation aft of the reference point: a yaw rate makes the aft flow a sway to port,
    so Y_ur > 0 and N_ur < 0 (the measured signs of the SUBOFF bare hull)."""
    L = slender_body_lift_matrix(X, S, -1.0, rho=RHO)
    assert -L[1, 5] > 0.0 and -L[5, 5] < 0.0 and -L[1, 1] < 0.0


def test_moves_with_the_reference_point_like_a_damping_matrix():
    p = np.array([0.4, 0.0, 0.05])
    about_o = slender_body_lift_matrix(X, S, -1.2, rho=RHO)
    about_p = slender_body_lift_matrix(X, S, -1.2, rho=RHO, ref=p)
    assert np.allclose(transform_matrix(about_o, to_point=p), about_p, atol=1e-9 * RHO)


def test_separation_station_is_hopkins_correlation():
    # the spheroid's area falls fastest at its tail: s1 = l, s0 = (0.378 + 0.527) l
    x0 = separation_station(X, S)
    assert A - x0 == pytest.approx(0.905 * 2 * A, rel=1e-3)


def _vehicle(body_lift, length=2.0):
    return parse_vehicle({"name": "t", "body_lift": body_lift, "hull": {"profile": [
        {"type": "myring_tail", "x": [-length / 2, -0.3], "radius": 0.1, "theta_deg": 25.0,
         "length": length / 2 - 0.3},
        {"type": "cylinder", "x": [-0.3, 0.7], "radius": 0.1},
        {"type": "myring_nose", "x": [0.7, length / 2], "radius": 0.1, "n": 2.0,
         "length": length / 2 - 0.7}]}}, file="t.yaml")


def test_vehicle_option_slender():
    m = estimate(_vehicle("slender"))
    assert m.conditions.lift["body_lift"]["method"] == "slender"
    assert m.lift[1, 1] > 0 and -m.lift[1, 5] > 0 and -m.lift[5, 5] < 0


def test_vehicle_option_errors():
    with pytest.raises(InputError, match="body_lift"):
        _vehicle("yes")
    with pytest.raises(InputError, match="body_lift"):
        estimate(parse_vehicle({"name": "s", "body_lift": "slender", "hull": {"profile": [
            {"type": "cylinder", "x": [-0.2, 0.2], "radius": 0.15}]}}, file="s.yaml"))


def test_munk_factor_limits_and_values():
    """k2 - k1 of Lamb's spheroid (USAF DATCOM sec. 4.2.1.1): 0 for the sphere (k1 = k2 = 1/2),
    rising with the fineness towards slender-body theory's 1; SUBOFF (l/d 8.575) 0.924."""
    from stripcoef.hull.lift import munk_factor
    assert munk_factor(1.0, 1.0) == pytest.approx(0.0, abs=1e-12)
    assert munk_factor(8.575, 1.0) == pytest.approx(0.924, abs=0.001)
    assert 0.99 < munk_factor(1000.0, 1.0) < 1.0
    f = [munk_factor(ld, 1.0) for ld in (2.0, 4.0, 8.0, 16.0)]
    assert np.all(np.diff(f) > 0)
    with pytest.raises(ValueError, match="l >= d"):
        munk_factor(0.5, 1.0)


def test_vehicle_option_datcom_is_the_slender_rule_times_munk_factor():
    """body_lift: datcom is the slender rule's lift matrix (every term, static and rotary)
    times k2 - k1 of the hull's l/d; the summary names the rule and the factor."""
    from stripcoef.hull.lift import munk_factor
    s, d = estimate(_vehicle("slender")), estimate(_vehicle("datcom"))
    info = d.conditions.lift["body_lift"]
    assert info["method"] == "datcom"
    k = munk_factor(info["length"], info["diameter"])
    assert info["munk_factor"] == pytest.approx(k)
    assert 0.8 < k < 1.0
    np.testing.assert_allclose(d.lift, k * s.lift, rtol=1e-12, atol=1e-15)


def test_vehicle_option_error_names_every_rule():
    with pytest.raises(InputError, match="datcom"):
        _vehicle("hopkins")
