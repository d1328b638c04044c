"""Issue 33: the independent benchmark compares a force effect's magnitude with the truth in
the units the log determines it in, the thrust's (benchmarks.diagnose_independent)."""

from __future__ import annotations

import numpy as np
import pytest

from benchmarks.diagnose_independent import magnitude_truth, thrust_gain, written_gain
from validation.independent import perturbed_truth
from validation.synthetic import rov_model


def _truth():
    prior = rov_model().to_dict()
    truth = perturbed_truth(prior, np.random.default_rng(3))
    truth.effect, truth.strength = "tether_drag", 0.2
    return prior, truth


def test_a_force_effect_is_compared_in_the_thrust_units():
    """tau_map g = ... + F: the log determines F / g; with a thrust scale s fitted and the
    written thrusters' gain g_w, F s g_w / g. Effects that are not forces keep the drawn
    strength."""
    prior, truth = _truth()
    g = thrust_gain(truth, prior, 0)
    assert g != pytest.approx(1.0, abs=1e-3)
    assert magnitude_truth(truth, prior, "tether_drag", "surge") == pytest.approx(0.2 / g)
    assert magnitude_truth(truth, prior, "tether_drag", "surge", 0.8, 1.1) == pytest.approx(
        0.2 * 0.8 * 1.1 / g)
    truth.strength = 0.25
    assert magnitude_truth(truth, prior, "thruster_lag", "surge") == 0.25


def test_the_written_gain_is_one_without_applied_gains_and_the_mean_with_them():
    prior, _ = _truth()
    assert written_gain({}, prior, "surge") == 1.0
    names = [t["name"] for t in prior["thrusters"]]
    same = {"thruster_gains": {"applied": True, "gains": {n: 1.2 for n in names}}}
    assert written_gain(same, prior, "surge") == pytest.approx(1.2)
    off = {"thruster_gains": {"applied": False, "gains": {n: 1.2 for n in names}}}
    assert written_gain(off, prior, "surge") == 1.0


def test_an_effect_replacing_a_prior_term_is_the_change_the_model_needs():
    """mag33d: the truth's buoyancy B_p + s and surge X_u = s replace the prior's terms, which
    stay absolute in the model's balance. At a level hover the truth's heave balance is
    g tau = W - B_true (Fossen 2011 eq. 4.6), the model's s g_w tau = (W - B_p) + b: the
    reference b is the one that makes the model's balance hold, and -s at g = s g_w = 1;
    likewise the surge balance g tau = X_u,true u against s g_w tau = (X_u,p + d_L) u."""
    from validation.independent import GRAVITY
    prior, truth = _truth()
    w = float(prior["mass"]) * GRAVITY
    b_p = float(prior["density"]) * float(prior["volume"]) * GRAVITY
    truth.effect, truth.strength, truth.buoyancy = "buoyancy_offset", 0.4, b_p + 0.4
    g = thrust_gain(truth, prior, 2)
    assert g != pytest.approx(1.0, abs=1e-3)
    for scale, written in ((1.0, 1.0), (0.9, 1.1)):
        b = magnitude_truth(truth, prior, "buoyancy_offset", "heave", scale, written)
        tau = (w - truth.buoyancy) / g                    # the log's mean command at a hover
        assert scale * written * tau == pytest.approx((w - b_p) + b)
    same = {**prior, "thrusters": [{**p, "ct_forward": t["ct_forward"], "eta_forward": 1.0}
                                   for p, t in zip(prior["thrusters"], truth.thrusters)]}
    assert magnitude_truth(truth, same, "buoyancy_offset", "heave") == pytest.approx(-0.4)
    truth.effect, truth.strength = "linear_drag", 2.5
    truth.d_l = np.array(truth.d_l, float)
    truth.d_l[0, 0] = 2.5
    g = thrust_gain(truth, prior, 0)
    d_l = magnitude_truth(truth, prior, "linear_drag", "surge")
    x_p = float(np.asarray(prior["linear_damping"], float)[0, 0])
    assert 2.5 / g == pytest.approx(x_p + d_l)


def test_a_noise_free_log_is_the_noisy_one_without_its_sensor_noise():
    """validation.independent.generate(logged_noise=False): the same truth and commands (the
    pilot flies on the noisy measurements), the logged states without the sensor noise."""
    from validation.independent import NOISE, generate
    prior = rov_model().to_dict()
    noisy, t1 = generate(prior, "linear_drag", 11, duration=4.0)
    clean, t2 = generate(prior, "linear_drag", 11, duration=4.0, logged_noise=False)
    assert t1.strength == t2.strength
    names = [c for c in noisy.columns if c.startswith("n_")]
    assert names
    for c in names:
        np.testing.assert_allclose(np.asarray(noisy[c]), np.asarray(clean[c]), rtol=0, atol=0)
    diff = np.asarray(noisy["u"], float) - np.asarray(clean["u"], float)
    assert np.std(diff) == pytest.approx(NOISE["u"], rel=0.5)
    assert np.any(diff != 0.0)


