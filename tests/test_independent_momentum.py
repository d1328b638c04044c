"""The independent simulator's momentum drag (validation/independent.py) is Indiveri's (1998,
sec. 4.2.4, eta-md model): F_md = -alpha n_h w, n_h the mean |command| of the thrusters that do
not push in heave, and its strength the same share of the hull's heave drag on any vehicle."""

from __future__ import annotations

import numpy as np
import pytest

from validation.independent import (Simulator, Truth, idle_thrusters, momentum_drag,
                                    momentum_drag_alpha)


def _thruster(name, direction, position, ct, limit):
    d = np.asarray(direction, float)
    return {"name": name, "position": np.asarray(position, float),
            "direction": d / np.linalg.norm(d),
            "ct_forward": ct, "ct_backward": ct, "max_forward": limit, "max_backward": limit,
            "deadband": 0.0}


def _truth(ct: float, limit: float = 40.0, effect=None, strength=None) -> Truth:
    """A BlueROV2-Heavy-like layout: four vectored horizontal thrusters, four vertical ones
    (full command sqrt(limit / ct))."""
    h = [_thruster(f"h{i}", (1.0, s, 0.0), (x, y, 0.0), ct, limit)
         for i, (s, x, y) in enumerate([(-1, 0.15, 0.1), (1, 0.15, -0.1), (1, -0.15, 0.1),
                                        (-1, -0.15, -0.1)])]
    v = [_thruster(f"v{i}", (0.0, 0.0, 1.0), (x, y, -0.1), ct, limit)
         for i, (x, y) in enumerate([(0.1, 0.2), (0.1, -0.2), (-0.1, 0.2), (-0.1, -0.2)])]
    return Truth(m_rb=np.diag([11.5] * 3 + [0.2, 0.25, 0.25]),
                 m_a=np.diag([5.5, 12.7, 14.6, 0.12, 0.12, 0.12]),
                 d_l=np.diag([4.0, 6.2, 5.2, 0.07, 0.07, 0.07]),
                 d_q=np.diag([18.2, 21.7, 36.9, 1.5, 1.5, 1.5]),
                 weight=11.5 * 9.81, buoyancy=11.5 * 9.81, r_g=np.zeros(3),
                 r_b=np.array([0.0, 0.0, -0.02]), thrusters=h + v, effect=effect,
                 strength=strength)


def test_only_the_thrusters_that_do_not_push_in_heave_count():
    truth = _truth(40.0)
    idle = idle_thrusters(truth, 2)
    assert idle == [0, 1, 2, 3]
    n = np.array([0.5, -0.3, 0.2, -0.6, 0.9, 0.9, -0.9, 0.9])
    # n_h = mean(0.5, 0.3, 0.2, 0.6) = 0.4; F = -alpha n_h w, opposing w
    assert momentum_drag(2.0, n, idle, 0.25) == pytest.approx(-2.0 * 0.4 * 0.25, rel=1e-12)
    assert momentum_drag(2.0, n, idle, -0.25) == pytest.approx(2.0 * 0.4 * 0.25, rel=1e-12)
    # the vertical thrusters' commands do not enter; idle horizontal thrusters: no force
    n_vert = n.copy()
    n_vert[4:] = [-1.0, 0.1, 0.0, 0.3]
    assert momentum_drag(2.0, n_vert, idle, 0.25) == momentum_drag(2.0, n, idle, 0.25)
    assert momentum_drag(2.0, np.r_[np.zeros(4), n[4:]], idle, 0.25) == 0.0
    # linear in n_h and in w
    assert momentum_drag(2.0, 3 * n, idle, 0.25) == pytest.approx(
        3 * momentum_drag(2.0, n, idle, 0.25), rel=1e-12)
    assert momentum_drag(2.0, n, idle, 0.75) == pytest.approx(
        3 * momentum_drag(2.0, n, idle, 0.25), rel=1e-12)
    assert momentum_drag(2.0, n, [], 0.25) == 0.0


def test_the_simulator_applies_it_in_heave_only():
    """M nu_dot of the effect's truth minus the clean truth's is (0, 0, -alpha n_h w, 0, 0, 0)."""
    alpha, n = 3.0, np.array([0.4, -0.4, 0.8, 0.0, 0.5, 0.5, 0.5, 0.5])
    x = np.zeros(13 + 8)
    x[3] = 1.0
    x[7:13] = [0.2, -0.1, 0.3, 0.05, -0.02, 0.1]
    clean, with_md = Simulator(_truth(40.0)), Simulator(_truth(40.0, effect="momentum_drag",
                                                                strength=alpha))
    diff = with_md.m @ (with_md.rhs(x, n, 5.0)[7:13] - clean.rhs(x, n, 5.0)[7:13])
    assert diff == pytest.approx([0, 0, -alpha * 0.4 * 0.3, 0, 0, 0], abs=1e-12)


def test_the_same_share_is_the_same_force_whatever_the_command_units():
    """alpha n_full / d_w is the drawn share; a vehicle whose full command is 200x larger (a
    VideoRay's ~220 against a BlueROV2's 1, same thrust) gets a 200x smaller alpha, the same
    force at the same share of full command."""
    unit, big = _truth(40.0), _truth(40.0 / 200.0 ** 2)
    a_unit, a_big = momentum_drag_alpha(unit, 0.7), momentum_drag_alpha(big, 0.7)
    assert a_big == pytest.approx(a_unit / 200.0, rel=1e-12)
    # d_w: D_L + D_Q w_max with D_L w_max + D_Q w_max^2 = 4 x 40 N
    w_max = (-5.2 + np.sqrt(5.2 ** 2 + 4 * 36.9 * 160.0)) / (2 * 36.9)
    assert a_unit * 1.0 == pytest.approx(0.7 * (5.2 + 36.9 * w_max), rel=1e-12)
    n_unit, n_big = np.full(8, 0.6), np.full(8, 0.6 * 200.0)
    idle = idle_thrusters(unit, 2)
    assert momentum_drag(a_big, n_big, idle, 0.3) == pytest.approx(
        momentum_drag(a_unit, n_unit, idle, 0.3), rel=1e-12)
