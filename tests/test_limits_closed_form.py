"""Single-DOF limits against closed forms, and scaling properties (Ferreira et al. 2009 sec. V.A-C)."""

import math

import numpy as np
import pytest

from limits_helpers import horizontal_pair, make_model, vertical_pair
from stripcoef.errors import UnreachableError
from stripcoef.limits.solver import (LimitOptions, heave_limit, surge_limit, sway_limit, yaw_limit,
                              solve_limits)
from validation.limits import closed_form_cases, quadratic_speed
from stripcoef.thrusters import Thruster


def test_report_closed_forms_agree():
    for case, solver, exact in closed_form_cases():
        assert solver == pytest.approx(exact, rel=1e-9), case


def test_surge_closed_form():
    m = make_model(linear=(3.0, 5, 5, 0.5, 1, 1), quadratic=(30.0, 150, 150, 1, 20, 20))
    lim = surge_limit(m)
    assert lim.speed == pytest.approx(quadratic_speed(20.0, 3.0, 30.0), rel=1e-9)
    assert sorted(lim.at_limit) == ["P1", "P2"]
    assert lim.thrust["P1"] == pytest.approx(10.0) and lim.thrust["P2"] == pytest.approx(10.0)


def test_surge_uses_forward_limit_and_reverse_is_separate():
    # forward 10 N, backward 4 N: forward speed must use the forward limit only
    m = make_model(thrusters=horizontal_pair(10.0, backward=4.0) + vertical_pair(10.0))
    assert surge_limit(m).speed == pytest.approx(quadratic_speed(20.0, 2.0, 20.0), rel=1e-9)


@pytest.mark.parametrize("ratio", [1.0, 0.97, 1.03])
def test_heave_closed_form_with_weight_and_buoyancy(ratio):
    m = make_model(buoyancy_ratio=ratio)
    w_minus_b = m.weight - m.buoyancy
    lim = heave_limit(m)
    # FRD: z down, d_L w + d_Q w|w| = T_z + (W - B)
    assert lim.speed == pytest.approx(quadratic_speed(20.0 + w_minus_b, 5.0, 150.0), rel=1e-9)


def test_yaw_on_the_spot_closed_form():
    m = make_model()
    lim = yaw_limit(m)
    # two 10 N thrusters at y = +-0.1 m, opposite thrust: N = 2 N m
    assert lim.speed == pytest.approx(quadratic_speed(2.0, 1.0, 20.0), rel=1e-9)
    assert lim.thrust["P1"] == pytest.approx(10.0) and lim.thrust["P2"] == pytest.approx(-10.0)


def test_sway_none_without_sway_thruster_and_closed_form_with_one():
    m = make_model()
    assert sway_limit(m) is None
    side = Thruster("S", np.array([0.0, 0, 0]), np.array([0, 1.0, 0]), max_forward=6.0,
                    max_backward=6.0)
    m2 = make_model(thrusters=horizontal_pair(10.0) + vertical_pair(10.0) + [side])
    assert sway_limit(m2).speed == pytest.approx(quadratic_speed(6.0, 5.0, 150.0), rel=1e-9)
    assert solve_limits(m2, radii=[5.0]).to_dict()["sway_speed_max"] == pytest.approx(
        quadratic_speed(6.0, 5.0, 150.0), rel=1e-9)


def test_quadratic_drag_doubling_thrust_scales_speed_by_sqrt2():
    lin0 = (0.0,) * 6
    a = make_model(linear=lin0)
    b = make_model(linear=lin0, thrusters=horizontal_pair(20.0) + vertical_pair(20.0))
    for f in (surge_limit, heave_limit, yaw_limit):
        assert f(b).speed == pytest.approx(math.sqrt(2.0) * f(a).speed, rel=1e-9)
    # the whole turning curve scales too (all terms quadratic in speed)
    ra = solve_limits(a, radii=[1.0, 3.0, 9.0])
    rb = solve_limits(b, radii=[1.0, 3.0, 9.0])
    for pa, pb in zip(ra.turning, rb.turning):
        assert pb.u_max == pytest.approx(math.sqrt(2.0) * pa.u_max, rel=1e-7)
        assert pb.drift_angle == pytest.approx(pa.drift_angle, abs=1e-7)


