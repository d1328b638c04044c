"""Lift formulas against measured captive-model data: DARPA SUBOFF (Roddy 1990, Table 4;
reference_tables/roddy1990_suboff).

Roddy's Y'_v is nondimensional on 1/2 rho L_BP^2 U (per v' = v/U). stripcoef's lift force is
-u L nu, so its Y_uv = -1/2 rho d^2 c_ydb (body) and -1/2 rho S c_La per fin, and
Y'_v = Y_uv / (1/2 rho L_BP^2): rho cancels.

Tolerance: 20 %, the tolerance this project states for its semi-empirical lift against
Prestero 2001 (docs/validation.md); Roddy's own uncertainty (4-5 % on the static derivatives,
10-25 % on the increments, which are differences of two measured rows) is inside it. No
factor is fitted: a miss is a strict xfail whose reason gives the numbers. The fin-hull
interference factor is slender-body theory's (1 + R/s)^2 on a cylindrical root, the model's
rule (hull.lift.interference_factor), not a value chosen for these data.
"""

from __future__ import annotations


import numpy as np
import pytest

from stripcoef.hull.lift import fin_lift_slope, lifting_line_slope
from validation import reference as ref
from validation.lift import (FT, LIFT_TOLERANCE, SUBOFF as SOURCE, afterbody_radius,
                             bare_hull_derivatives, bare_hull_model, body_Yv, datcom_body_Yv,
                             flat_plate_points, fully_appended_Yv, hull_radius, increment_Yv,
                             plane_chord, planes_geometry, planes_interference,
                             planes_root_radii, sail_geometry, sail_interference, val, within,
                             appendix_curve, odd_slope, stock_lift_slopes,
                             SUBOFF_TOLERANCE, drift_curve_comparisons, suboff_comparisons)


# ---------------------------------------------------------------------------
# the data and the geometry
# ---------------------------------------------------------------------------
def test_increments_add_up_to_the_fully_appended_model():
    # bare hull + sail + planes = -0.027554 against -0.027834 measured (Roddy's 4-5 %)
    assert ref.agrees(ref.reference_value(SOURCE, "Yv.fully_appended"), val("Yv.sum_of_parts"))


def test_geometry_as_published():
    assert val("hull.L") / val("hull.D") == pytest.approx(8.575, abs=5e-4)  # Groves: 8.575
    assert val("hull.L") * FT == pytest.approx(4.3561, abs=5e-5)      # manifest: 4.3561 m
    # the stern planes' root radius is the fixed point it is stored as
    r = 0.3
    for _ in range(60):
        r = afterbody_radius(val("planes.x_te") - plane_chord(r) / 2)
    assert r == pytest.approx(val("planes.r_root"), abs=1e-6)
    # the afterbody equation meets the largest radius where the parallel middle body ends
    assert afterbody_radius(13.979167 - 3.333333) == pytest.approx(0.833333, rel=1e-6)


def test_hull_equations_join():
    """The bow, middle body, afterbody and cap equations (Groves et al. 1989, as coded in the
    public generator) meet without steps and close the hull at both ends."""
    rmax = val("hull.Rmax")
    assert hull_radius(0.0) == 0.0 and hull_radius(val("hull.L")) == 0.0
    assert hull_radius(3.333333) == pytest.approx(rmax, rel=1e-6)              # bow -> middle
    assert hull_radius(10.645833 + 1e-9) == pytest.approx(rmax, rel=1e-6)      # middle -> aft
    assert hull_radius(13.979167 + 1e-7) == pytest.approx(0.1175 * rmax, rel=1e-4)  # -> cap
    x = np.linspace(1e-4, val("hull.L") - 1e-4, 2001)
    r = np.array([hull_radius(t) for t in x])
    assert np.all(r > 0) and r.max() == pytest.approx(rmax)


def test_bare_hull_model_lift_is_the_formula():
    """The whole model of the bare hull (table profile of the Groves equations) carries the
    body-lift formula's Y'_v: a bare body of revolution has no Munk force in sway."""
    assert bare_hull_derivatives()["Yv"] == pytest.approx(body_Yv(), rel=1e-6)
    cb = bare_hull_model().center_of_buoyancy[0]
    assert (0.5 * val("hull.L") - cb / FT) / val("hull.L") == pytest.approx(0.461, abs=1e-3)


