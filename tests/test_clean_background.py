"""benchmarks.clean_background: a clean-log step is the truth's background only when its
fitted change is within a factor 2 of the truth's own change on the log."""

from __future__ import annotations

from benchmarks.clean_background import verdict


def test_an_asymmetry_the_truth_has_is_background_and_the_wrong_way_is_not():
    truth = {"eta_forward": 1.044, "eta_backward": 0.924, "gain": 0.984}
    # BlueROV2 282147 pitch: fitted 0.933 against the truth's 0.885
    assert verdict("thrust_asymmetry", truth, 1.8,
                   {"eta_forward": 0.817, "eta_backward": 0.762}) == "background"
    # the other way (BlueROV2 5193037 heave: fitted 0.897 against the truth's 1.051)
    other = {"eta_forward": 0.982, "eta_backward": 1.032, "gain": 1.010}
    assert verdict("thrust_asymmetry", other, -1.6,
                   {"eta_forward": 0.854, "eta_backward": 0.766}).startswith("false positive")
    # a scale the other way from the truth's gain (BlueROV2 282147 pitch), and one three
    # times the truth's change
    assert verdict("thrust_effectiveness", truth, 1.8,
                   {"scale": 1.17}) == "false positive (wrong direction)"
    assert verdict("thrust_effectiveness", {**truth, "gain": 0.95}, 1.8,
                   {"scale": 0.85}) == "false positive"


def test_a_scale_near_the_truths_gain_and_a_buoyancy_offset_are_background():
    truth = {"eta_forward": 0.896, "eta_backward": 0.857, "gain": 0.878}
    assert verdict("thrust_effectiveness", truth, 1.8, {"scale": 0.812}) == "background"
    assert verdict("buoyancy_offset", truth, 1.8, {"b": -1.8}) == "background"
    assert verdict("linear_drag", truth, 1.8, {"d_L": 2.0}) == "false positive"
