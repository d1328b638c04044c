"""``body_lift: slender``: the fins' slender-body interference (Pitts, Nielsen & Kaattari 1957)
and boundary-layer dynamic pressure, their properties, and the errors of bad input kept under it
(issue 34; the SUBOFF comparison is in tests/test_lift_data.py)."""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml

from stripcoef import estimate
from stripcoef.cli import main
from stripcoef.errors import ModelWarning
from stripcoef.hull.lift import (HEAD_SEPARATION_H, _head_h, _head_h1,
                                 boundary_layer_pressure_ratio, boundary_layer_thickness,
                                 power_law_exponent, surface_speed_ratio,
                                 turbulent_boundary_layer, wing_body_factors)
from stripcoef.sections.added_mass import circle_with_fins

REMUS = Path(__file__).resolve().parents[1] / "geometry" / "remus100.yaml"


def _remus_data(**top):
    data = yaml.safe_load(REMUS.read_text())
    data.update(top)
    return data


@pytest.fixture(scope="module")
def remus_slender(tmp_path_factory):
    path = tmp_path_factory.mktemp("slender") / "remus_slender.yaml"
    path.write_text(yaml.safe_dump(_remus_data(body_lift="slender")))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)          # REMUS is 7 % buoyant
        return estimate(path)


# ---------------------------------------------------------------------------
# the factors: limits and the identities of slender-body theory
# ---------------------------------------------------------------------------
@pytest.mark.parametrize("tau", [0.05, 0.2, 0.447, 0.6, 0.9])
def test_wing_body_identities(tau):
    """K_W(B) + K_B(W) = (1 + tau)^2, the finned circle's apparent mass over the exposed pair's
    (Newman 1977, sec. 4.13); k_W(B) + k_B(W) = K_W(B) (reciprocity); every factor positive."""
    f = wing_body_factors(tau)
    s, rho = 1.0, 1000.0
    a = tau * s
    finned = circle_with_fins(a, s, rho=rho)[0] / (rho * math.pi) - a * a   # fins' share [m^2]
    assert f["K_WB"] + f["K_BW"] == pytest.approx(finned / (s - a) ** 2, rel=1e-9)
    assert f["k_WB"] + f["k_BW"] == pytest.approx(f["K_WB"], rel=1e-12)
    assert min(f.values()) > 0.0
    assert f["K_WB"] > f["k_WB"]                 # the body's upwash adds to the fin's own lift


@pytest.mark.parametrize("tau", [0.2, 0.447, 0.7])
def test_wing_in_presence_of_body_is_the_mapped_loading(tau):
    """K_W(B) from its definition, independently of the closed form: the fin panels' span
    loading of slender-body theory, the potential jump 2 V alpha sqrt(S^2 - (y + a^2/y)^2),
    S = s + a^2/s (the finned circle mapped onto a slit), integrated over both panels, over the
    exposed pair alone (jump 2 V alpha sqrt(b^2 - y^2), b = s - a, integral pi b^2 / 2 per
    half): K_W(B) = 4 int_a^s sqrt(...) dy / (pi (s - a)^2) (Pitts, Nielsen & Kaattari 1957;
    Nielsen 1988, ch. 5)."""
    from scipy.integrate import quad
    a, s = tau, 1.0
    big = s + a * a / s
    loading = quad(lambda y: math.sqrt(max(big * big - (y + a * a / y) ** 2, 0.0)), a, s,
                   limit=200)[0]
    assert wing_body_factors(tau)["K_WB"] == pytest.approx(4 * loading / (math.pi * (s - a) ** 2),
                                                           rel=1e-7)