# ---------------------------------------------------------------------------
# the lift formulas against the data
# ---------------------------------------------------------------------------
@pytest.mark.xfail(strict=True, reason=(
    "Hoerner/Prestero body lift 0.003 (l/d)/deg on d^2 gives Y'_v = -0.0210 for the SUBOFF bare "
    "hull (l/d = 8.575), Roddy 1990 measured -0.00595: 3.5 times (+252 %). The measured slope is "
    "0.00085 (l/d)/deg (0.418/rad on d^2)."))
def test_body_lift_against_suboff_bare_hull():
    assert within(body_Yv(), val("Yv.bare_hull"))


def test_datcom_body_method_misses_suboff_too():
    """The DATCOM body method (sec. 4.2.1.1, Hopkins 1951), the published alternative to
    Hoerner's correlation, is not a way out: 2.5 times the measured bare-hull lift, with x_0 at
    0.825 l on the afterbody (a comparison, not the model's method)."""
    yv, x0 = datcom_body_Yv()
    assert x0 == pytest.approx(0.8246, abs=1e-3)
    assert yv / val("Yv.bare_hull") == pytest.approx(2.53, abs=0.01)
    assert not within(yv, val("Yv.bare_hull"))


def test_bare_hull_yaw_moment_against_suboff():
    """N'_v of the bare hull, the Munk moment of the model's added mass plus the body lift's
    moment about the centre of buoyancy: -0.01216 against -0.012795 measured (-5 %). The
    moment centre of the data is not quoted; 0.05 L_BP either way moves N'_v by 2.3 %."""
    nv = bare_hull_derivatives()["Nv"]
    assert within(nv, val("Nv.bare_hull"))
    assert nv / val("Nv.bare_hull") == pytest.approx(0.951, abs=0.002)


@pytest.mark.xfail(strict=True, reason=(
    "The model's body lift answers the sideslip at the centre of buoyancy only (Prestero's "
    "form), so the bare hull's Y'_r is the added mass's -0.00067 against +0.001811 measured "
    "(wrong sign) and N'_r +0.00002 against -0.001597: the measured signs are those of a force "
    "far aft answering the local cross-flow v + x r."))
@pytest.mark.parametrize("key", ["Yr", "Nr"])
def test_bare_hull_rotary_derivatives_against_suboff(key):
    assert within(bare_hull_derivatives()[key], val(f"{key}.bare_hull"))


def test_sail_lift_against_the_measured_increment():
    """The sail sits on the parallel middle body: Helmbold's slope times slender-body theory's
    fin-hull interference (1 + R/s)^2 = 2.41 gives -0.0162 against -0.0171 measured (-5 %);
    without the factor it was -60 %."""
    assert sail_interference() == pytest.approx(2.408, abs=1e-3)
    assert within(increment_Yv(sail_geometry, 1, sail_interference()), val("Yv.sail_increment"))


@pytest.mark.xfail(strict=True, reason=(
    "Helmbold fin lift of the two vertical SUBOFF stern planes (AR_e = 1.47, "
    "c_La = 2.01/rad) gives Y'_v = -0.00550 against the measured increment -0.00455 (+21 %). "
    "Their roots run down the tapering afterbody (r = 0.514 to 0.271 ft), outside slender-body "
    "theory's cylinder, so the model applies no hull interference; the cylinder's factor 2.16 "
    "would give +161 %: the afterbody's thick boundary layer and closing body take most of it. "
    "Prestero's lifting-line slope (2.54/rad) gives -0.00694 (+53 %)."))
def test_stern_plane_lift_against_the_measured_increment():
    assert planes_interference()[0] == 1.0
    assert within(increment_Yv(planes_geometry, 2), val("Yv.planes_increment"))


@pytest.mark.xfail(strict=True, reason=(
    "Fully appended SUBOFF: the model's three rows sum to Y'_v = -0.0427 against -0.0278 "
    "measured (+53 %), the body lift's miss (before the sail's hull interference the two fin "
    "misses hid it: +19 %)."))
def test_fully_appended_against_suboff():
    assert within(fully_appended_Yv(), val("Yv.fully_appended"))


