"""The tether's signature, its dependence on the paid-out length, tested again with the thrust
map's per-thruster gains free when the test without them fails (``stripcoef.diagnose.gainfree``,
issue 33): seeded known truths whose thrusters deliver other than the prior's map (a real
vehicle's thrusters differ from their bench map; the independent benchmark draws each
x U(0.75, 1.25)).
"""

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import stripcoef
from stripcoef.diagnose.gainfree import GAINS_FREE, variant
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from stripcoef.logfile import Log
from validation.synthetic import GAINS_OFF
from validation.synthetic import gains_off_log as _log

ROOT = Path(__file__).resolve().parent.parent
#: the truth's thrust per unit of the prior's map, per thruster [-]
GAINS = GAINS_OFF



def test_retest_holds_one_gain_per_thruster_acting_in_the_dof():
    log, prior, _ = _log(None, 1, duration=40.0)
    assert variant(get_effect("tether_drag")) is GAINS_FREE
    assert variant(GAINS_FREE) is None and variant(get_effect("current")) is None
    data = window_data(log, prior)
    # the written effect releases D_Q; the buoyancy change is fitted with it, not written
    tether = get_effect("tether_drag").nuisance(data, 0)
    assert tether.shape == (data.n_windows, 2)
    # surge: a buoyancy change Delta B changes the restoring force by -Delta B sin(theta)
    np.testing.assert_allclose(tether[:, 1], data.mean(np.sin(data.eta[:, 4])), rtol=1e-12,
                               atol=1e-15)
    eff = GAINS_FREE
    nuis = eff.nuisance(data, 0)
    # D_Q, the buoyancy change, then port and starboard (the two thrusters that push in surge)
    assert nuis.shape == (data.n_windows, 4)
    acting = data.acting(0)
    assert [prior.thrusters[k].name for k in acting] == ["port", "starboard"]
    np.testing.assert_allclose(nuis[:, 2:].sum(axis=1), data.mean_held(data.tau[:, 0]),
                               rtol=1e-12, atol=1e-12)
    low = eff.nuisance_lower(data, 0)
    assert low[0] == pytest.approx(-abs(prior.quadratic_damping[0, 0]))
    assert low[1] == -np.inf
    np.testing.assert_allclose(low[2:], -0.9)
    assert len(eff.prior_sd(data, 0)) == 5 and np.all(np.isinf(eff.prior_sd(data, 0)))
    # without the length column there is no signature and no nuisance
    no_length = Log({k: v for k, v in log.columns.items() if k != "tether_length"})
    assert eff.nuisance(window_data(no_length, prior), 0) is None


@pytest.mark.slow
def test_tether_hidden_by_the_sway_added_mass_is_named_first():
    """The independent simulator's VideoRay-like vehicle, seed 12 (truth: every coefficient
    family x U(0.75, 1.25), surge thrust 1.049 x the prior's map, c_t = 0.283): without the
    retest the tether's test gave z = 2.1 and nothing was named; with the gains free z = 4.9,
    and the tether written without them had c_t = 0.273. What hid it was not the thrust map
    but the sway added mass (4.38 kg against the prior's 4.73), which surge's calibration
    did not hold (sway has no thruster, so it was not "excited"): with it calibrated
    through C_A (stripcoef.diagnose.cross) the test without the gains finds the tether
    (z 6.0 in the oracle probe of issue 33) and no retest is needed; its c_t is 17 % high."""
    from validation.independent import generate as independent
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        prior = stripcoef.estimate(ROOT / "geometry" / "videoray_pro3.yaml")
        log, truth = independent(prior.to_dict(), "tether_drag", 12, duration=300.0)
        res = diagnose(log, prior, dof="surge").to_dict()
    assert res["steps"] and res["steps"][0]["effect"] == "tether_drag"
    assert res["steps"][0]["signature"] == "dependence on tether_length"
    assert "M_sway" in res["per_dof"]["surge"]["calibration"]["parameters"]
    # c_t 0.332 against 0.283 (+17 %): within 3 of its standard deviations, not within
    # 15 % (measured, issue 33: the prior with the truth's buoyancy alone gives 0.299, with
    # its thrust map alone 0.287: (W - B) sin(theta) and the map's error stay in surge)
    step = res["steps"][0]
    got = step["final_parameters"]["c_t"]
    assert abs(got - truth.strength) < 3.0 * step["std"]["c_t"]


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="a tether found by the test without the gains is "
                   "written with the c_t of that fit: the thrust map's error (0.8 and 1.2) "
                   "biases it, 0.180 for a truth of 0.225 (the retest's fit, with the gains "
                   "free, gives 0.226, but its gains are not written)")
def test_tether_magnitude_when_the_thrust_map_is_off():
    log, prior, known = _log("tether_drag", 2, duration=240.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="surge").to_dict()
    assert res["steps"] and res["steps"][0]["effect"] == "tether_drag"
    got = res["steps"][0]["final_parameters"]["c_t"]
    assert got == pytest.approx(known["magnitude"], rel=0.05)