def test_wing_body_limits():
    small, large = wing_body_factors(1e-4), wing_body_factors(0.9999)
    assert small["K_WB"] == pytest.approx(1.0, abs=1e-3) and small["k_WB"] == pytest.approx(1.0, abs=1e-3)
    assert small["K_BW"] == pytest.approx(0.0, abs=1e-3) and small["k_BW"] == pytest.approx(0.0, abs=1e-3)
    assert large["K_WB"] == pytest.approx(2.0, abs=1e-3) and large["K_BW"] == pytest.approx(2.0, abs=1e-3)
    assert large["k_WB"] == pytest.approx(1.0, abs=1e-3) and large["k_BW"] == pytest.approx(1.0, abs=1e-3)
    # k_W(B) dips below 1 between the limits (NACA Report 1307's curve): about 0.935 near 0.35
    k = [wing_body_factors(t)["k_WB"] for t in np.linspace(0.05, 0.95, 91)]
    assert 0.93 < min(k) < 0.94
    for bad in (0.0, 1.0, -0.1):
        with pytest.raises(ValueError, match="a/s"):
            wing_body_factors(bad)


def test_boundary_layer_formulas():
    """delta = 0.37 x Re_x^-1/5; the 1/7 profile's mean q over a fin: 7/9 for a fin as tall as
    the layer, 1 outside it, (b/delta)^(2/7) 7/9 inside, continuous and falling with delta."""
    assert boundary_layer_thickness(2.0, 3.0, 1e-6) == pytest.approx(0.37 * 2.0 * 6e6 ** -0.2)
    assert boundary_layer_thickness(0.0, 3.0, 1e-6) == 0.0
    assert boundary_layer_pressure_ratio(1.0, 0.0) == 1.0
    assert boundary_layer_pressure_ratio(1.0, 1.0) == pytest.approx(7 / 9)
    assert boundary_layer_pressure_ratio(0.5, 1.0) == pytest.approx(7 / 9 * 0.5 ** (2 / 7))
    assert boundary_layer_pressure_ratio(2.0, 1.0) == pytest.approx((7 / 9 + 1) / 2)
    q = [boundary_layer_pressure_ratio(1.0, d) for d in np.linspace(0.0, 3.0, 31)]
    assert np.all(np.diff(q) < 0)
    with pytest.raises(ValueError, match="span"):
        boundary_layer_pressure_ratio(0.0, 0.1)


def test_power_law_profiles():
    """H = 1 + 2p (1/7: H = 9/7) and the mean q of a fin as tall as the layer 1/(1 + 2p)."""
    assert power_law_exponent(9 / 7) == pytest.approx(1 / 7)
    for p in (1 / 9, 1 / 7, 0.25, 0.4):
        assert boundary_layer_pressure_ratio(1.0, 1.0, p) == pytest.approx(1 / (1 + 2 * p))
    assert boundary_layer_pressure_ratio(0.7, 1.3, 1 / 7) == boundary_layer_pressure_ratio(0.7, 1.3)
    with pytest.raises(ValueError, match="H > 1"):
        power_law_exponent(1.0)


def test_head_shape_factor_relation_inverts():
    """Head's H1(H) (two branches meeting near H = 1.6) and its inverse round-trip."""
    for h in (1.2, 1.3, 1.45, 1.59, 1.61, 1.8, 2.4, 3.0):
        assert _head_h(_head_h1(h)) == pytest.approx(h, abs=1e-9)
    assert _head_h1(1.3) > _head_h1(1.5) > _head_h1(2.0)      # H1 falls as H rises


def test_head_method_on_a_flat_plate():
    """A long cylinder (constant radius and edge speed): Head's momentum thickness within 10 %
    of the 1/7-power flat plate's 0.036 x Re_x^-1/5 and H near the flat plate's 1.3-1.4
    (Schlichting 1979, ch. XXI); no separation."""
    s = np.linspace(0.0, 20.0, 401)
    bl = turbulent_boundary_layer(s, np.full_like(s, 1.0), np.ones_like(s), speed=5.0,
                                  viscosity=1e-6)
    assert bl["separation"] is None and bl["end"] == pytest.approx(20.0)
    for x in (5.0, 10.0, 20.0):
        theta = np.interp(x, bl["s"], bl["theta"])
        assert theta == pytest.approx(0.036 * x * (5.0 * x / 1e-6) ** -0.2, rel=0.10), x
    assert 1.25 < bl["H"][-1] < 1.42
    # Head's layer thickness delta = theta (H1 + H) is the flat plate's order, 0.37 x Re^-1/5
    assert np.interp(10.0, bl["s"], bl["delta"]) == pytest.approx(
        boundary_layer_thickness(10.0, 5.0, 1e-6), rel=0.35)