def test_linear_drag_doubling_thrust_doubles_speed():
    quad0 = (0.0,) * 6
    a = make_model(quadratic=quad0)
    b = make_model(quadratic=quad0, thrusters=horizontal_pair(20.0) + vertical_pair(20.0))
    assert surge_limit(b).speed == pytest.approx(2.0 * surge_limit(a).speed, rel=1e-9)


def test_no_yaw_thruster_is_unreachable_not_nan():
    m = make_model(thrusters=[Thruster("T", np.array([-0.5, 0, 0]), np.array([1.0, 0, 0]),
                                       max_forward=10.0, max_backward=10.0)] + vertical_pair(5))
    with pytest.raises(UnreachableError, match="yaw"):
        yaw_limit(m)


def test_cannot_hold_depth_is_unreachable():
    m = make_model(buoyancy_ratio=0.5)          # 245 N too heavy for 2 x 10 N
    with pytest.raises(UnreachableError, match="zero speed"):
        surge_limit(m)


def test_no_drag_in_a_direction_has_no_finite_limit():
    m = make_model(linear=(0.0, 5, 5, 0.5, 1, 1), quadratic=(0.0, 150, 150, 1, 20, 20))
    with pytest.raises(UnreachableError, match="no finite limit"):
        surge_limit(m)


def test_coriolis_option_does_not_change_straight_line():
    m = make_model()
    a = surge_limit(m, options=LimitOptions(coriolis=False))
    assert a.speed == pytest.approx(surge_limit(m).speed, rel=1e-12)


def test_redundant_thrusters_use_the_linear_programme():
    # two identical pairs of 5 N thrusters = one pair of 10 N (the LP shares the load)
    pair_a = horizontal_pair(5.0)
    pair_b = [Thruster(t.name + "b", t.position, t.direction, max_forward=5.0,
                       max_backward=5.0) for t in pair_a]
    red = make_model(thrusters=pair_a + pair_b + vertical_pair(10.0))
    ref = make_model()
    from stripcoef.limits.solver import _Allocator
    assert _Allocator(red).square is None and _Allocator(ref).square is not None
    for f in (surge_limit, heave_limit, yaw_limit):
        assert f(red).speed == pytest.approx(f(ref).speed, rel=1e-7)
    a = solve_limits(red, radii=[2.0, 6.0])
    b = solve_limits(ref, radii=[2.0, 6.0])
    for pa, pb in zip(a.turning, b.turning):
        assert pa.u_max == pytest.approx(pb.u_max, rel=1e-7)


def test_direct_allocation_equals_linear_programme():
    from stripcoef.limits.solver import _Allocator
    m = make_model()
    alloc = _Allocator(m)
    tau = np.array([3.0, 0.0, 2.0, 0.1, 0.5, 0.3])
    s_direct, t_direct = alloc.utilisation(tau)
    alloc.square = None
    s_lp, t_lp = alloc.utilisation(tau)
    assert s_lp == pytest.approx(s_direct, rel=1e-7)
    np.testing.assert_allclose(t_lp, t_direct, rtol=1e-6, atol=1e-9)


def test_buoyant_vehicle_without_vertical_thrusters_is_a_clear_error():
    m = make_model(buoyancy_ratio=1.01, thrusters=horizontal_pair(10.0))
    with pytest.raises(UnreachableError, match="heave force Z"):
        surge_limit(m)
    # neutrally buoyant: the horizontal limits exist, the dive does not
    m0 = make_model(thrusters=horizontal_pair(10.0))
    assert surge_limit(m0).speed == pytest.approx(quadratic_speed(20.0, 2.0, 20.0), rel=1e-9)
    with pytest.raises(UnreachableError, match="heave"):
        heave_limit(m0)
