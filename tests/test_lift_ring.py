"""The ring (annular) wing as a lift element: its lift slope's exact limits, its lift matrix,
bad input, and ring wing No. 1 on the SUBOFF hull against Roddy's configuration 6 minus 3
(issue 34; docs/validation.md, 'The ring wing')."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stripcoef.assembly.lift import ring_wing_lift
from stripcoef.errors import InputError
from stripcoef.geometry.vehicle import parse_vehicle
from stripcoef.hull.lift import (FIN_EFFICIENCY, fin_lift_slope, ring_wing_lift_matrix,
                                 ring_wing_lift_slope)


def test_ring_slope_has_the_slender_and_lifting_line_limits():
    """A -> 0: slender-body theory's pi A (exterior circle plus the enclosed fluid, 2 rho pi
    R^2), twice the planar slender wing's pi A / 2 (Helmbold's planar limit); A -> infinity:
    the ring's lifting line (pi a0 / 2) / (1 + a0 / 4A), to first order in 1/A."""
    for a in (1e-4, 1e-3):
        assert ring_wing_lift_slope(a) == pytest.approx(math.pi * a, rel=1e-3)
        assert ring_wing_lift_slope(a) == pytest.approx(2.0 * fin_lift_slope(a), rel=2e-3)
    a0 = 2.0 * math.pi * FIN_EFFICIENCY
    for a in (1e3, 1e4):
        line = 0.5 * math.pi * a0 / (1.0 + a0 / (4.0 * a))
        assert ring_wing_lift_slope(a) == pytest.approx(line, rel=(a0 / a) ** 2)
    a = np.array([0.3, 1.0, 3.0, 10.0])
    slope = ring_wing_lift_slope(a)
    assert np.all(np.diff(slope) > 0) and np.all(slope < math.pi * a)   # below both limits
    assert np.all(slope < 0.5 * math.pi * a0 / (1.0 + a0 / (4.0 * a)))
    with pytest.raises(ValueError, match="D/c > 0"):
        ring_wing_lift_slope(0.0)


def test_ring_lift_matrix_is_axisymmetric_and_answers_the_local_cross_flow():
    """Sway and heave alike; a force at the quarter chord x answering v + x_w r, the rotation's
    incidence at the three-quarter chord x_w = x - c/2 (hull.lift.rotary_incidence_point): Y_ur = x_w Y_uv,
    N_uv = x Y_uv, N_ur = x x_w Y_uv; the sideslip and heave terms symmetric (N_uv = Y_ur
    only where x_w = x)."""
    x, c = -1.7, 0.23
    xw = x - 0.5 * c
    m = ring_wing_lift_matrix(0.12, c, [x, 0.0, 0.0], rho=1000.0, pressure_ratio=0.5)
    k = 0.5 * 1000.0 * 2 * 0.12 * c * ring_wing_lift_slope(2 * 0.12 / c) * 0.5
    assert m[1, 1] == pytest.approx(k) and m[2, 2] == pytest.approx(k)
    assert m[1, 5] == pytest.approx(xw * k) and m[5, 1] == pytest.approx(x * k)
    assert m[5, 5] == pytest.approx(x * xw * k)
    assert m[2, 4] == pytest.approx(-xw * k) and m[4, 2] == pytest.approx(-x * k)
    assert m[4, 4] == pytest.approx(x * xw * k)
    np.testing.assert_allclose(m[:3, :3], m[:3, :3].T, atol=1e-12)
    with pytest.raises(ValueError, match="R, c > 0"):
        ring_wing_lift_matrix(0.0, 0.2, [0, 0, 0], rho=1000.0)


def _hull(body_lift="slender"):
    """A 2 m spheroid-like hull of revolution (l/d = 10), x forward from its middle [m]."""
    xs = np.linspace(-1.0, 1.0, 201)
    pts = [[float(x), float(0.1 * math.sqrt(max(1.0 - x * x, 0.0)))] for x in xs]
    return parse_vehicle({"name": "ring test", "fluid": {"water": "fresh"},
                          "body_lift": body_lift, "reference_speed": 2.0,
                          "hull": {"profile": [{"type": "table", "x": [-1.0, 1.0],
                                                "points": pts}]}},
                         file="ring.yaml")