def test_head_method_separates_in_a_strong_adverse_gradient():
    """A decelerating edge speed U_e/U = 1 - k s: H grows and Head's criterion is reached,
    earlier for the steeper gradient; an accelerating one thins the layer."""
    s = np.linspace(0.0, 4.0, 401)
    r = np.ones_like(s)
    sep = []
    for k in (0.15, 0.20):
        bl = turbulent_boundary_layer(s, r, 1.0 - k * s, speed=5.0, viscosity=1e-6)
        assert bl["separation"] is not None
        assert bl["H"][-1] == pytest.approx(HEAD_SEPARATION_H, abs=1e-3)
        sep.append(bl["separation"])
    assert sep[1] < sep[0]
    flat = turbulent_boundary_layer(s, r, np.ones_like(s), speed=5.0, viscosity=1e-6)
    fast = turbulent_boundary_layer(s, r, 1.0 + 0.1 * s, speed=5.0, viscosity=1e-6)
    assert fast["theta"][-1] < flat["theta"][-1]


def test_head_layer_is_insensitive_to_round_off_on_a_tabulated_hull():
    """On the SUBOFF hull tabulated as a polyline (a kink at every vertex) a relative change of
    1e-13 in the radii moves Head's theta by < 1e-10 along the afterbody (the adaptive solver
    used before moved it by 2 % at 0.95 l: the 3-5 % machine-to-machine spread of issue 34),
    and halving every step (the same polyline with its midpoints added) by < 1e-5 (2e-6 at
    0.97 l, where the hull closes)."""
    from validation.lift import RODDY_SPEED, suboff_vehicle_data
    from stripcoef.geometry.vehicle import parse_vehicle

    vehicle = parse_vehicle(suboff_vehicle_data(3, "off"), file="SUBOFF config 3")
    lo, hi = vehicle.hull.x_extent()
    s = np.linspace(0.0, hi - lo, 2001)
    r = vehicle.hull.half_breadth(hi - s)
    nu = float(vehicle.fluid.kinematic_viscosity)

    ue = surface_speed_ratio(s, np.pi * r ** 2)
    base = turbulent_boundary_layer(s, r, ue, speed=RODDY_SPEED, viscosity=nu)
    at = (hi - lo) * np.array([0.8, 0.9, 0.95, 0.97])
    theta = np.interp(at, base["s"], base["theta"])
    nudged = turbulent_boundary_layer(s, r * (1.0 + 1e-13), ue, speed=RODDY_SPEED, viscosity=nu)
    np.testing.assert_allclose(np.interp(at, nudged["s"], nudged["theta"]), theta, rtol=1e-10)
    fine = np.sort(np.concatenate([s, 0.5 * (s[1:] + s[:-1])]))
    halved = turbulent_boundary_layer(fine, np.interp(fine, s, r), np.interp(fine, s, ue),
                                      speed=RODDY_SPEED, viscosity=nu)
    np.testing.assert_allclose(np.interp(at, halved["s"], halved["theta"]), theta, rtol=1e-5)


def test_surface_speed_of_a_slender_spheroid():
    """The line-source surface speed of a prolate spheroid (l/d = 10) against the exact
    potential flow at mid-length, U (1 + k1) with Lamb's k1 = 0.0207: within 0.5 %; it falls
    below 1 towards the ends where the body closes."""
    from stripcoef.hull.lamb import lamb_k_factors

    a, b = 5.0, 0.5
    s = np.linspace(0.0, 2 * a, 2001)
    area = np.pi * b * b * np.clip(1.0 - ((s - a) / a) ** 2, 0.0, None)
    ue = surface_speed_ratio(s, area)
    k1 = lamb_k_factors(a / b)[0]
    assert np.interp(a, s, ue) == pytest.approx(1.0 + k1, rel=0.005)
    assert np.interp(0.02 * a, s, ue) < 1.0 + k1


