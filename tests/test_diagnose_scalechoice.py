"""Issue 33: a thrust scale fitted in the commanded force's units, and the choice between a
thrust scale and an added-mass change (stripcoef.diagnose.scalechoice): which one the log
needs, or that it cannot tell them apart.

Every log is generated from a known truth with seeded noise.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from stripcoef.diagnose.fit import _Config, _evaluate
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.diagnose.scalechoice import contender, judged_with_bands
from stripcoef.diagnose.select import _dof_calibration, excited_dofs
from stripcoef.diagnose.settings import DiagnoseSettings
from stripcoef.diagnose.written import thrust_scale
from stripcoef.effects.laws import get_effect
from stripcoef.effects.windows import window_data
from test_diagnose_select import _surge_log
from validation.synthetic import rov_model


def test_the_scale_is_a_profiled_parameter_with_its_bounds():
    eff = get_effect("thrust_effectiveness")
    assert eff.to_parameters(np.zeros(0), np.array([-0.3])) == {"scale": pytest.approx(0.7)}
    assert eff.residual_scale(np.array([-0.3])) == pytest.approx(0.7)
    grid = eff.grid(None, 0)
    assert grid[0] == pytest.approx(eff.BOUNDS[0] - 1) and grid[-1] == pytest.approx(
        eff.BOUNDS[1] - 1)
    assert eff.at_bound({"scale": 0.05}) == "lower"
    assert eff.at_bound({"scale": 2.0}) == "upper"
    assert eff.at_bound({"scale": 0.7}) == ""
    assert judged_with_bands(eff) and judged_with_bands(get_effect("added_mass_error"))
    assert not judged_with_bands(get_effect("linear_drag"))


def test_contenders_of_the_choice():
    rec = {"effect": "added_mass_error", "significant": False, "_only_evidence": True,
           "band_excess": 3.0, "rejected_because": ["not beyond chance on 56 windows"]}
    assert contender(rec)
    within = {**rec, "_only_evidence": False, "band_excess": 2.0, "rejected_because": [
        "no signature in this log and the M change it implies (0.9) is within 2.5 bands"]}
    assert contender(within)
    assert not contender({**within, "rejected_because": ["z = 1.0 < 3"]})
    assert contender({"effect": "thrust_effectiveness", "significant": True,
                      "band_excess": None})
    assert not contender({"effect": "thrust_effectiveness", "significant": False,
                          "rejected_because": ["z = 1.6 < 3"]})
    assert contender({"effect": "thrust_effectiveness", "significant": False,
                      "rejected_because": ["held-out error rises (-6.3% gain, beyond 2%)"]})
    assert not contender({"effect": "linear_drag", "significant": True, "band_excess": 9.0})


def test_a_scaled_fit_is_measured_in_the_commanded_force():
    """The design of a configuration holding a scale s is the residual divided by s, and
    the velocity noise of its inertia column by s^2 (fit._Config.residual_scale)."""
    prior = rov_model()
    data = window_data(_surge_log(prior, 3, duration=40.0), prior, window=2.0)
    cal, _ = _dof_calibration(data, 0, DiagnoseSettings(), [0], [])
    base = _Config(data, 0, cal, [])
    eff = get_effect("thrust_effectiveness")
    cfg = base.with_terms([(eff, np.array([-0.4]))])
    y0, h0, _ = base.design()
    y, h, _ = cfg.design()
    tau = data.mean_held(data.tau[:, 0])
    np.testing.assert_allclose(y, (y0 + 0.4 * tau) / 0.6, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(h, h0 / 0.6, rtol=1e-12)
    assert cfg.m_info()[2] == pytest.approx(base.m_info()[2] / 0.36, rel=1e-12)


def test_the_written_final_error_is_in_the_commanded_force():
    model = rov_model().with_effects({"name": "thrust_effectiveness", "dof": "surge",
                                      "parameters": {"scale": 0.6}, "std": {},
                                      "units": {"scale": "-"}})
    assert thrust_scale(model, "surge") == pytest.approx(0.6)
    assert thrust_scale(model, "heave") == 1.0


@pytest.mark.slow
def test_a_thrust_scale_in_a_one_dof_log_is_not_told_from_an_added_mass():
    """A truth whose thrusters deliver 0.7 of the map (stripcoef's own simulation, surge
    only). Profiled in the commanded force's units the scale is within 10 % of 0.7 (0.756:
    a surge-only log has no force the thrust does not carry, only the bands of the inertia
    and the drag fix the scale, and the posterior shares the change with them). Diagnosed,
    the first step is one of the two with the other named as not told apart (measured:
    the added mass written, the posterior likelihood ratios 15.8 and 15.1), and its size
    is the truth's in its own terms: the inertia the log shows, (M_RB + M_A)/0.7."""
    prior = rov_model()
    truth = replace(prior, thrusters=[replace(t, ct_forward=0.7 * t.ct_forward,
                                              ct_backward=0.7 * t.ct_backward)
                                      for t in prior.thrusters])
    log = _surge_log(truth, 7, duration=150.0)
    data = window_data(log, prior, window=4.0)
    cal, _ = _dof_calibration(data, 0, DiagnoseSettings(), excited_dofs(data), [])
    ev = _evaluate(_Config(data, 0, cal, [(get_effect("thrust_effectiveness"), None)]))
    assert 1.0 + ev["hyper"][0] == pytest.approx(0.7, rel=0.1)
    first = diagnose(log, prior, dof="surge").to_dict()["steps"][0]
    named = {first["effect"], *first.get("ambiguous_with", ())}
    assert named == {"thrust_effectiveness", "added_mass_error"}
    if first["effect"] == "added_mass_error":
        m = prior.mass_matrix[0, 0]
        assert first["selected_parameters"]["delta_m"] == pytest.approx(m / 0.7 - m, rel=0.15)
    else:
        assert first["selected_parameters"]["scale"] == pytest.approx(0.7, rel=0.1)


