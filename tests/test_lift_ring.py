"""The ring (annular) wing as a lift element: Weissinger's lift slope against its exact limits,
Fletcher's measured rings and a vortex lattice, its lift matrix (in the hull's separated wake
too), bad input, and ring wing No. 1 on the SUBOFF hull against Roddy's configuration 6 minus 3
(issue 34; docs/validation.md, 'The ring wing')."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stripcoef.assembly.lift import ring_wing_lift
from stripcoef.errors import InputError
from stripcoef.geometry.vehicle import parse_vehicle
from stripcoef.hull.lift import fin_lift_slope, ring_wing_lift_matrix, ring_wing_lift_slope


def test_ring_slope_has_the_slender_and_lifting_line_limits():
    """Weissinger's closed form (Wagner 2021 eq. 15) has both exact limits: A -> 0 (a long
    chord), slender-body theory's pi A (exterior circle plus the enclosed fluid, 2 rho pi
    R^2), twice the planar slender wing's pi A / 2 (Helmbold's planar limit); A -> infinity (a
    short chord), Ribner's lifting line pi^2 / (1 + pi / 2A), to first order in 1/A."""
    for a in (1e-4, 1e-3):
        assert ring_wing_lift_slope(a) == pytest.approx(math.pi * a, rel=1e-3)
        assert ring_wing_lift_slope(a) == pytest.approx(2.0 * fin_lift_slope(a, efficiency=1.0),
                                                        rel=2e-3)
    for a in (1e3, 1e4):
        line = math.pi ** 2 / (1.0 + 0.5 * math.pi / a)
        assert ring_wing_lift_slope(a) == pytest.approx(line, rel=2.0 / a ** 2)
    a = np.array([0.3, 1.0, 3.0, 10.0])
    slope = ring_wing_lift_slope(a)
    assert np.all(np.diff(slope) > 0) and np.all(slope < math.pi * a)   # below both limits
    assert np.all(slope < math.pi ** 2 / (1.0 + 0.5 * math.pi / a))
    # by hand at A = 1: pi^2 / (1 + pi/2 + arctan 1.2) = 2.8633 /rad
    assert ring_wing_lift_slope(1.0) == pytest.approx(2.8633, abs=1e-4)
    with pytest.raises(ValueError, match="D/c > 0"):
        ring_wing_lift_slope(0.0)


def _fletcher():
    """Fletcher 1957 (NACA TN 4117, Fig. 11): (A = D/c, slope [1/rad] on D c, its reading
    tolerance [1/rad]) of his five rings (reference_tables/annular_wing)."""
    from validation import reference as ref
    out = []
    for i in range(1, 6):
        a = ref.reference_value("annular_wing", f"A.{i}")["value"]
        row = ref.reference_value("annular_wing", f"CLa.{i}")
        out.append((a, math.degrees(row["value"]), math.degrees(row["atol"])))
    return out


def test_ring_slope_against_fletchers_measured_rings():
    """Weissinger's slope within 3 % of Fletcher's five measured rings, A = 1/3 to 3 (the
    largest gap 2.3 %, at A = 2/3 and 3; the reading's own tolerance is 0.001 /deg, 1-5.6 %);
    the earlier model (Helmbold's interpolation with the fins' a = 0.9) was 5 % low at A = 1/3."""
    for a, measured, _ in _fletcher():
        assert ring_wing_lift_slope(a) == pytest.approx(measured, rel=0.03), a


def test_a_ring_of_vanishing_chord_carries_no_force_and_a_long_one_the_slender_force():
    """The force k = 1/2 rho (2 R c) C_La: c -> 0 (A -> infinity), k -> 0 as c pi^2 (the
    lifting line); c/D -> infinity, k -> 2 rho pi R^2 (slender-body theory's ring: Hoerner's
    L = q pi D^2 alpha, twice the solid body of the same diameter)."""
    rho, radius = 1000.0, 0.12
    ks = []
    for c in (1e-6, 1e-8):
        ks.append(ring_wing_lift_matrix(radius, c, [0.0, 0.0, 0.0], rho=rho)[1, 1])
        assert ks[-1] == pytest.approx(0.5 * rho * 2.0 * radius * c * math.pi ** 2, rel=1e-4)
    assert ks[1] == pytest.approx(1e-2 * ks[0], rel=1e-4)        # -> 0 with the chord
    for c in (1e3, 1e5):
        k = ring_wing_lift_matrix(radius, c * radius, [0.0, 0.0, 0.0], rho=rho)[1, 1]
        assert k == pytest.approx(2.0 * rho * math.pi * radius ** 2, rel=2.0 / c)


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
    stern, info = ring_wing_lift(_hull(), 1000.0, [0, 0, 0], wake=False, **ring)
    assert info_free["pressure_ratio"] == 1.0
    assert 0.0 < info["pressure_ratio"] < 1.0
    np.testing.assert_allclose(stern, free * info["pressure_ratio"], atol=1e-12)