def test_no_tether_is_named_on_a_clean_log_with_the_thrust_map_off():
    log, prior, _ = _log(None, 2, duration=120.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="surge", effects=["tether_drag"]).to_dict()
    assert not any(s["effect"] == "tether_drag" for s in res["steps"])
    cand = {c["effect"]: c for c in res["per_dof"]["surge"]["candidates"]}["tether_drag"]
    assert cand["signature"] == "dependence on tether_length"
    assert not cand["significant"]


def test_the_buoyancy_column_is_the_restoring_force_of_a_buoyancy_change():
    """A model lighter by Delta B [N] (a larger displaced volume) leaves, against the same log,
    a window residual larger by Delta B times the column in every translation: the window
    mean of sin(theta), -cos(theta) sin(phi), -cos(theta) cos(phi) (Fossen 2011, eq. 4.6)."""
    from stripcoef.effects.hydrodynamic import buoyancy_column

    log, prior, _ = _log(None, 1, duration=40.0)
    delta_b = 1.5
    lighter = replace(prior, volume=prior.volume + delta_b / (prior.density * prior.gravity))
    d0, d1 = window_data(log, prior), window_data(log, lighter)
    assert np.ptp(d0.eta[:, 4]) > 0.01 and np.ptp(d0.eta[:, 3]) > 0.01
    for dof in range(3):
        np.testing.assert_allclose(d0.e0[:, dof] - d1.e0[:, dof],
                                   delta_b * buoyancy_column(d0, dof), rtol=1e-6,
                                   atol=1e-9 * delta_b)


@pytest.mark.slow
def test_a_dof_thrust_scale_does_not_remove_the_gain_bias_of_a_tether():
    """The independent simulator's BlueROV2-like tether log of seed 28113028 (truth c_t
    0.2025 in the thrust's units), diagnosed in surge alone: the retest with each thruster's
    gain free finds the tether, and the c_t written from the fit with the prior's map is
    +88 %. Fitted beside the DOF's thrust scale (what one DOF could write) it stays +88 %:
    the bias is the gains' contrasts, which explain most of the surge residual (measured,
    ``benchmarks.tether_gain_probe``; docs/performance.md, ``tether33d``)."""
    from benchmarks.tether_gain_probe import probe

    rec = probe("bluerov2_heavy", 28113028, 300.0)
    assert rec["retested"]
    a, b, c = rec["prior_map"], rec["thrust_scale"], rec["gains_free"]
    assert a["c_t"] == pytest.approx(rec["selected"], rel=1e-9)
    assert a["error"] > 0.5                           # the written c_t is far off
    assert abs(b["error"] - a["error"]) < 0.05       # a common scale does not move it
    assert abs(c["error"]) < abs(a["error"]) / 3     # the gains free do
    assert c["held_out_error"] < 0.2 * a["held_out_error"]


def test_the_bias_is_retested_with_one_gain_per_thruster_acting_in_the_dof():
    """A heave bias (buoyancy offset) whose test fails is repeated with the thrust gains free
    (Indiveri 1998 eq. 4.16: the weight-buoyancy term identified beside the thrusters'
    efficiency): the columns are the tether's gain columns, no D_Q, no buoyancy change."""
    from stripcoef.diagnose.gainfree import BIAS_GAINS_FREE
    from stripcoef.effects.hydrodynamic import BuoyancyOffsetGainsFree

    log, prior, _ = _log(None, 1, duration=40.0)
    assert variant(get_effect("buoyancy_offset"), 2) is BIAS_GAINS_FREE
    assert isinstance(BIAS_GAINS_FREE, BuoyancyOffsetGainsFree)
    assert variant(BIAS_GAINS_FREE, 2) is None
    # heave only: elsewhere the bias is not the weight-buoyancy term of Indiveri's model
    assert all(variant(get_effect("buoyancy_offset"), d) is None for d in (0, 1, 3, 4, 5))
    assert variant(get_effect("tether_drag"), 0) is GAINS_FREE
    data = window_data(log, prior)
    for dof in (0, 2):
        nuis = BIAS_GAINS_FREE.nuisance(data, dof)
        acting = data.acting(dof)
        assert nuis.shape == (data.n_windows, len(acting))
        np.testing.assert_allclose(nuis, GAINS_FREE.nuisance(data, dof)[:, 2:], rtol=1e-12,
                                   atol=1e-15)
        np.testing.assert_allclose(BIAS_GAINS_FREE.nuisance_lower(data, dof), -0.9)
        assert np.all(np.isinf(BIAS_GAINS_FREE.prior_sd(data, dof)))
    # the bias's own column is the written effect's
    np.testing.assert_allclose(BIAS_GAINS_FREE.own_design(data, 2)[1],
                               get_effect("buoyancy_offset").own_design(data, 2)[1])