def test_comparison_numbers_as_reported():
    """The numbers the xfail reasons and docs/validation.md state (so they cannot drift)."""
    assert body_Yv() / val("Yv.bare_hull") == pytest.approx(3.52, abs=0.01)
    sail, planes = val("Yv.sail_increment"), val("Yv.planes_increment")
    k = sail_interference()
    assert sail_geometry()[1] == pytest.approx(1.118, abs=1e-3)
    assert increment_Yv(sail_geometry, 1) / sail == pytest.approx(0.395, abs=1e-3)
    assert increment_Yv(sail_geometry, 1, 1.0, lifting_line_slope) / sail == pytest.approx(0.531, abs=1e-3)
    assert increment_Yv(sail_geometry, 1, k) / sail == pytest.approx(0.952, abs=1e-3)
    assert increment_Yv(sail_geometry, 1, k, lifting_line_slope) / sail == pytest.approx(1.278, abs=1e-3)
    assert planes_root_radii() == pytest.approx([0.514, 0.271], abs=1e-3)
    assert planes_interference()[1] == pytest.approx(2.158, abs=1e-3)
    assert fully_appended_Yv() / val("Yv.fully_appended") == pytest.approx(1.534, abs=2e-3)
    assert planes_geometry()[1] == pytest.approx(1.467, abs=1e-3)
    assert increment_Yv(planes_geometry, 2) / planes == pytest.approx(1.209, abs=1e-3)
    assert increment_Yv(planes_geometry, 2, 1.0, lifting_line_slope) / planes == pytest.approx(1.526, abs=1e-3)
    assert increment_Yv(planes_geometry, 2, planes_interference()[1]) / planes == pytest.approx(2.609, abs=2e-3)


# ---------------------------------------------------------------------------
# fin lift slope against measured flat plates (reference_tables/flat_plate_lift)
# ---------------------------------------------------------------------------
def test_fin_lift_slope_against_measured_flat_plates():
    """Helmbold's slope (the model's) within 20 % of all 18 measured points, AR 0.57-6.05 (the
    points' own scatter is +-7 %); the lifting-line form Prestero uses misses 6 of them, by up
    to +71 % at AR 0.57."""
    ar, cla = flat_plate_points()
    ours = fin_lift_slope(ar)
    assert np.all(np.abs(ours / cla - 1) <= LIFT_TOLERANCE)
    assert np.max(np.abs(ours / cla - 1)) == pytest.approx(0.156, abs=0.002)
    ll = lifting_line_slope(ar)
    assert np.sum(np.abs(ll / cla - 1) > LIFT_TOLERANCE) == 6
    assert np.max(ll / cla - 1) == pytest.approx(0.713, abs=0.002)


# ---------------------------------------------------------------------------
# Roddy 1990 Table 4 and Appendix B (reference_tables/roddy1990_suboff, read from the OCR text)
# ---------------------------------------------------------------------------
FIRST_QUOTATION = {"Yv.bare_hull": "c3.Yv", "Nv.bare_hull": "c3.Nv", "Yr.bare_hull": "c3.Yr",
                   "Nr.bare_hull": "c3.Nr", "Yv.hull_sail": "c4.Yv", "Nv.hull_sail": "c4.Nv",
                   "Yv.hull_planes": "c5.Yv", "Nv.hull_planes": "c5.Nv",
                   "Yv.fully_appended": "c2.Yv", "Nv.fully_appended": "c2.Nv",
                   "Zw.config1": "c1.Zw", "Mw.config1": "c1.Mw", "hull.L_BP": "t1.L_BP"}


@pytest.mark.parametrize("quoted,table4", sorted(FIRST_QUOTATION.items()))
def test_first_quotation_equals_table4(quoted, table4):
    assert val(quoted) == pytest.approx(val(table4), rel=1e-6)


def test_table4_is_complete():
    names = {r["name"] for r in ref.load_table(SOURCE, "table4_derivatives")}
    horizontal = ("Yv", "Nv", "Kv", "Yr", "Nr", "Yvdot", "Nvdot", "Yrdot", "Nrdot", "G")
    vertical = ("Zw", "Mw", "Zq", "Mq", "Zwdot", "Mwdot", "Zqdot", "Mqdot", "G", "Zds", "Mds")
    expected = {f"c{c}.{d}" for c in (2, 3, 4, 5, 6) for d in horizontal}
    expected |= {f"c1.{d}" for d in vertical} | {"c2.Ydr", "c2.Ndr", "c2.Kdr"}
    assert expected <= names
    assert val("moment_point.x") == pytest.approx(6.6042)
    # Table 1: the planes' printed area is their trapezoid within 1.3 % (0.2637 from the
    # printed chords and span, 0.267 printed), the aspect ratio span^2/area to print precision
    assert 0.5 * (val("t1.plane.c_root") + val("t1.plane.c_tip")) * val("t1.plane.span") \
        == pytest.approx(val("t1.plane.S"), rel=0.015)
    assert val("t1.plane.span") ** 2 / val("t1.plane.S") == pytest.approx(val("t1.plane.AR"), abs=2e-3)
    # the sail's printed area is 3 % below span x chord (0.881): its cap is rounded
    assert val("t1.sail.span") * val("t1.sail.chord") == pytest.approx(val("t1.sail.S"), rel=0.035)