def test_wake_fraction_takes_the_cross_flow_at_the_separation_station_off():
    """f = 1: the ring answers w - w_0, the cross-flow relative to a wake moving with the
    body's cross-velocity at x_0: nothing in sway or heave, k (x_w - x_0) in yaw and pitch
    rate, the force still at the quarter chord x."""
    x, c, x0 = -1.7, 0.23, -1.2
    xw = x - 0.5 * c
    free = ring_wing_lift_matrix(0.12, c, [x, 0.0, 0.0], rho=1000.0)
    m = ring_wing_lift_matrix(0.12, c, [x, 0.0, 0.0], rho=1000.0, wake_fraction=1.0,
                              wake_point=[x0, 0.0, 0.0])
    k = free[1, 1]
    assert m[1, 1] == pytest.approx(0.0, abs=1e-12) and m[2, 2] == pytest.approx(0.0, abs=1e-12)
    assert m[5, 1] == pytest.approx(0.0, abs=1e-12) and m[4, 2] == pytest.approx(0.0, abs=1e-12)
    assert m[1, 5] == pytest.approx((xw - x0) * k) and m[5, 5] == pytest.approx(x * (xw - x0) * k)
    assert m[2, 4] == pytest.approx(-(xw - x0) * k)
    half = ring_wing_lift_matrix(0.12, c, [x, 0.0, 0.0], rho=1000.0, wake_fraction=0.5,
                                 wake_point=[x0, 0.0, 0.0])
    np.testing.assert_allclose(half, 0.5 * (free + m), atol=1e-12)
    for bad in ({"wake_fraction": 1.5, "wake_point": [x0, 0, 0]}, {"wake_fraction": 0.5}):
        with pytest.raises(ValueError, match="0 <= f <= 1"):
            ring_wing_lift_matrix(0.12, c, [x, 0.0, 0.0], rho=1000.0, **bad)


def test_ring_inside_the_separated_wake_lifts_only_in_rotation():
    """On the test hull (slender rule: Hopkins's station at x = -0.805 m, where the section's
    radius 0.059 m is above the ring's) the ring behind it has f = 1: no sway force; ahead of
    the station, or under Hoerner's rule (no station), f = 0; a ring wider than the wake's
    section takes f = S(x_0) / (pi R^2). The rule is an option (``wake=True``); the default is
    the ring in the undisturbed cross-flow."""
    ring = {"x_le": -0.82, "x_te": -0.95, "r_le": 0.055, "r_te": 0.055}
    assert ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **ring)[1]["wake_fraction"] == 0.0
    ring = {**ring, "wake": True}
    m, info = ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **ring)
    assert info["wake_fraction"] == 1.0 and info["separation_radius"] > 0.055
    assert m[1, 1] == pytest.approx(0.0, abs=1e-12) and m[1, 5] < 0.0     # Y_ur = -L[1, 5] > 0
    off, info_off = ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **{**ring, "wake": False})
    assert info_off["wake_fraction"] == 0.0 and off[1, 1] > 0.0
    ahead = {"x_le": -0.75, "x_te": -0.9, "r_le": 0.09, "r_te": 0.09, "wake": True}
    assert ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **ahead)[1]["wake_fraction"] == 0.0
    assert ring_wing_lift(_hull("on"), 1000.0, [0, 0, 0], **ring)[1]["wake_fraction"] == 0.0
    wide = {"x_le": -0.82, "x_te": -0.95, "r_le": 0.09, "r_te": 0.09, "wake": True}
    f = ring_wing_lift(_hull(), 1000.0, [0, 0, 0], **wide)[1]
    assert f["wake_fraction"] == pytest.approx((f["separation_radius"] / 0.09) ** 2)
    assert 0.0 < f["wake_fraction"] < 1.0


