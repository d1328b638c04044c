"""Issue 33, adopt33g: with ``retest_scales`` (an option) a whole-log thrust scale or
added-mass release is judged again in the model the shared fits wrote, like every other own
step (:func:`stripcoef.diagnose.stepwise.retest_steps`; Efroymson 1960; Draper & Smith 1998
sec. 15.2).

The seeded log is the independent simulator's (validation.independent), BlueROV2-like log
1795940006 of seed 1795938998 of ``benchmarks.diagnose_independent``: a thruster lag of
0.770 s in every thruster, the truth's roll thrust 0.933 of the prior's map on the log.
"""

from __future__ import annotations

import warnings
from types import SimpleNamespace

import pytest

from conftest import shipped_model
from stripcoef.diagnose.stepwise import _own_steps


def _step(effect, signature=""):
    return SimpleNamespace(effect=effect, signature=signature, not_determined=None)


def test_a_scale_and_an_added_mass_release_are_judged_again_the_shared_effects_are_not():
    r = SimpleNamespace(steps=(_step("thrust_effectiveness"), _step("added_mass_error"),
                               _step("thruster_lag"), _step("current"),
                               _step("linear_drag")))
    assert [s.effect for s in _own_steps(r, scales=True)] == [
        "thrust_effectiveness", "added_mass_error", "linear_drag"]
    # the default: the steps judged with the bands are not judged again
    assert [s.effect for s in _own_steps(r)] == ["linear_drag"]


@pytest.mark.slow
def test_a_roll_scale_fitted_before_the_shared_lag_is_withdrawn_beside_it():
    """Roll's selection named a thrust scale 1.78 (z 21) before the thrusters' one lag was
    fitted over the DOFs and written into roll (the lag's held-out gain in roll beside the
    scale -2.4). Judged again beside the lag, the scale (1.51) and roll's calibrated inertia
    are not told apart (its implied inertia change within 2.5 bands of the added mass), so
    roll holds the lag alone; the truth has no roll scale (0.933 of the map on the log)."""
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    log, truth = generate(prior.to_dict(), "thruster_lag", 1795940006, duration=300.0)
    assert truth.strength == pytest.approx(0.7704, abs=1e-4)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf"),
                       retest_scales=True).to_dict()
    roll = res["per_dof"]["roll"]
    assert [s["effect"] for s in roll["steps"]] == ["thruster_lag"]
    lag = roll["steps"][0]["parameters"]["time_constant"]
    assert lag == pytest.approx(truth.strength, rel=0.05)
    withdrawn = {w["effect"]: w for w in roll.get("withdrawn") or ()}
    assert "judged again" in withdrawn["thrust_effectiveness"]["reason"]
    assert "2.5 bands" in withdrawn["thrust_effectiveness"]["reason"]
    # no DOF holds a thrust scale: the truth's gains on the log are the background's
    assert not any(s["effect"] == "thrust_effectiveness"
                   for r in res["per_dof"].values() for s in r["steps"])