def _stability_margin(c):
    m = val(f"c{c}.m")
    xgm = val(f"c{c}.xGm_1e4") * 1e-4
    if c == 1:
        return 1.0 - val("c1.Mw") * (val("c1.Zq") + m) / (val("c1.Zw") * (val("c1.Mq") - xgm))
    return 1.0 - val(f"c{c}.Nv") * (val(f"c{c}.Yr") - m) / (val(f"c{c}.Yv") * (val(f"c{c}.Nr") - xgm))


@pytest.mark.parametrize("config", [1, 2, 3, 4, 5, 6])
def test_printed_stability_margin_follows_from_the_printed_derivatives(config):
    """Roddy p. 6: G_h = 1 - N'_v (Y'_r - m') / [Y'_v (N'_r - x_G' m')] (G_v likewise): the
    transcribed Table 4 and Table 1 rows reproduce each printed G to its printed precision
    (a check of the transcription and of the sign convention)."""
    assert _stability_margin(config) == pytest.approx(val(f"c{config}.G"), rel=2e-3)


@pytest.mark.parametrize("config", [1, 2, 3, 4, 5, 6])
def test_appendix_b_slopes_reproduce_table4(config):
    """The least-squares slope of the Appendix B curves over |angle| <= 4 deg is Table 4's
    derivative: the moment within 5 % (Roddy's static uncertainty) for every configuration,
    with drift positive for v < 0 (v' = -sin beta) and incidence positive for w > 0; the force
    of the appended configurations within 10 %. Without fins (3, 6) the force curve bends
    upward already by 4 deg (the slope there is 17 % and 30 % above Roddy's, which is the
    slope at the origin): the body's lift is non-linear from the start."""
    force, moment = ("Z", "M") if config == 1 else ("Y", "N")
    sign = 1.0 if config == 1 else -1.0
    moment_slope = sign * odd_slope(*appendix_curve(config, moment))
    assert moment_slope == pytest.approx(val(f"c{config}.{'Mw' if config == 1 else 'Nv'}"), rel=0.05)
    ratio = sign * odd_slope(*appendix_curve(config, force)) / val(f"c{config}.{'Zw' if config == 1 else 'Yv'}")
    if config in (3, 6):
        assert 1.1 < ratio < 1.35
    else:
        assert ratio == pytest.approx(1.0, abs=0.10)


def test_stock_lift_slopes():
    """One stern appendage's own lift, measured on its stock: 1.1-1.3 /rad in drift, about 1.4
    /rad deflected (rudder and sternplane agree within 2 %)."""
    s = stock_lift_slopes()
    assert 1.1 < s["drift"] < 1.3
    assert s["rudder"] == pytest.approx(s["sternplane"], rel=0.02)
    assert 1.3 < s["rudder"] < 1.5


# ---------------------------------------------------------------------------
# every configuration and derivative (docs/validation.md, 'Every configuration and derivative')
# ---------------------------------------------------------------------------
_BODY = ("Hopkins's separation station (0.825 l on SUBOFF, correlated on missile boat-tails) is "
         "too far forward for SUBOFF's streamlined afterbody, whose flow stays attached longer: the "
         "default body lift (DATCOM: slender-body lift ahead of x_0 times Munk's k2 - k1 = 0.924) "
         "is 2.56 times the bare hull's Y'_v (2.78 without the factor) and its moment too small; "
         "no published submarine correlation for the station was found, and the other published "
         "methods miss further (validation.lift.body_lift_candidates: Hoerner 3.5 times, "
         "potential lift attached to the tail 0.00-0.08); Stratford's separation criterion on "
         "the hull's own layer (body_lift: stratford, 0.902 l) meets 18 of the 26 checks but "
         "fewer drift points and rotary terms, so it is an option (tests/test_lift_separation.py)")
_FIN = ("each plane's own force is 1.29 /rad on the printed area against 1.42 deflected (-9 %) "
        "and 1.23 in drift (+5 %) on its stock (Helmbold 2.08 x k_W(B) 0.94 x stern dynamic "
        "pressure 0.64: potential flow 0.86, Head's boundary layer 0.74)")
