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