def test_an_added_mass_and_a_thrust_scale_are_compared_at_the_written_gains():
    """fresh33f: the written model's thrust in the DOF is s g_w of the prior's map. An added
    mass is the truth's inertia at that thrust less the prior's, (M_RB + M_A,true) s g_w / g
    - (M_RB + M_A,prior), as a force effect is F s g_w / g; a thrust scale is the one that
    makes s g_w the truth's g. At g_w = 1 both are the rule before."""
    from benchmarks.diagnose_independent import prior_inertia
    prior, truth = _truth()
    truth.effect = "added_mass_error"
    g = thrust_gain(truth, prior, 0)
    m_rb = float(np.asarray(prior["rigid_body_mass"], float)[0, 0])
    m_true = m_rb + float(truth.m_a[0, 0])
    for scale, written in ((1.0, 1.0), (0.9, 0.856), (1.05, 1.2)):
        ref = magnitude_truth(truth, prior, "added_mass_error", "surge", scale, written)
        # the model's inertia over its thrust equals the truth's over its own
        assert (prior_inertia(prior, 0) + ref) / (scale * written) == pytest.approx(m_true / g)
        te = magnitude_truth(truth, prior, "thrust_effectiveness", "surge", scale, written)
        assert te * written == pytest.approx(g)
    # a force effect keeps its rule (s g_w / g)
    assert magnitude_truth(truth, prior, "tether_drag", "surge", 0.9, 0.856) == pytest.approx(
        truth.strength * 0.9 * 0.856 / g)


def _old_row(prior, truth, category, scale, gains, estimate):
    """A row as the benchmark wrote it before fresh33f: its reference at g_w = 1 (the rule
    then), the applied gains stored (None: none applied), no mark."""
    return {"vehicle": "rov", "category": category, "seed": 1, "mode": "all", "dof": "surge",
            "thruster_gains": gains, "estimate": estimate,
            "magnitude_truth": magnitude_truth(truth, prior, category, "surge", scale, 1.0),
            "magnitude_error": 0.5}


def test_a_stored_row_is_converted_from_its_own_gains():
    """benchmarks.diagnose_independent.converted on constructed rows: the converted reference is the
    present rule's at the row's written gain (here every thruster's gain 0.856: g_w 0.856),
    its error recomputed from the row's estimate; a row without applied gains, a marked
    row and a force effect's row keep their reference."""
    from benchmarks.diagnose_independent import converted
    prior, truth = _truth()
    priors = {"rov": prior}
    gains = {t["name"]: 0.856 for t in prior["thrusters"]}
    for category, scale in (("added_mass_error", 0.95), ("thrust_effectiveness", 1.0)):
        truth.effect = category
        new = magnitude_truth(truth, prior, category, "surge", scale, 0.856)
        row = _old_row(prior, truth, category, scale, gains, estimate=1.03 * new)
        got = converted(row, priors)
        assert got["written_gain"] == pytest.approx(0.856)
        assert got["magnitude_truth"] == pytest.approx(new)
        assert got["magnitude_error"] == pytest.approx(0.03)
        assert got["magnitude_truth_before"] == row["magnitude_truth"]
        assert converted(got, priors) is got                    # marked: left as it is
        plain = _old_row(prior, truth, category, scale, None, estimate=1.0)
        assert converted(plain, priors)["magnitude_truth"] == pytest.approx(
            plain["magnitude_truth"])
    tether = {**_old_row(prior, truth, "thrust_effectiveness", 1.0, gains, 1.0),
              "category": "tether_drag"}
    assert converted(tether, priors) is tether


def test_a_kept_effect_is_compared_at_the_scales_the_written_model_holds():
    """fresh33f: a kept step's value is read back from the written model, which holds no
    removed thrust scale; a removed step's value is the final fit's, beside every scale. A
    stored row of a kept linear drag beside a removed scale 0.8 is converted to the reference
    at scale 1: (r + X_u,p) / 0.8 - X_u,p."""
    from benchmarks.diagnose_independent import converted, held_scales
    te = [{"effect": "thrust_effectiveness", "kept": False, "parameters": {"scale": 0.8}},
          {"effect": "thrust_effectiveness", "kept": True, "parameters": {"scale": 0.9}}]
    assert held_scales(te, True) == pytest.approx(0.9)
    assert held_scales(te, False) == pytest.approx(0.72)
    prior, truth = _truth()
    truth.effect, truth.strength = "linear_drag", 2.5
    truth.d_l = np.array(truth.d_l, float)
    truth.d_l[0, 0] = 2.5
    x_p = float(np.asarray(prior["linear_damping"], float)[0, 0])
    old = magnitude_truth(truth, prior, "linear_drag", "surge", 0.8)
    new = magnitude_truth(truth, prior, "linear_drag", "surge", 1.0)
    assert new == pytest.approx((old + x_p) / 0.8 - x_p)
    row = {"vehicle": "rov", "category": "linear_drag", "seed": 1, "mode": "all", "dof": "surge",
           "thruster_gains": None, "estimate": new, "magnitude_truth": old,
           "magnitude_error": 0.3,
           "step_detail": {"surge": [{"effect": "linear_drag", "kept": True,
                                      "parameters": {"d_L": new}}, te[0]]}}
    got = converted(row, {"rov": prior})
    assert got["magnitude_truth"] == pytest.approx(new)
    assert got["magnitude_error"] == pytest.approx(0.0, abs=1e-9)
    removed = {**row, "step_detail": {"surge": [{"effect": "linear_drag", "kept": False,
                                                 "parameters": {"d_L": new}}, te[0]]}}
    assert converted(removed, {"rov": prior}) is removed      # fitted beside the scale
