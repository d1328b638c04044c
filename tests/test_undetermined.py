"""What one DOF cannot determine (``stripcoef.diagnose.undetermined``, issue 33). The rule: a
one-DOF tether is determined when it is identified apart from the thrusters' gains beside the
map the model writes -- its test passes on that map, and refitted with each gain free beside
it its c_t stays MIN_Z sd from zero (Rothenberg 1971; ``crossscale.refitted_z``). On the prior's
map (``dof_gains=False``) a tether found only by the retest with each thruster's gain free is
named, its c_t reported as not determined by one DOF (the gain-free value and its sd),
nothing written; with the gains fitted in the DOF (``dof_gains``, the default) the same log's
tether is found on the gained map, identified apart from the gains, and written. The
independent benchmark scores a step not determined as named first, its magnitude not claimed.

The seeded known truth: the synthetic ROV (validation/synthetic.py) whose port and starboard
thrusters deliver 0.8 and 1.2 of the prior's map (a real vehicle's thrusters differ from their
bench map), so that yaw commands leak into surge through their contrast, with a tether of
known c_t (seed 1, 120 s: truth 0.1774).
"""

import warnings

import numpy as np
import pytest

from stripcoef.diagnose.gainfree import retested
from stripcoef.diagnose.pipeline import diagnose
from stripcoef.diagnose.gains import MIN_GAIN
from stripcoef.diagnose.report import text_summary
from stripcoef.diagnose.settings import MIN_Z, DiagnoseSettings
from stripcoef.diagnose.undetermined import ADVICE, gain_dependence, identified_z, unwritten
from stripcoef.diagnose.written import window_errors, written_effects
from stripcoef.diagnose.heldout import split
from stripcoef.diagnose.settings import VALIDATION_FRACTION
from validation.synthetic import GAINS_OFF, gains_off_log, rov_model, with_gains

#: the truth's thrust per unit of the prior's map, per thruster [-]
GAINS = GAINS_OFF



@pytest.fixture(scope="module")
def surge():
    """The rule on the prior's map: the gains not fitted in the DOF (``dof_gains=False``)."""
    log, prior, known = gains_off_log()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="surge", dof_gains=False)
    return log, prior, known, res


@pytest.fixture(scope="module")
def gained():
    """The same log diagnosed as by default: the gains fitted in the DOF's balance."""
    log, prior, known = gains_off_log()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="surge", dof_gains=True)
    return log, prior, known, res


def test_the_gains_are_fitted_in_one_dof_by_default():
    assert DiagnoseSettings().dof_gains is True


@pytest.mark.slow
def test_with_the_gains_fitted_the_tether_is_identified_apart_from_them_and_written(gained):
    """The one rule on the gained map: the tether's test passes there (no retest), with each
    gain free beside it c_t stays MIN_Z sd from zero (the refit of crossscale.refitted_z,
    the same as gain_dependence's gain-free fit), so it is determined and written, near the
    truth (measured c_t 0.181 for 0.1774), beside the gains it was fitted with (port 0.72,
    starboard 1.28 for the truth's 0.8 and 1.2)."""
    log, prior, known, res = gained
    gains = res.thruster_gains
    assert gains["applied"], gains["reason"]
    for name, truth in (("port", 0.8), ("starboard", 1.2)):
        assert abs(gains["gains"][name] - truth) < 3.0 * gains["std"][name]
    r = res.per_dof["surge"]
    step = r.steps[0]
    assert step.effect == "tether_drag" and not retested(step)
    assert step.not_determined is None and step.kept
    test = gain_dependence(step, res.fits["surge"])
    z = identified_z(step, res.fits["surge"])
    assert z == pytest.approx(abs(test["gains_free"]) / test["gains_free_std"], rel=1e-6)
    assert z >= MIN_Z
    c_t = written_effects(res.model, "surge")["tether_drag"]["c_t"]
    assert c_t == pytest.approx(step.final_parameters["c_t"], rel=1e-9)
    assert c_t == pytest.approx(known["magnitude"], rel=0.10)
    # the written model holds the gains (its thrusters' efficiencies)
    eff = {th.name: th.eta_forward / p.eta_forward
           for th, p in zip(res.model.thrusters, prior.thrusters)}
    assert eff["port"] == pytest.approx(gains["gains"]["port"], rel=1e-9)


def test_a_gain_below_the_physical_bound_is_not_written():
    """A one-DOF gain fit that puts a thruster under MIN_GAIN of its map (here the truth's
    own port thruster at 5 %: fitted 0.02) is not written: the bound every thrust factor of
    the library is held to (gains.MIN_GAIN)."""
    log, prior, _ = gains_off_log(gains={"port": 0.05, "starboard": 1.95, "vertical": 1.0,
                                         "lateral": 1.0})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="surge", dof_gains=True)
    gains = res.thruster_gains
    assert min(gains["gains"].values()) < MIN_GAIN
    assert not gains["applied"] and "physical bound" in gains["reason"]
    assert [th.eta_forward for th in res.model.thrusters] == pytest.approx(
        [th.eta_forward for th in prior.thrusters], rel=1e-12)