# ---------------------------------------------------------------------------
# properties of a vehicle under body_lift: slender
# ---------------------------------------------------------------------------
def test_slender_rotary_signs_and_fin_symmetry(remus_slender):
    """REMUS with its fins aft: the lift's Y_ur > 0, N_ur < 0, Z_uq < 0, M_uq < 0 (a yaw or
    pitch rate gives the aft fins and afterbody a cross-flow, damping the turn); the symmetric
    fin pairs give no roll from sway or heave and no cross-coupling; the rudder's force is
    +Y only, the elevator's -Z only."""
    lift = remus_slender.lift
    assert -lift[1, 5] > 0 and -lift[5, 5] < 0
    assert -lift[2, 4] < 0 and -lift[4, 4] < 0
    scale = abs(lift[1, 1])
    for i, j in ((3, 1), (3, 2), (1, 2), (2, 1), (5, 2), (4, 1)):
        assert abs(lift[i, j]) <= 1e-9 * scale * 10, (i, j)
    b = {s.kind: np.asarray(s.derivative) for s in remus_slender.control_surfaces}
    assert b["rudder"][1] > 0 and b["elevator"][2] < 0
    assert abs(b["rudder"][2]) + abs(b["rudder"][3]) < 1e-9 * b["rudder"][1]
    assert abs(b["elevator"][1]) + abs(b["elevator"][3]) < 1e-9 * abs(b["elevator"][2])
    info = remus_slender.conditions["lift"]["fin_lift"]
    assert all(f["body_upwash"] is False and 0.0 < f["pressure_ratio"] < 1.0 for f in info)
    assert len({round(f["interference"], 12) for f in info}) == 1     # all four fins alike


def test_port_and_starboard_fins_mirror(tmp_path):
    """A single fin on the starboard side and its mirror on the port side give mirrored lift
    (y -> -y: the rows and columns of v, p, r change sign)."""
    def one(side):
        data = _remus_data(body_lift="slender")
        data["control_surfaces"] = [data["control_surfaces"][1]]
        data["control_surfaces"][0]["fins"] = ["fin_" + side]
        data["appendages"] = [a for a in data["appendages"] if a["name"] == "fin_" + side]
        path = tmp_path / f"{side}.yaml"
        path.write_text(yaml.safe_dump(data))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelWarning)
            return estimate(path)
    stb, port = one("starboard"), one("port")
    m = np.diag([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])
    np.testing.assert_allclose(port.lift, m @ stb.lift @ m, atol=1e-12)
    np.testing.assert_allclose(port.control_surfaces[0].derivative,
                               m @ stb.control_surfaces[0].derivative, atol=1e-12)


def _edit_fin_beyond_the_end(data):
    data["appendages"][0]["center"] = [-5.0, 0.0, -0.0858]


def _edit_past_stall(data):
    data["control_surfaces"][0]["max_deflection_deg"] = 25.0


