"""Issue 33: a whole-log thrust scale must be identified apart from the other DOFs' added
masses (:mod:`stripcoef.diagnose.crossscale`).

The independent simulator's pilot holds roll and pitch level with the vehicle file's
C(nu) nu as a feed-forward (validation.independent.Pilot.coriolis), so the BlueROV2's pitch
command is mostly that Coriolis moment, and a scale of it imitates an error of the added
masses in it (closed-loop identifiability, Ljung 1999 sec. 13.4). Seed 29113033 of the
issue-size run (benchmarks/data/diagnose_independent_300s.md; added_mass_error: the truth's
surge added mass 2.48x the file's, its thrusters moving the pitch thrust by +2.6 %) named a
pitch scale of 1.64 at z 3.0. Refitted with the added masses of the other DOFs free beside
it (Rothenberg 1971, Theorem 1: identified only by what the other columns do not span) it
falls under the z gate. A true scale (seed 29113036, thrust_effectiveness: the truth's pitch
thrust -40 % on the log) stays identified.

The logs are generated from known truths with seeded noise.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from conftest import parts_trial, whole_log_parts

PITCH = 4


@lru_cache(maxsize=None)
def _pitch_scale(effect: str, seed: int):
    """``(parts, trial)``: the siblings of a BlueROV2 log's six DOFs and the selection's
    record of a pitch thrust scale in it."""
    parts, _ = whole_log_parts("bluerov2_heavy.yaml", range(6), effect, seed, 300.0)
    return parts, parts_trial(parts, "thrust_effectiveness", PITCH)


def _z(trial) -> float:
    from stripcoef.diagnose.select import _own_estimate
    _, value, sd = _own_estimate(trial["_cfg"], trial["_ev"])
    return float(abs(value[-1]) / sd[-1])


def test_the_free_scale_holds_the_other_dofs_added_masses_free():
    from stripcoef.diagnose.crossscale import CrossMassFreeScale, cross_free_scale
    eff = cross_free_scale(("M_surge", "M_heave"))
    assert isinstance(eff, CrossMassFreeScale) and eff.name == "thrust_effectiveness"
    assert eff.nuisance_names == ("M_surge", "M_heave")
    # the registry's scale is unchanged (an effect is a frozen spec)
    from stripcoef.effects.laws import get_effect
    assert get_effect("thrust_effectiveness").nuisance_names == ()


def test_other_effects_are_not_tested():
    from stripcoef.diagnose.crossscale import cross_mass_confounded
    assert cross_mass_confounded({"effect": "linear_drag", "_cfg": object()}, PITCH, {}) == ""
    assert cross_mass_confounded({"effect": "thrust_effectiveness"}, PITCH, {}) == ""


@pytest.mark.slow
def test_a_pitch_scale_of_the_feed_forward_is_not_identified():
    """Seed 29113033: the pitch scale passes the z gate alone and falls under it with the
    other DOFs' added masses free."""
    from stripcoef.diagnose.crossscale import cross_mass_confounded, cross_names
    from stripcoef.diagnose.settings import MIN_Z
    parts, trial = _pitch_scale("added_mass_error", 29113033)
    assert {"M_surge", "M_heave"} <= set(cross_names(trial["_cfg"]))
    assert _z(trial) >= MIN_Z
    assert trial["_ev"]["hyper"][0] > 0.3           # a scale well above 1
    why = cross_mass_confounded(trial, PITCH, {})
    assert why.startswith("not identified apart from the other DOFs' added masses"), why
    # the same reason in the whole-log contradictions
    assert any(w == why for w in parts.contradictions(trial, PITCH))


@pytest.mark.slow
def test_a_true_pitch_scale_stays_identified():
    """Seed 29113036: the truth's thrusters deliver about 0.6 of their map in pitch; the scale
    is still far from 1 with the added masses free."""
    from stripcoef.diagnose.crossscale import cross_mass_confounded
    _, trial = _pitch_scale("thrust_effectiveness", 29113036)
    assert trial["_ev"]["hyper"][0] < -0.2
    assert cross_mass_confounded(trial, PITCH, {}) == ""
    assert np.isfinite(_z(trial))
