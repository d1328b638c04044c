"""The published rules for a fin's incidence in drift and in rotation on SUBOFF
(validation.fin_incidence, issue 34)."""

from __future__ import annotations

import numpy as np
import pytest

from validation.fin_incidence import (CANDIDATES, candidate_lift, candidate_model, checks,
                                      chord_over_length, component_rows, epsilon_at,
                                      sail_diagnosis)
from validation.lift import _roddy_derivatives, issue_checks, suboff_model


def test_the_models_own_rule_adds_nothing():
    """The 3/4-chord candidate is the model: dL = 0 to round-off."""
    dl = candidate_lift(5, "datcom", "three_quarter")
    assert np.abs(dl).max() <= 1e-12 * np.abs(suboff_model(5, "datcom").lift).max()


@pytest.mark.slow
def test_a_lifting_surface_rule_moves_only_the_rotation_column():
    """Moving the rotation's incidence point changes the yaw-rate column only, by the fins'
    drift column times the shift (the lift's u (a' - a)^T): Y'_r and N'_r move, Y'_v and N'_v
    do not, and the trailing edge is a quarter chord aft of the 3/4 chord on the planes'
    lever."""
    base = _roddy_derivatives(suboff_model(5, "datcom"))
    te = _roddy_derivatives(candidate_model(5, "datcom", "trailing_edge"))
    assert te["Yv"] == pytest.approx(base["Yv"], rel=1e-12)
    assert te["Nv"] == pytest.approx(base["Nv"], rel=1e-12)
    fins = {r["candidate"]: r for r in component_rows("datcom")
            if r["component"] == "stern planes"}
    shift = fins["trailing_edge"]["lever"] - fins["three_quarter"]["lever"]
    # the increment's lever holds the planes' added mass and Munk part too: within 10 %
    assert shift == pytest.approx(-0.25 * chord_over_length(), rel=0.10)
    assert fins["three_quarter"]["lever"] > fins["lattice"]["lever"] > fins["trailing_edge"][
        "lever"]


@pytest.mark.slow
def test_the_downwash_on_the_static_terms_keeps_the_rotary_terms():
    """The aircraft tail's rule scales the drift terms by 1 - epsilon and keeps the yaw-rate
    terms; epsilon is the body pair's sidewash at the rudders (large under datcom's forward
    station, small under stratford_panel's)."""
    rows = {(r["method"], r["component"], r["candidate"]): r
            for m in ("datcom", "stratford_panel") for r in component_rows(m)}
    eps = epsilon_at(5, "datcom")
    assert 0.3 < eps < 0.6
    assert epsilon_at(5, "stratford_panel") < 0.1
    d, b = (rows[("datcom", "stern planes", c)] for c in ("static_downwash", "three_quarter"))
    assert d["Yr"] == pytest.approx(b["Yr"], rel=1e-9)
    assert d["Yv"] < b["Yv"]
    assert d["lever"] < b["lever"] < 0.0


@pytest.mark.slow
def test_no_rule_reaches_roddys_levers():
    """None of the rules gives the stern planes' measured lever (-0.99) or the sail's (+0.11)
    within 0.05 of the length (the closest: the downwash on the static terms, -0.85 under
    datcom; the sail's trailing edge, +0.17)."""
    for m in ("datcom", "stratford_panel"):
        for r in component_rows(m):
            assert abs(r["lever"] - r["measured_lever"]) > 0.05, r


def test_an_unknown_rule_is_an_error():
    with pytest.raises(ValueError, match="incidence candidate"):
        candidate_lift(5, "datcom", "quarter_chord")


@pytest.mark.slow
def test_the_models_rule_counts_what_lift_band_counts():
    """The checks of the model's own rule are the library's (validation.lift.issue_checks,
    drift_curve_checks)."""
    from validation.lift import drift_curve_checks

    c = checks("stratford_panel", "three_quarter")
    assert c["table4"][0] == issue_checks("stratford_panel")
    assert c["drift"] == drift_curve_checks("stratford_panel")
    from validation.lift import lift_band
    assert c["band"] == pytest.approx(lift_band("stratford_panel")["lift"], rel=1e-9)
    assert set(CANDIDATES) >= {"three_quarter", "trailing_edge"}


@pytest.mark.slow
def test_validation_doc_fin_incidence_section_is_current():
    """docs/validation.md's section of these rules is what the code writes now."""
    from test_validation_doc import assert_section_is_current

    assert_section_is_current("fin_incidence")