@pytest.mark.slow
def test_a_tether_found_only_with_the_gains_free_is_named_and_not_written(surge):
    log, prior, known, res = surge
    r = res.per_dof["surge"]
    step = r.steps[0]
    assert step.effect == "tether_drag" and retested(step)       # named first, by the retest
    nd = step.not_determined
    assert nd is not None and nd["retested"] and nd["parameter"] == "c_t"
    assert unwritten(r) == {"tether_drag"}
    # nothing written: not in the model, not among its effects, the step not kept
    assert step.kept is False
    assert "tether_drag" not in written_effects(res.model, "surge")
    assert not any(e.get("name") == "tether_drag" for e in res.model.effects)
    # reported: the gain-free fit's value and its sd, never the prior map's
    assert step.parameters == {"c_t": nd["gains_free"]}
    assert step.final_parameters == {"c_t": nd["gains_free"]}
    assert step.std == {"c_t": nd["gains_free_std"]}
    # the known truth: the prior map's c_t is far off (the gains' contrast), the gain-free
    # value within 2 of its standard deviations (measured 0.259 and 0.1995 for 0.1774)
    truth = known["magnitude"]
    assert nd["prior_map"] > 1.3 * truth
    assert abs(nd["gains_free"] - truth) < 2.0 * nd["gains_free_std"]
    assert nd["z"] > 1.0          # Hausman: the value moves beyond the difference's noise
    # the written model is the reported one: its window error on the fitting part is the
    # final error printed (the calibration refitted without the tether)
    train = split(log, VALIDATION_FRACTION, key="validation")[0]
    assert r.final_error == pytest.approx(
        window_errors(train, res.model, [0], window=res.window_s)["surge"], rel=1e-9)
    # and the text says so, and what to do
    text = text_summary(res)
    assert "c_t not determined by one DOF" in text and ADVICE in text
    assert "[removed" not in text
    assert res.to_dict()["per_dof"]["surge"]["steps"][0]["not_determined"]["advice"] == ADVICE


@pytest.mark.slow
def test_the_gain_test_of_a_tether_with_the_right_map_does_not_move(surge):
    """On the same log against a prior that holds the truth's map, the tether is found by
    the test with that map (no retest, nothing marked, written) and its c_t does not move
    beyond the difference's noise when the gains are freed (Hausman's z below MIN_Z)."""
    log, _, known, wrong = surge
    prior = rov_model()
    truth_map = with_gains(prior, GAINS)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, truth_map, dof="surge", dof_gains=False)
    step = res.per_dof["surge"].steps[0]
    assert step.effect == "tether_drag" and not retested(step)
    assert step.not_determined is None and step.kept
    test = gain_dependence(step, res.fits["surge"])
    assert test["z"] < 3.0
    # closer to the truth than the wrong map's fit (measured 0.206 against 0.259, truth
    # 0.1774: what is left is not the gains')
    truth = known["magnitude"]
    off = wrong.per_dof["surge"].steps[0].not_determined["prior_map"]
    assert abs(step.final_parameters["c_t"] - truth) < 0.6 * abs(off - truth)


def test_the_benchmark_scores_a_value_not_determined_as_named_not_claimed():
    from benchmarks.diagnose_independent import summarise

    base = {"vehicle": "bluerov2_heavy", "category": "tether_drag", "mode": "dof",
            "dof": "surge", "truth": 0.2, "first": "tether_drag", "first_set": ["tether_drag"],
            "n_steps": 1, "unexplained": False, "max_gain": 0.5, "cut": 4.0,
            "t_simulate": 1.0, "t_diagnose": 1.0, "step_dofs": ["surge"],
            "step_effects": {"surge": ["tether_drag"]}}
    claimed = {**base, "seed": 1, "magnitude_error": 0.05, "magnitude_truth": 0.2}
    unclaimed = {**base, "seed": 2, "magnitude_truth": 0.2, "magnitude_not_claimed": True,
                 "not_determined": {"gains_free": 0.23, "gains_free_std": 0.01,
                                    "prior_map": 0.38, "prior_map_std": 0.15, "z": 63.0,
                                    "retested": True},
                 "gains_free_error": 0.15, "prior_map_error": 0.9}
    text = summarise([claimed, unclaimed], 0, 300.0)
    row = [line for line in text.splitlines() if line.startswith("| tether_drag | dof")][0]
    cells = [c.strip() for c in row.split("|")]
    assert cells[4] == "2/2"                          # named first: both
    assert cells[7] == "1/2 (1 not claimed)"          # magnitude: the claimed one only
    assert "no magnitude claimed: 1" in text and "of the 1 claimed: 1 within" in text
    assert "0.23 ± 0.01 (+15.0 %), prior map 0.38 (+90.0 %)" in text
    assert np.isfinite(claimed["magnitude_error"])


@pytest.mark.slow
def test_the_option_off_writes_the_prior_maps_fit_as_before(surge):
    """``not_determined=False``: the same step written from the fit with the prior's map,
    its c_t the value the rule reports as the prior map's."""
    log, prior, _, res = surge
    nd = res.per_dof["surge"].steps[0].not_determined
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        old = diagnose(log, prior, dof="surge", not_determined=False, dof_gains=False)
    step = old.per_dof["surge"].steps[0]
    assert step.effect == "tether_drag" and step.not_determined is None
    assert step.kept
    assert written_effects(old.model, "surge")["tether_drag"]["c_t"] == pytest.approx(
        nd["prior_map"], rel=1e-6)