# ---------------------------------------------------------------------------
# ring wing No. 1 on SUBOFF against Roddy's configuration 6 - 3 (docs/validation.md)
# ---------------------------------------------------------------------------
def _increments(method, wake=True):
    from validation.lift import suboff_derivatives
    a, b = suboff_derivatives(3, method), suboff_derivatives(3, method, True, wake=wake)
    return {k: b[k] - a[k] for k in ("Yv", "Nv", "Yr", "Nr")}


def _measured():
    from validation.lift import val
    return {k: val(f"c6.{k}") - val(f"c3.{k}") for k in ("Yv", "Nv", "Yr", "Nr")}


def _bare_yv():
    from validation.lift import val
    return val("c3.Yv")


@pytest.mark.slow
@pytest.mark.parametrize("method", ["datcom", "stratford_panel"])
def test_ring_drift_increment_against_configuration_6(method):
    """Roddy's ring adds nothing in drift (configuration 6 - 3: Y'_v +0.000005, N'_v
    -0.000144); the ring inside the hull's separated wake (ring radius 0.39 ft, the section at
    the separation station 0.72 ft (DATCOM) or 0.49 ft (Stratford on the panel flow)) adds
    nothing either; without the wake rule it added Y'_v -0.0025 to -0.0027."""
    model, measured = _increments(method), _measured()
    assert abs(model["Yv"] - measured["Yv"]) <= 0.15 * abs(_bare_yv())
    assert abs(model["Nv"] - measured["Nv"]) <= 0.05 * abs(measured["Nv"] - _bare_yv())
    old = _increments(method, wake=False)
    assert old["Yv"] < -0.002


@pytest.mark.slow
def test_ring_rotary_increments_against_configuration_6():
    """In yaw rotation the ring in the wake answers (x_r - x_0) r only: the measured sign, 0.20
    (Y'_r) and 0.28 (N'_r) of the measured increments under the default rule; without the wake
    rule 0.67 and 0.92 (docs/validation.md, 'The ring wing'); nothing fitted."""
    model, measured = _increments("datcom"), _measured()
    assert model["Yr"] / measured["Yr"] == pytest.approx(0.20, abs=0.03)
    assert model["Nr"] / measured["Nr"] == pytest.approx(0.28, abs=0.03)
    old = _increments("datcom", wake=False)
    assert old["Yr"] / measured["Yr"] == pytest.approx(0.67, abs=0.03)
    assert old["Nr"] / measured["Nr"] == pytest.approx(0.92, abs=0.03)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason=(
    "Roddy's ring adds Y'_r +0.0020, N'_r -0.00073 in yaw rotation (a force 0.36 L_BP aft of "
    "the moment point, ahead of the ring at 0.52) and nothing in drift; a ring answering the "
    "cross-flow relative to the wake gives 0.15-0.20 of Y'_r, one answering the local "
    "cross-flow 0.67-0.72 with a drift force the data do not have: the ring's effect on the "
    "afterbody's flow ahead of it is not modelled"))
def test_ring_rotary_increment_within_25_percent():
    model, measured = _increments("datcom"), _measured()
    assert model["Yr"] / measured["Yr"] == pytest.approx(1.0, abs=0.25)


def test_ring_slope_against_a_vortex_lattice():
    """Weissinger's closed form against a lifting-surface solution of the thin cylindrical
    ring (validation.lift.ring_vortex_lattice, 32 x 6 panels) at SUBOFF's ring wing No. 1
    (A = 1.05): 3.022 against 2.984 /rad, within 2 %."""
    from validation.lift import ring_vortex_lattice
    assert ring_vortex_lattice(1.05) == pytest.approx(3.022, abs=0.002)
    assert ring_wing_lift_slope(1.05) == pytest.approx(ring_vortex_lattice(1.05), rel=0.02)


@pytest.mark.parametrize("aspect_ratio", [0.3, 3.0, 10.0])
def test_ring_slope_against_a_vortex_lattice_across_aspect_ratios(aspect_ratio):
    """Within 2 % of the vortex lattice (64 x 8 panels) from A = 0.3 to 10."""
    from validation.lift import ring_vortex_lattice
    assert ring_wing_lift_slope(aspect_ratio) == pytest.approx(
        ring_vortex_lattice(aspect_ratio, 64, 8), rel=0.02)