#: (configuration, derivative) -> why the default model (body_lift: auto, the DATCOM rule) misses
#: the issue's tolerance.
KNOWN_MISSES = {
    (3, "Nv"): "bare hull N'_v 0.76 of measured (tolerance 10 %): " + _BODY,
    (6, "Nv"): "hull + ring N'_v 0.66 of measured (0.75 without the ring): the ring lifts in "
               "drift in the model (Y'_v -0.0025 in the stern flow) and not in Roddy's data; "
               + _BODY,
    (4, "Yv"): "hull + sail Y'_v 1.48 times measured: " + _BODY,
    (5, "Yv"): "hull + planes Y'_v 1.96 times measured: " + _BODY,
    (5, "Nv"): "hull + planes N'_v 0.66 of measured: " + _BODY,
    (2, "Yv"): "fully appended Y'_v 1.50 times measured (1.41 without the ring wing): " + _BODY,
    (2, "Nv"): "fully appended N'_v 0.77 of measured (0.86 without the ring wing): the model's "
               "ring lifts in drift, Roddy's does not (configuration 6 - 3: Y'_v +0.000005)",
    (1, "Zw"): "configuration 1 Z'_w 1.65 times measured (1.48 without the ring wing, which "
               "lifts in the model's drift and not in Roddy's): " + _BODY,
    (1, "Mw"): "configuration 1 M'_w 0.59 of measured (0.71 without the ring wing): " + _BODY,
    (4, "Yr"): "hull + sail Y'_r: measured -0.000023 (zero within its 10 %), model +0.0013: the "
               "sail's rotary force (-0.0036, twice the measured -0.0018: its lever 0.19 L_BP "
               "forward against 0.11 measured, validation.lift.rotary_buildup) does not cancel "
               "the body's +0.0050",
    (4, "Nr"): "hull + sail N'_r 1.37 times measured: the body's N'_r (bare hull 1.52 times) "
               "carried over",
    (3, "Yv"): "bare hull Y'_v 2.56 times measured (the issue asks only for the error stated): "
               + _BODY,
    (6, "Yv"): "hull + ring Y'_v 2.98 times measured (error stated only; 2.57 without the ring, "
               "which lifts in the model's drift and not in Roddy's): " + _BODY,
}
_CASES = [(c, n) for c in (3, 4, 5, 6, 2, 1)
          for n in ((("Zw", "Mw", "Zq", "Mq", "Zds", "Mds") if c == 1 else ("Yv", "Nv", "Yr", "Nr"))
                    + (("Ydr", "Ndr") if c == 2 else ()))]


@pytest.mark.parametrize("config,name", [
    pytest.param(c, n, marks=pytest.mark.xfail(strict=True, reason=KNOWN_MISSES[(c, n)]))
    if (c, n) in KNOWN_MISSES else (c, n) for c, n in _CASES])
def test_suboff_derivative_with_slender_body_lift(config, name):
    """The default (body_lift: auto, the DATCOM rule) against Roddy's Table 4 with the issue's tolerances: static and
    control within 15 %, rotary right sign and within 25 % (configurations 1, 2, 4, 5); bare
    hull and hull + ring: N'_v within 10 %, rotary signs (Y'_v's error stated: a strict xfail)."""
    rows = {(r["config"], r["name"]): r for r in suboff_comparisons()}
    r = rows[(config, name)]
    if r["ok"] is None:      # Y'_v of 3 and 6: held to the static 15 %, its miss stated
        assert abs(r["ratio"] - 1) <= SUBOFF_TOLERANCE["static"], r
    else:
        assert r["ok"], r


def test_slender_body_lift_fixes_the_rotary_signs_that_hoerners_form_misses():
    rows = {(r["config"], r["name"]): r for r in suboff_comparisons()}
    bare_yr, bare_nr = rows[(3, "Yr")], rows[(3, "Nr")]
    assert bare_yr["hoerner"] < 0 < bare_yr["measured"]          # Hoerner: wrong sign
    assert abs(bare_nr["hoerner"]) < 0.01 * abs(bare_nr["measured"])  # Hoerner: nothing
    assert bare_yr["slender"] > 0 and bare_nr["slender"] < 0
    for c, n in ((1, "Zq"), (1, "Mq"), (2, "Nr"), (5, "Nr")):   # the 25 %, appended
        assert rows[(c, n)]["ratio"] == pytest.approx(1.0, abs=0.25)


@pytest.mark.slow
def test_table4_stability_indices_of_the_fully_appended_body():
    """Table 4's derivatives with the model's m' (docs/validation.md, decision of issue 34):
    the fully appended SUBOFF is directionally unstable (G_H < 0, configuration 2) and, at
    speed, in pitch (G_V < 0, configuration 1)."""
    from validation.lift import FT, stability_indices, suboff_model
    s = stability_indices()
    model = suboff_model(2, "on", True)
    assert s["m"] == pytest.approx(model.mass / (0.5 * model.density * (FT * 13.9792) ** 3),
                                   rel=1e-4)
    assert abs(s["x_G"]) < 0.01                  # the moment point is near the centre of buoyancy
    assert s["horizontal"]["measured"] < 0 and s["vertical"]["measured"] < 0


