"""Steady turning circle: properties and the MARES Munk paradox (Ferreira et al. 2009 sec. V.D)."""

import math

import numpy as np
import pytest

from limits_helpers import make_model
from stripcoef.errors import InputError, UnreachableError
from stripcoef.limits.solver import (LimitOptions, min_turning_radius, required_force, solve_limits,
                              steady_turn, turn_limit, turning_curve)

RADII = [0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0]


@pytest.fixture(scope="module")
def model():
    return make_model()


@pytest.mark.parametrize("munk", [True, False])
def test_u_max_rises_towards_straight_line(model, munk):
    res = solve_limits(model, radii=RADII, munk=munk)
    u = np.array([p.u_max for p in res.turning])
    assert np.all(np.diff(u) > 0.0)
    assert np.all(u < res.surge_speed_max)
    # the Munk moment decays only like R^-1/2 (drift angle ~ R^-1/2), so the straight
    # line is approached slowly with it
    assert turn_limit(model, 1e7, options=LimitOptions(munk=munk)).u_max == pytest.approx(
        res.surge_speed_max, rel=0.01)
    if not munk:
        assert u[-1] == pytest.approx(res.surge_speed_max, rel=0.03)


def test_turn_is_a_steady_balance(model):
    p = turn_limit(model, 3.0, options=LimitOptions(munk=False))
    nu = [p.u_max, p.v, 0, 0, 0, p.yaw_rate]
    tau = required_force(model, nu, options=LimitOptions(munk=False))
    b = model.allocation()
    t = np.array([p.thrust[n] for n in p.thrust])
    # every thruster-controlled row balances; the sway row balances with no sway thrust
    for row in (0, 1, 2, 4, 5):
        assert (b @ t)[row] == pytest.approx(tau[row], abs=1e-7)
    assert p.yaw_rate == pytest.approx(math.hypot(p.u_max, p.v) / 3.0, rel=1e-12)
    assert max(abs(x) for x in p.thrust.values()) == pytest.approx(10.0, rel=1e-6)


def test_nose_points_into_the_circle(model):
    # Ferreira et al. 2009, eq. 60: v = 0 does not balance sway; the nose points to the centre
    for p in turning_curve(model, RADII):
        assert p.v < 0.0 and p.drift_angle > 0.0


def test_drift_angle_falls_with_radius(model):
    d = [p.drift_angle for p in turning_curve(model, RADII, options=LimitOptions(munk=False))]
    assert np.all(np.diff(d) < 0.0)


def test_without_coriolis_a_symmetric_vehicle_does_not_drift(model):
    for p in turning_curve(model, [1.0, 5.0], options=LimitOptions(coriolis=False)):
        assert p.v == pytest.approx(0.0, abs=1e-12)


def test_munk_paradox_on_hand_built_slender_body(model):
    b = model.allocation()
    with_munk = turning_curve(model, [2.0, 4.0, 8.0, 16.0], options=LimitOptions(munk=True))
    without = turning_curve(model, [2.0, 4.0, 8.0, 16.0], options=LimitOptions(munk=False))
    for p in with_munk:
        n_thr = b[5] @ np.array(list(p.thrust.values()))
        assert p.yaw_rate > 0.0 and n_thr < 0.0       # moment opposes the rotation
    for p in without:
        n_thr = b[5] @ np.array(list(p.thrust.values()))
        assert n_thr > 0.0
        assert p.saturated == "P1"                     # port = outer in a starboard turn


def test_steady_turn_above_u_max_is_unreachable(model):
    p = turn_limit(model, 4.0)
    ok = steady_turn(model, 4.0, 0.9 * p.u_max)
    assert max(abs(x) for x in ok.thrust.values()) < 10.0
    with pytest.raises(UnreachableError, match="thrust") as err:
        steady_turn(model, 4.0, 1.05 * p.u_max)
    # the message names the smallest circle at that speed, which is larger than 4 m
    rmin = float(str(err.value).split("R = ")[1].split(" m")[0])
    assert rmin > 4.0
    assert rmin == pytest.approx(min_turning_radius(model, 1.05 * p.u_max), rel=1e-3)


def test_min_turning_radius_inverts_u_max(model):
    p = turn_limit(model, 5.0)
    assert min_turning_radius(model, p.u_max) == pytest.approx(5.0, rel=1e-6)
    with pytest.raises(UnreachableError):
        min_turning_radius(model, 1.01 * solve_limits(model, radii=[1.0]).surge_speed_max)


@pytest.mark.parametrize("radii", [[-1.0, 2.0], [2.0, 1.0], [1.0, 1.0], [0.0], []])
def test_bad_radii(model, radii):
    with pytest.raises(InputError, match="radi"):
        turning_curve(model, radii)


def test_mirrored_vehicle_turns_the_same_with_thrusters_swapped(model):
    # a starboard turn of the mirror image (y -> -y) is the port turn of the original;
    # for a port-starboard symmetric vehicle both must give the same u_max
    from dataclasses import replace
    mirrored = replace(model, thrusters=[
        replace(t, position=np.array(t.position) * [1, -1, 1]) for t in model.thrusters])
    a = turning_curve(model, [2.0, 8.0], options=LimitOptions(munk=False))
    b = turning_curve(mirrored, [2.0, 8.0], options=LimitOptions(munk=False))
    for pa, pb in zip(a, b):
        assert pb.u_max == pytest.approx(pa.u_max, rel=1e-9)
        assert pb.thrust["P2"] == pytest.approx(pa.thrust["P1"], rel=1e-7)
        assert pb.saturated == "P2"


def test_straight_line_limits_do_not_depend_on_the_reference_point():
    # pure translation is the same motion about any point: M_RB, M_A, D_L and the
    # translation columns of D_Q move exactly (HydroModel.about), g and B with the point
    import warnings
    from stripcoef.limits.solver import heave_limit, surge_limit
    m = make_model(buoyancy_ratio=1.02)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        moved = m.about([0.3, 0.0, 0.05])
    for f in (surge_limit, heave_limit):
        assert f(moved).speed == pytest.approx(f(m).speed, rel=1e-9)


def test_steady_turn_is_where_the_dynamics_settle():
    # integrate M nu_dot = B T - tau_req(nu) from rest with the thrusts of the turn at its
    # limit (Munk off): the vehicle must settle on (u_max, v, r) - the steady state the
    # solver found is the attractor, with the same signs as the equations of motion
    from scipy.integrate import solve_ivp
    m = make_model(z_g=0.0)
    opts = LimitOptions(munk=False)
    p = turn_limit(m, 3.0, options=opts)
    tau = m.allocation() @ np.array([p.thrust[t.name] for t in m.thrusters])
    minv = np.linalg.inv(m.mass_matrix)

    def rhs(_, nu):
        return minv @ (tau - required_force(m, nu, options=opts))

    sol = solve_ivp(rhs, (0.0, 400.0), np.zeros(6), rtol=1e-9, atol=1e-12)
    u, v, r = sol.y[0, -1], sol.y[1, -1], sol.y[5, -1]
    assert u == pytest.approx(p.u_max, rel=1e-4)
    assert v == pytest.approx(p.v, rel=1e-3)
    assert r == pytest.approx(p.yaw_rate, rel=1e-4)