@pytest.mark.parametrize("kw,text", [
    ({"x_le": 1.5, "x_te": 0.8, "r_le": 0.15, "r_te": 0.15}, "outside the hull's length"),
    ({"x_le": 0.8, "x_te": 0.9, "r_le": 0.15, "r_te": 0.15}, "outside the hull's length"),
    ({"x_le": -0.8, "x_te": -0.9, "r_le": 0.15, "r_te": -0.1}, "outside the hull's length"),
    ({"x_le": 0.1, "x_te": 0.0, "r_le": 0.05, "r_te": 0.05}, "inside the hull"),
])
def test_bad_ring_is_a_one_line_error(kw, text):
    with pytest.raises(InputError, match=text) as err:
        ring_wing_lift(_hull(), 1000.0, [0.0, 0.0, 0.0], **kw)
    assert "\n" not in str(err.value)


def test_ring_in_the_stern_flow_lifts_less_than_in_the_free_stream():
    """Under ``body_lift: slender`` the ring sits in the hull's layer and slowed stern flow
    (pressure ratio < 1); under Hoerner's rule it sees the free stream (ratio 1)."""
    ring = {"x_le": -0.75, "x_te": -0.9, "r_le": 0.09, "r_te": 0.09}
    free, info_free = ring_wing_lift(_hull("on"), 1000.0, [0, 0, 0], **ring)
    stern, info = ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **ring)
    assert info_free["pressure_ratio"] == 1.0
    assert 0.0 < info["pressure_ratio"] < 1.0
    np.testing.assert_allclose(stern, free * info["pressure_ratio"], atol=1e-12)


# ---------------------------------------------------------------------------
# ring wing No. 1 on SUBOFF against Roddy's configuration 6 - 3 (docs/validation.md)
# ---------------------------------------------------------------------------
def _increments(method):
    from validation.lift import suboff_derivatives
    a, b = suboff_derivatives(3, method), suboff_derivatives(3, method, True)
    return {k: b[k] - a[k] for k in ("Yv", "Nv", "Yr", "Nr")}


def _measured():
    from validation.lift import val
    return {k: val(f"c6.{k}") - val(f"c3.{k}") for k in ("Yv", "Nv", "Yr", "Nr")}


@pytest.mark.slow
def test_ring_rotary_increments_against_configuration_6():
    """In yaw rotation the model's ring in the stern flow (body_lift: slender) gives the
    measured increments' sign and 0.66 (Y'_r) and 0.91 (N'_r) of them (docs/validation.md,
    'The ring wing'); nothing fitted."""
    model, measured = _increments("slender"), _measured()
    assert model["Yr"] / measured["Yr"] == pytest.approx(0.66, abs=0.05)
    assert model["Nr"] / measured["Nr"] == pytest.approx(0.91, abs=0.05)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "Roddy's ring adds nothing in drift (configuration 6 - 3: Y'_v +0.000005, within 0.1 % of "
    "the bare hull's) while it lifts in yaw rotation; the model's ring, a lift answering the "
    "local cross-flow, adds Y'_v -0.0025 in the stern flow (-0.0089 in the free stream): the "
    "sidewash of the afterbody's shed vortices in drift is not modelled (no published method "
    "found)"))
def test_ring_drift_increment_against_configuration_6():
    model, measured = _increments("slender"), _measured()
    assert abs(model["Yv"] - measured["Yv"]) <= 0.15 * abs(_bare_yv())


def _bare_yv():
    from validation.lift import val
    return val("c3.Yv")


def test_ring_slope_against_a_vortex_lattice():
    """The interpolation against a lifting-surface solution of the thin cylindrical ring
    (validation.lift.ring_vortex_lattice, 32 x 6 panels, a = 1 in both) at SUBOFF's ring
    wing No. 1 (A = 1.05): 3.022 against 2.995 /rad, within 2 %."""
    from validation.lift import ring_vortex_lattice
    assert ring_vortex_lattice(1.05) == pytest.approx(3.022, abs=0.002)
    assert ring_wing_lift_slope(1.05, efficiency=1.0) == pytest.approx(
        ring_vortex_lattice(1.05), rel=0.02)


@pytest.mark.parametrize("aspect_ratio", [0.3, 3.0, 10.0])
def test_ring_slope_against_a_vortex_lattice_across_aspect_ratios(aspect_ratio):
    """Within 2 % of the vortex lattice (64 x 8 panels) from A = 0.3 to 10."""
    from validation.lift import ring_vortex_lattice
    assert ring_wing_lift_slope(aspect_ratio, efficiency=1.0) == pytest.approx(
        ring_vortex_lattice(aspect_ratio, 64, 8), rel=0.02)