@pytest.mark.slow
@pytest.mark.parametrize("rule", ["hoerner", "slender", "datcom"])
@pytest.mark.xfail(strict=True, reason="the model is stable under the Hoerner, slender and "
                   "DATCOM rules (G_H 0.34, 0.37, 0.27; G_V 0.47, 0.46, 0.31) where Table 4 "
                   "gives the fully appended body G_H -0.45, G_V -1.17: their Y'_v, Z'_w "
                   "are too large and N'_v, M'_w short (the Stratford option has the measured "
                   "sign: tests/test_lift_separation.py)")
def test_model_stability_indices_have_the_measured_sign(rule):
    from validation.lift import stability_indices
    s = stability_indices()
    assert s["horizontal"][rule] < 0 and s["vertical"][rule] < 0


def test_stern_plane_carry_over_against_the_stock():
    """The whole-body force of the two deflected rudders over their own (stock) forces: Roddy's
    Y'_dr over twice the stock force, 1.53, against slender-body theory's (k_W(B) + k_B(W)) /
    k_W(B) at tau = R/s of the planes' mid-chord root, 1.49 (Pitts, Nielsen & Kaattari 1957;
    nothing fitted). Tolerance 10 %: Roddy's control uncertainty (6-10 %)."""
    from validation.lift import measured_carry_over, model_stock_slopes
    assert measured_carry_over() == pytest.approx(1.529, abs=0.005)
    assert model_stock_slopes()["carry"] == pytest.approx(measured_carry_over(), rel=0.10)


def test_stern_plane_own_force_deflected_against_the_stock():
    """A deflected plane's own force within 20 % of the measured stock force (the issue's
    tolerance): model 1.29 /rad against 1.42 (upper rudder, configuration 2) and 1.41 (port
    sternplane, configuration 1), on the printed area, with the hull's boundary layer from
    Head's method (a flat plate's gave 1.59, +12 %)."""
    from validation.lift import model_stock_slopes
    model, s = model_stock_slopes(), stock_lift_slopes()
    for key in ("rudder", "sternplane"):
        assert model[key] == pytest.approx(s[key], rel=0.20), key


def test_stern_plane_own_force_in_drift_against_the_stock():
    """One plane's own force in drift within 20 % of the stock force: 1.29 /rad against 1.23
    (configuration 5's upper rudder), behind Hopkins's station (no body upwash, k_W(B)), in
    the hull's boundary layer from Head's method (a flat plate's gave +30 %; _FIN)."""
    from validation.lift import model_stock_slopes
    assert model_stock_slopes()["drift"] == pytest.approx(stock_lift_slopes()["drift"], rel=0.20)


@pytest.mark.xfail(strict=True, reason="the default model's Y'(beta) is 1.09-2.5 times Roddy's from 4 "
                   "to 18 deg (configurations 2-5, body_lift: auto, the DATCOM rule; 2 with the "
                   "ring wing; 21 of 40 points within 20 %): the linear body lift is too large "
                   "(Hopkins's station), and at 18 deg the quadratic cross-flow adds 41-89 % of "
                   "the lift (the strips' D_L has no sway entry on SUBOFF: "
                   "test_suboff_linear_damping_has_no_sway); N'(beta) is within 20 % at every "
                   "angle for configurations 2 and 4, from 8 deg for 3, from 12 deg for 5")
def test_drift_curves_within_20_percent():
    for c in drift_curve_comparisons():
        if c["method"] == "datcom":
            assert c["model"] == pytest.approx(c["measured"], rel=0.20), c