def test_the_sail_diagnosis_solves_its_own_equations():
    """The two elements reproduce the measured Y'_v, N'_v and Y'_r of the sail's increment
    (4 - 3) exactly and put the sail's incidence between its 3/4 chord and, within 0.01 L_BP,
    its trailing edge; N'_r, left free, within 30 %."""
    from validation.rotary_trace import measured_increment

    d = sail_diagnosis("stratford_panel")
    inc = measured_increment(4, 3)
    k_s, k_b = d["k_s"], d["k_b"]
    assert -(k_s + k_b) == pytest.approx(inc["Yv"], rel=1e-12)
    assert -(k_s * d["x_s"] + k_b * d["x_b"]) == pytest.approx(inc["Nv"], rel=1e-12)
    assert -(k_s * d["x_i"] + k_b * d["x_b"]) == pytest.approx(inc["Yr"], rel=1e-12)
    assert 0.0 < d["strength_ratio"] < 1.0 and 0.0 < d["body_ratio"] < 1.0
    assert d["x_te"] - 0.01 < d["x_i"] < d["x_i_model"]
    assert abs(d["Nr_ratio"] - 1.0) < 0.3
    assert d["x_b"] == pytest.approx(-0.418, abs=0.01)
    assert inc["Yr"] / inc["Yv"] == pytest.approx(0.108, abs=0.002)


@pytest.mark.slow
def test_the_rank_one_change_is_the_model_built_with_the_rule(monkeypatch):
    """dL = sum u (a' - a)^T is exactly the model estimated with the lift's rotary incidence
    point moved to the trailing edge (configuration 2 as built, sail and planes)."""
    import warnings

    import stripcoef
    import stripcoef.assembly.lift as lift
    from stripcoef.geometry.vehicle import parse_vehicle
    from validation.lift import _moment_point, suboff_vehicle_data

    via_rule = _roddy_derivatives(candidate_model(2, "stratford_panel", "trailing_edge"))
    monkeypatch.setattr(lift, "rotary_incidence_point",
                        lambda p, c: np.asarray(p, float) - np.array([0.75 * c, 0.0, 0.0]))
    vehicle = parse_vehicle(suboff_vehicle_data(2, "stratford_panel"), file="SUBOFF config 2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        direct = _roddy_derivatives(stripcoef.estimate(vehicle).about(_moment_point()))
    for k, v in direct.items():
        assert via_rule[k] == pytest.approx(v, rel=1e-9, abs=1e-12), k


@pytest.mark.slow
def test_the_mmg_inflow_scales_both_terms_and_moves_the_lever_aft():
    """The MMG what-if (gamma_R (v + l_R r) at the rudder, KVLCC2 constants of Yasukawa &
    Yoshimura 2015) changes the planes' panels only: the sail's increment is the model's, the
    planes' drift column is gamma_R times the model's fin part, the lever moves aft to near the
    effective station l'_R L_BP from midship (the increment holds added mass and Munk part:
    within 0.03 L_BP), still short of Roddy's -0.99; the rudders alone give the same yaw-plane
    rows (the horizontal planes answer w and q only)."""
    from validation.fin_incidence import MMG_GAMMA_R, MMG_L_R, mmg_station
    from validation.lift import FT, val

    assert MMG_GAMMA_R == pytest.approx(0.5175) and MMG_L_R == -0.710
    rows = {(r["component"], r["candidate"]): r for r in component_rows("datcom")}
    for cand in ("mmg_planes", "mmg_rudder"):
        sail, base = rows[("sail", cand)], rows[("sail", "three_quarter")]
        for k in ("Yv", "Nv", "Yr", "Nr", "lever"):
            assert sail[k] == pytest.approx(base[k], rel=1e-12), k
    p, r = rows[("stern planes", "mmg_planes")], rows[("stern planes", "mmg_rudder")]
    for k in ("Yv", "Nv", "Yr", "Nr"):
        assert p[k] == pytest.approx(r[k], rel=1e-9), k
    x_r = mmg_station() / (FT * val("t1.L_BP"))
    assert x_r == pytest.approx(MMG_L_R + (val("moment_point.x") - 0.5 * val("t1.L_BP"))
                                / val("t1.L_BP"), rel=1e-12)
    assert p["lever"] == pytest.approx(x_r, abs=0.03)
    assert p["measured_lever"] < p["lever"] - 0.2
    # the yaw-plane rows differ from the model's by the fins' lift alone: Y'_v drops by
    # (1 - gamma_R) of the planes' lift, which is most of the increment
    b = rows[("stern planes", "three_quarter")]
    assert 0.4 < p["Yv"] / b["Yv"] < 0.6
    dl = candidate_lift(5, "datcom", "mmg_rudder")
    assert np.abs(dl[2]).max() == 0.0 and np.abs(dl[4]).max() == 0.0   # no Z, M from rudders