def _independent(vehicle, category, seed):
    import warnings

    import stripcoef
    from conftest import ROOT
    from validation.independent import generate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        prior = stripcoef.estimate(ROOT / "geometry" / f"{vehicle}.yaml")
    log, truth = generate(prior.to_dict(), category, seed, duration=300.0)
    return prior, log, truth


@pytest.mark.slow
def test_a_thrust_effectiveness_the_calibration_absorbed_is_named_with_its_size():
    """Independent simulator, BlueROV2-like, seed 5242: the thrusters deliver 0.688 of the
    map in surge (a drawn 0.707 times the thrusters' own factors). The calibration alone
    moves the added mass 3.1 bands and the drag 1.8: the scale has no held-out gain, and was
    named after an added-mass error at 0.54 (the release went first and freed the inertia).
    Judged with the bands it is named first, within 5 % of 0.688, and no added mass."""
    from benchmarks.diagnose_independent import thrust_gain

    prior, log, truth = _independent("bluerov2_heavy", "thrust_effectiveness", 5242)
    gain = thrust_gain(truth, prior.to_dict(), 0)
    assert gain == pytest.approx(0.688, abs=1e-3)
    steps = diagnose(log, prior, dof="surge").to_dict()["steps"]
    assert [s["effect"] for s in steps] == ["thrust_effectiveness"]
    assert steps[0]["selected_parameters"]["scale"] == pytest.approx(gain, rel=0.05)


@pytest.mark.slow
def test_an_added_mass_the_log_does_not_tell_from_a_thrust_scale_is_named_with_it():
    """Independent simulator, BlueROV2-like, seed 5243: the surge added mass is 2.03x the
    truth's perturbed one, the thrusters 0.93 of the map. Beside each other neither the
    added mass nor a thrust scale is needed (model holding both: Holm p 0.1 and 0.5): the
    step writes the added mass (the lower posterior cost) and names the scale as
    ambiguous; its size is that of the truth in the prior's thrust units, (M_RB + M_A) / g
    - M_prior = 8.27 kg, within 15 %."""
    from stripcoef.diagnose.report import text_summary

    prior, log, truth = _independent("bluerov2_heavy", "added_mass_error", 5243)
    res = diagnose(log, prior, dof="surge").to_dict()
    assert "the log does not tell it from thrust_effectiveness" in text_summary(res)
    first = res["steps"][0]
    assert first["effect"] == "added_mass_error"
    assert first["ambiguous_with"] == ["thrust_effectiveness"]
    assert first["choice"]["needed"] == {"added_mass_error": False,
                                         "thrust_effectiveness": False}
    assert first["selected_parameters"]["delta_m"] == pytest.approx(8.27, rel=0.15)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="issue 33, traced: with the other DOFs' added masses "
                   "calibrated in surge (diagnose.cross) M_22 v r and M_33 w q have the "
                   "regressors of the weighed mass's Coriolis force m(wq - vr), the one force "
                   "of the surge balance the thrust map does not carry, so the scale is left to "
                   "the bands (z 9.8 with them at the prior, 2.8 calibrated; fitted 0.877 for a "
                   "true 1.095) and is no contender; the calibration then holds the truth in "
                   "the thrust's units (M_sway -1.05, M_heave -2.14 for -0.94, -1.72; the "
                   "release 1.39 for 1.42) and a thrust asymmetry (eta 0.870/0.885), the truth's "
                   "port/starboard contrast 1.129/1.060, is best on held-out error (with that "
                   "contrast in the map: a scale 0.855 is named). A joint fit of the shared added "
                   "masses over all moving DOFs did not restore it (sway's thrust-less balance "
                   "alone gives M_22 1.18 for 4.66): not fixed")
def test_an_added_mass_with_a_thrust_gain_is_named_with_both():
    """Independent simulator, VideoRay-like, seed 871904: the surge added mass is 2.54x
    the prior's (+2.24 kg) and the surge thrusters deliver 1.095 of the map (their own
    U(0.75, 1.25) factors). Both are needed beside each other: the scale (within 5 % of
    1.095), then the added mass, within 15 % of the truth. (Steps after them, not asserted
    here: a momentum drag and a thrust asymmetry, which the validation judges.)"""
    from benchmarks.diagnose_independent import thrust_gain

    prior, log, truth = _independent("videoray_pro3", "added_mass_error", 871904)
    gain = thrust_gain(truth, prior.to_dict(), 0)
    steps = diagnose(log, prior, dof="surge").to_dict()["steps"]
    assert [s["effect"] for s in steps][:2] == ["thrust_effectiveness", "added_mass_error"]
    assert steps[0]["selected_parameters"]["scale"] == pytest.approx(gain, rel=0.05)
    assert steps[1]["selected_parameters"]["delta_m"] == pytest.approx(truth.strength,
                                                                       rel=0.15)