@pytest.mark.slow
def test_suboff_linear_damping_has_no_sway():
    """Issue 34's suspected second cause of the drift-curve excess, the strips' linear damping
    D_L adding a linear sway force to the lift: on SUBOFF at Roddy's 6.5 knots the hull's
    cross-flow Reynolds number (1.49e6) is above the circle's drag crisis, the power-law exponent
    is clamped to 2 and D_L has no sway, heave, pitch or yaw entry; the drift force is the lift,
    the quadratic cross-flow and the Munk moment (validation.lift.drift_force_parts), and the
    parts add up to the drift-curve model."""
    from validation.lift import drift_force_parts, suboff_model
    for config, ring in ((3, False), (2, True)):
        dl = np.asarray(suboff_model(config, "datcom", ring).linear_damping)
        assert np.all(dl[np.ix_([1, 2, 4, 5], [1, 2, 4, 5])] == 0.0), dl
    parts = drift_force_parts(3, 8.0, "datcom")
    assert max(map(abs, parts["linear_damping"])) == 0.0
    assert parts["munk"][0] == pytest.approx(0.0, abs=1e-12)     # no Munk sway force
    model = [c["model"] for c in drift_curve_comparisons()
             if (c["config"], c["beta"], c["method"]) == (3, 8.0, "datcom")]
    assert sum(p[0] for p in parts.values()) == pytest.approx(model[0], rel=1e-9)
    assert sum(p[1] for p in parts.values()) == pytest.approx(model[1], rel=1e-9)
    assert parts["crossflow"][0] > 0 and parts["lift"][0] > parts["crossflow"][0]


def test_measured_drift_point_never_extrapolates():
    """Configuration 2 ran to -13.4 deg only: beyond it the tare C(0) replaces C(-beta); past
    either end of a curve the comparison refuses."""
    from validation.lift import measured_odd
    deg, coef = np.array([-10.0, 0.0, 10.0, 20.0]), np.array([-1.0, 0.1, 1.2, 2.1])
    assert measured_odd(deg, coef, 10.0) == pytest.approx(1.1)
    assert measured_odd(deg, coef, 15.0) == pytest.approx(1.65 - 0.1)
    with pytest.raises(ValueError, match="outside"):
        measured_odd(deg, coef, 25.0)


@pytest.mark.parametrize("config", [2, 3, 4, 5])
def test_suboff_vehicle_files_are_current(config):
    """validation/suboff/config<n>.yaml is what scripts/make_suboff_vehicles.py writes, and it
    loads as a vehicle with the expected appendages."""
    import yaml
    from pathlib import Path

    from stripcoef.geometry.vehicle import load_vehicle
    from validation.lift import suboff_vehicle_data

    path = Path(__file__).resolve().parents[1] / "validation" / "suboff" / f"config{config}.yaml"
    assert yaml.safe_load(path.read_text()) == suboff_vehicle_data(config), \
        "stale: run python -m scripts.make_suboff_vehicles"
    vehicle = load_vehicle(path)
    names = {b.name for b in vehicle.bodies}
    assert ("sail" in names) == (config in (2, 4))
    assert ("plane_top" in names) == (config in (2, 5))


# ---------------------------------------------------------------------------
# the published body-lift methods and the ring wing (docs/validation.md)
# ---------------------------------------------------------------------------
def test_ring_wing_struts_sit_on_the_groves_hull():
    """Groves et al.'s Table 5 strut roots lie on the hull their Table 1 equations define (an
    independent check of the afterbody equation as coded), and the ring's chord line is the
    printed one: 0.750 ft long, converging 5.6 deg."""
    for end in ("le", "te"):
        x, r = val(f"strut.x_{end}_hull"), val(f"strut.r_{end}_hull")
        assert hull_radius(x) == pytest.approx(r, abs=2e-5), end
    dx = val("rw1.x_te") - val("rw1.x_le")
    dr = val("rw1.r_te") - val("rw1.r_le")
    assert np.hypot(dx, dr) == pytest.approx(0.7503, abs=1e-4)
    assert np.degrees(np.arctan2(-dr, dx)) == pytest.approx(5.62, abs=0.01)
    # the struts reach the ring inside its chord, on its inner (lower) surface
    x_on = (val("strut.x_le_rw1") - val("rw1.x_le")) / dx
    r_chord = val("rw1.r_le") + x_on * dr
    assert 0.0 < x_on < 1.0 and 0.0 < r_chord - val("strut.r_le_rw1") < 0.1 * np.hypot(dx, dr)