@pytest.mark.parametrize("edit,key,text", [
    (_edit_fin_beyond_the_end, "appendages", "fin_top"),
    (_edit_past_stall, "control_surfaces[0].max_deflection_deg", "beyond the stall angle"),
], ids=["fin beyond the hull's end", "deflection past stall"])
def test_bad_input_keeps_its_one_line_error(tmp_path, capsys, edit, key, text):
    data = _remus_data(body_lift="slender")
    edit(data)
    f = tmp_path / "bad.yaml"
    f.write_text(yaml.safe_dump(data))
    out = tmp_path / "out.json"
    assert main(["coefficients", str(f), "--json", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert not out.exists()
    assert err.count("\n") == 1 and key in err and text in err and "Traceback" not in err, err


def test_axial_velocity_of_a_uniform_source_ramp():
    """S rising linearly from 0 to S_0 over s in [0, a] and constant behind: the sources
    S_0/a per unit length give u/U - 1 = S_0/(4 pi a) [1/sqrt((s - a)^2 + r^2) - 1/sqrt(s^2 + r^2)]
    (the integral in closed form); a closing body slows the flow, a middle body speeds it."""
    from stripcoef.hull.lift import axial_velocity_ratio
    a, s0 = 1.0, 0.3
    s = np.linspace(0.0, 4.0, 40001)
    area = np.minimum(s / a, 1.0) * s0
    for sp, rp in ((0.5, 0.2), (2.0, 0.4), (-0.5, 0.3)):
        exact = 1.0 + s0 / (4 * math.pi * a) * (1 / math.hypot(sp - a, rp) - 1 / math.hypot(sp, rp))
        assert axial_velocity_ratio(s, area, sp, rp) == pytest.approx(exact, rel=1e-6)
    closing = s0 - area                     # the mirror: a closing tail slows the flow behind
    assert axial_velocity_ratio(s, closing, 0.8, 0.2) < 1.0


def test_fins_in_heads_layer_and_a_hull_shorter_than_the_laminar_run(tmp_path):
    """REMUS at its 1.5 m/s: the fins sit in Head's turbulent layer (thicker than a flat
    plate's over the closing tail cone) and lose dynamic pressure to it; at 0.1 m/s the laminar
    run (Re_x = 5e5, 5 m) is longer than the hull, no turbulent layer is computed and the fins
    keep the body's axial-flow ratio alone, without an error."""
    from stripcoef.hull.lift import boundary_layer_thickness

    fins = {}
    for speed in (1.5, 0.1):
        path = tmp_path / f"remus_{speed}.yaml"
        path.write_text(yaml.safe_dump(_remus_data(body_lift="slender", reference_speed=speed)))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ModelWarning)
            fins[speed] = estimate(path).conditions.lift["fin_lift"]
    for f in fins[1.5]:
        assert f["boundary_layer_method"] == "Head"
        assert f["boundary_layer"] > boundary_layer_thickness(1.2, 1.5, 1.2e-6)
        assert f["pressure_ratio"] < f["stream_ratio"]
    for f in fins[0.1]:
        assert f["boundary_layer_method"] == "laminar" and f["boundary_layer"] == 0.0
        assert f["pressure_ratio"] == pytest.approx(f["stream_ratio"])


def test_datcom_rule_changes_the_body_lift_only(remus_slender):
    """``body_lift: datcom`` (the default's rule, also ``auto``) keeps the fins of the slender
    rule (their stern flow, factors and deflection derivatives) and scales only the body's
    slender-body lift by Munk's k2 - k1: L_datcom - L_slender = (k2 - k1 - 1) L_body."""
    from stripcoef.assembly.lift import _body_lift
    from stripcoef.geometry.vehicle import parse_vehicle
    from stripcoef.hull.lift import munk_factor

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        datcom = estimate(parse_vehicle(_remus_data(body_lift="datcom"), file="remus.yaml"))
        auto = estimate(parse_vehicle(_remus_data(), file="remus.yaml"))
    np.testing.assert_array_equal(auto.lift, datcom.lift)
    np.testing.assert_allclose(datcom.control_matrix, remus_slender.control_matrix, rtol=1e-12)
    fins_s = remus_slender.conditions.lift["fin_lift"]
    fins_d = datcom.conditions.lift["fin_lift"]
    assert [f["pressure_ratio"] for f in fins_d] == pytest.approx(
        [f["pressure_ratio"] for f in fins_s], rel=1e-12)
    vehicle = parse_vehicle(_remus_data(body_lift="slender"), file="remus.yaml")
    body = _body_lift(vehicle, datcom.density, datcom.reference_point, datcom.reference_point)
    info = datcom.conditions.lift["body_lift"]
    k = munk_factor(info["length"], info["diameter"])
    np.testing.assert_allclose(datcom.lift - remus_slender.lift, (k - 1.0) * body[0],
                               rtol=1e-9, atol=1e-9 * float(np.abs(body[0]).max()))
