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
