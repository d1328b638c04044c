"""Issue 33 (spur33d): a thrust asymmetry in a translation must be identified apart from a
dead band fitted beside a buoyancy change
(:meth:`stripcoef.diagnose.thrusterparts.ThrusterParts.deadband_confounded`).

The logs are the independent simulator's (validation.independent): every truth's thrusters
deliver U(0.75, 1.25) x their maps and its buoyancy U(0.98, 1.02) x the prior's; a dead band
or an asymmetry only where drawn.
"""

from __future__ import annotations

import pytest

from conftest import parts_trial, shipped_model, whole_log_parts
from stripcoef.diagnose.thrusterparts import BuoyancyFreeDeadband

SIX = (0, 1, 2, 3, 4, 5)
HEAVE, YAW = 2, 5


def test_the_check_leaves_rotations_and_other_effects_alone():
    from stripcoef.diagnose.thrusterparts import OneDofParts
    from stripcoef.effects.windows import window_data
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    log, _ = generate(prior.to_dict(), "deadband", 1795930177, duration=30.0)
    one = OneDofParts(window_data(log, prior), [HEAVE])
    assert one.deadband_confounded({"effect": "deadband"}, HEAVE) == ""
    assert one.deadband_confounded({"effect": "thrust_asymmetry"}, YAW) == ""
    eff = BuoyancyFreeDeadband()
    assert eff.nuisance(one.data, HEAVE).shape == (one.data.n_windows, 1)
    assert eff.name == "deadband"


@pytest.mark.slow
def test_a_heave_asymmetry_that_is_the_truths_dead_band_is_refused():
    """Fresh seed 1795929171, BlueROV2-like dead-band log 1795930177 (every thruster's dead
    band 0.252 of the full command, the truth 2.17 N heavier than the prior, no asymmetry):
    the heave asymmetry is identified apart from a buoyancy change alone, not beside the dead
    band profiled with the buoyancy change free, whose width is the truth's."""
    parts, truth = whole_log_parts("bluerov2_heavy.yaml", SIX, "deadband", 1795930177, 300.0)
    trial = parts_trial(parts, "thrust_asymmetry", HEAVE)
    assert parts.buoyancy_confounded(trial, HEAVE) == ""
    why = parts.deadband_confounded(trial, HEAVE)
    assert why.startswith("not identified apart from a dead band"), why
    width = float(why.split("dead band of ")[1].split(" ")[0])
    assert width == pytest.approx(truth.strength, rel=0.05)


@pytest.mark.slow
def test_an_asymmetry_of_every_thruster_is_identified_beside_a_dead_band():
    """A truth whose thrusters all deliver the drawn share of their backward maps (seed
    29112026's BlueROV2-like asymmetry log 29113052): its heave asymmetry stands beside the
    dead band and the buoyancy change."""
    parts, _ = whole_log_parts("bluerov2_heavy.yaml", SIX, "thrust_asymmetry", 29113052, 300.0)
    trial = parts_trial(parts, "thrust_asymmetry", HEAVE)
    assert parts.deadband_confounded(trial, HEAVE) == ""