@pytest.mark.slow
def test_published_body_lift_methods_bracket_the_bare_hull():
    """Every published body-lift method in reach on the bare hull (added to the Munk part,
    about Roddy's moment point): the ones cut at a separation station (Hoerner's point force,
    Hopkins's x_0) lift too much, the potential ones with the cross-flow attached to the base
    or the tail (Allen & Perkins's base term, on the hull and on its boundary-layer
    displacement body) lift far too little; none is within the issue's 15 %. Allen & Perkins's
    base term is its closed form 2 S(x_AP) / L_BP^2."""
    from validation.lift import body_lift_candidates

    rows = {r["method"]: r for r in body_lift_candidates()}
    measured = val("c3.Yv")
    cut_names = [name for name in rows if name.startswith(("Hoerner", "Hopkins x_0"))]
    assert len(cut_names) == 3, list(rows)
    cut = [rows[name] for name in cut_names]
    head = rows.pop("Head's displacement body to the aft perpendicular")
    attached = [r for name, r in rows.items() if name not in cut_names]
    assert all(r["Yv"] / measured > 2.5 for r in cut)
    assert all(0.0 <= r["Yv"] / measured < 0.1 for r in attached)
    base = -2.0 * np.pi * afterbody_radius(13.979167) ** 2 / val("t1.L_BP") ** 2
    assert rows["Allen & Perkins base term"]["Yv"] == pytest.approx(base, rel=0.02)
    # attached potential lift leaves the Munk part's N'_v, 1.25 times the measured
    for r in attached:
        assert r["Nv"] / val("c3.Nv") == pytest.approx(1.25, abs=0.03)
    # Head's thick stern layer as a displacement body: between the two groups, every bare-hull
    # term with the measured sign, none within the tolerance (0.39, 1.17, 0.30, 0.41)
    ratios = {k: head[k] / val(f"c3.{k}") for k in ("Yv", "Nv", "Yr", "Nr")}
    assert 0.1 < ratios["Yv"] < 0.5 and 1.1 < ratios["Nv"] < 1.25
    assert all(v > 0 for v in ratios.values())


@pytest.mark.slow
def test_head_boundary_layer_finds_no_separation_on_suboff():
    """Head's method on the bare hull's axial potential flow: the shape factor peaks at 1.64
    near 0.957 l and never reaches the separation criterion ahead of the tail, so the
    boundary-layer route gives no station to cut the body lift at; replacing Hopkins's body
    lift by Head's displacement body meets fewer of the issue's lift checks (6 of 22 against
    11)."""
    from validation.lift import bare_hull_layer, body_lift_substitution

    layer = bare_hull_layer()
    assert layer["separation"] is None
    assert layer["H_max"] == pytest.approx(1.64, abs=0.02)
    assert layer["at"] == pytest.approx(0.957, abs=0.01)
    sub = body_lift_substitution()
    assert sub["head"] < sub["hopkins"]


@pytest.mark.slow
def test_line_source_surface_speed_against_the_panel_solution_on_suboff():
    """The surface speed Head's layer is computed on (line sources, hull.lift.surface_speed_ratio)
    against the axisymmetric panel solution of the same hull (hull.axisymmetric, surge mode):
    within 7 % from the parallel middle body to 0.97 l; the line sources miss part of the
    shoulder's suction peak (1.07 against 1.12 near 0.78 l), so the adverse gradient behind it
    and the layer at the stern planes come out thinner (delta 0.41 against 0.46 ft with the
    panel speed: the fins' dynamic pressure ratio 0.74 against 0.68)."""

    from stripcoef.hull.lift import surface_speed_ratio
    from validation.lift import suboff_surface_speeds

    length = val("hull.L")
    s, r, xc, panel = suboff_surface_speeds()
    line = surface_speed_ratio(s, np.pi * r ** 2)
    for frac in np.linspace(0.5, 0.97, 48):
        p = np.interp(frac * length, xc, panel)
        assert np.interp(frac * length, s, line) == pytest.approx(p, rel=0.07), frac
    near = (xc > 0.74 * length) & (xc < 0.82 * length)
    assert panel[near].max() == pytest.approx(1.12, abs=0.01)
    assert line[(s > 0.74 * length) & (s < 0.82 * length)].max() == pytest.approx(1.07, abs=0.01)
    # the layer at the stern planes' root mid chord (Roddy's 6.5 knots), ft, and the fins'
    # dynamic pressure with the panel speed over the model's
    from validation.lift import panel_speed_sensitivity

    sens = panel_speed_sensitivity()
    assert sens["delta_line"] == pytest.approx(0.41, abs=0.01)
    assert sens["delta_panel"] == pytest.approx(0.46, abs=0.01)
    assert sens["scale"] == pytest.approx(0.91, abs=0.01)


@pytest.mark.slow
def test_validation_doc_lift_section_is_current():
    """docs/validation.md's lift section is what the code writes now (tests/test_validation_doc.py),
    checked here beside the tests that build the same SUBOFF models (``validation.lift``'s
    ``suboff_model``, ``bare_hull_model``: cached in the process). Under two xdist workers the
    section and this module landed on different workers and each built them: 7.2 and 7.9 s of
    CPU more than in one process (measured, issue 31)."""
    from test_validation_doc import assert_section_is_current

    assert_section_is_current("lift")
