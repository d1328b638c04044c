"""The thrusters' gains fitted again beside a water current the DOFs found
(``stripcoef.diagnose.regains``, option ``gains_beside_current``; issue 33)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from _gains import contrast_error
from conftest import shipped_model
from stripcoef.diagnose.gains import fit_thruster_gains
from stripcoef.diagnose.regains import (current_kept, found_current, with_found_current,
                                        withdrawn)
from stripcoef.diagnose.select import select_dofs
from stripcoef.effects.laws import effect_window_forces
from stripcoef.effects.windows import window_data


def _per(*steps):
    return {"surge": SimpleNamespace(steps=tuple(steps))}


def _step(effect, parameters, final=None):
    return SimpleNamespace(effect=effect, parameters=parameters, final_parameters=final,
                           not_determined=False)


def test_the_gains_fitted_beside_the_current_stand_or_fall_with_it():
    """Mode "joint": the gains fitted beside the current are its fitted partner, written
    only while some DOF keeps the current (current_kept); withdrawn, the first pass's
    record says why."""
    from stripcoef.diagnose.gains import ThrusterGains

    vc = {"current_north": 0.1, "current_east": 0.0}
    per = {"surge": SimpleNamespace(steps=(_step("current", vc),)),
           "sway": SimpleNamespace(steps=(_step("current", vc),))}
    assert current_kept(per, set())
    assert current_kept(per, {("effect", "surge", "current")})
    assert not current_kept(per, {("effect", "surge", "current"),
                                  ("effect", "sway", "current")})
    assert not current_kept(_per(_step("buoyancy_offset", {"b": 0.3})), set())
    g = ThrusterGains(names=("a", "b"), gains=(1.1, 0.9), std=(0.01, 0.01), prior_sd=0.05,
                      combinations=(), test={}, noise={}, dofs=("surge",), applied=True,
                      reason="significant")
    first = ThrusterGains(names=("a", "b"), gains=(1.05, 0.95), std=(0.01, 0.01),
                          prior_sd=0.05, combinations=(), test={}, noise={},
                          dofs=("surge",), applied=True, reason="significant")
    back = withdrawn(g, first)
    assert back.gains == first.gains and back.applied
    assert "withdrawn" in back.reason and "1.1" in back.reason
    assert withdrawn(g, None) is None


def test_the_current_found_is_the_shared_one_and_none_without_one():
    vc = {"current_north": 0.12, "current_east": -0.05}
    per = _per(_step("buoyancy_offset", {"b": 0.3}),
               _step("current", {"current_north": 0.2, "current_east": 0.0}, final=vc))
    assert found_current(per) == vc          # the value refitted with every other step
    assert found_current(_per(_step("buoyancy_offset", {"b": 0.3}))) is None
    prior = shipped_model("bluerov2_heavy.yaml")
    assert with_found_current(prior, _per()) is None
    water = with_found_current(prior, per)
    assert water.effects[-1] == {"name": "current", "dof": "all", "parameters": vc}
    assert len(water.effects) == len(prior.effects) + 1



@pytest.mark.slow
def test_gains_fitted_beside_the_current_lose_the_omitted_variable_bias():
    """A seeded truth with a 0.18 m/s current (the real-style current log's draw, seed 9):
    the gains fitted on the prior's residual take part of the current's force (omitted-
    variable bias, Greene 2012 sec. 4.3.2); fitted on the residual of the prior with the
    truth's current they are closer to the truth's contrasts."""
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    log, truth = generate(prior.to_dict(), "current", 9, duration=150.0, rate=20.0)
    data = window_data(log, prior, window=4.0)
    excited, _ = select_dofs(data)
    without = fit_thruster_gains(data, excited, excited=excited)
    water = prior.with_effects({"name": "current", "dof": "all", "parameters": {
        "current_north": float(truth.current[0]), "current_east": float(truth.current[1])}})
    data_c = window_data(log, water, window=4.0)
    data_c.e0 = data_c.e0 - effect_window_forces(data_c, water)
    beside = fit_thruster_gains(data_c, excited, excited=excited)
    e_without = contrast_error(without, truth, prior, data.alloc)
    e_beside = contrast_error(beside, truth, prior, data.alloc)
    assert e_beside < 0.5 * e_without, (e_without, e_beside)


@pytest.mark.slow
def test_gains_fitted_with_the_current_free_beside_them_find_both():
    """The same seeded truth: with the current's two columns free in the gains' joint fit
    (``shared``, linearised about the value given, here none at all: the first fit's
    situation), the gains' contrasts are as close to the truth's as beside the truth's own
    current, and the linearised current is the truth's within 10 % (Gauss-Newton from 0;
    the least-squares estimate of an omitted regressor removes its bias, Greene 2012
    sec. 4.3.2)."""
    from stripcoef.diagnose.regains import current_columns
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    log, truth = generate(prior.to_dict(), "current", 9, duration=150.0, rate=20.0)
    zero = {"current_north": 0.0, "current_east": 0.0}
    water = prior.with_effects({"name": "current", "dof": "all", "parameters": zero})
    data = window_data(log, water, window=4.0)
    excited, _ = select_dofs(data)
    without = fit_thruster_gains(data, excited, excited=excited)
    joint = fit_thruster_gains(data, excited, excited=excited,
                               shared=(("current_north", "current_east"),
                                       current_columns(data, zero, excited)))
    assert joint.significant
    e_without = contrast_error(without, truth, prior, data.alloc)
    e_joint = contrast_error(joint, truth, prior, data.alloc)
    assert e_joint < 0.5 * e_without, (e_without, e_joint)
    vc = np.array([joint.calibration["shared.current_north"],
                   joint.calibration["shared.current_east"]])
    want = np.asarray(truth.current[:2], float)
    assert np.linalg.norm(vc - want) < 0.1 * np.linalg.norm(want), (vc, want)


def test_a_bad_mode_is_a_one_line_input_error():
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.errors import InputError
    with pytest.raises(InputError, match="gains_beside_current"):
        diagnose(None, None, time_limit=1.0, gains_beside_current="sometimes")


def test_the_long_run_variance_of_white_noise_is_its_variance_and_grows_with_correlation():
    """Newey & West 1987 with the lag of 1994 (heldout.long_run_variance, the Vuong test's
    variance): for white noise about its variance; for a series of repeated values
    (positively correlated) larger."""
    from stripcoef.diagnose.heldout import long_run_variance as _long_run_variance

    rng = np.random.default_rng(3)
    e = rng.normal(0.0, 2.0, 4000)
    assert _long_run_variance(e) == pytest.approx(4.0, rel=0.1)
    assert _long_run_variance(np.repeat(e[:1000], 4)) > 2.0 * _long_run_variance(e)


def test_a_current_whose_columns_a_gain_can_imitate_is_not_identified_apart():
    """The current's variance inflation beside the contrasts (regains._vif, Rothenberg
    1971): columns a gain contrast reproduces (a log that does not turn) give an infinite
    or large VIF, columns orthogonal to it 1."""
    from stripcoef.diagnose.regains import MAX_VIF, _vif

    rng = np.random.default_rng(5)
    n = 200
    cal = rng.normal(size=(n, 2))
    gain = rng.normal(size=(n, 1))
    cur = np.column_stack([rng.normal(size=n), rng.normal(size=n)])

    def lam(current):
        h = np.column_stack([cal, current, gain])
        return h.T @ h

    both = np.column_stack([cal, gain])
    orth = cur - both @ np.linalg.lstsq(both, cur, rcond=None)[0]
    assert _vif(lam(orth), 4, [2, 3]) == pytest.approx(1.0, abs=1e-9)
    alike = np.column_stack([gain[:, 0] + 0.01 * cur[:, 0], cur[:, 1]])
    assert _vif(lam(alike), 4, [2, 3]) > MAX_VIF


@pytest.mark.slow
def test_the_log_that_turns_tells_a_current_from_the_gains():
    """Mode "test" (regains.explain, Vuong 1989): on the seeded 150-s truth with a 0.18 m/s
    current (seed 9; its heading turns through several revolutions) the current is
    identified apart from the gains' contrasts (VIF <= MAX_VIF) and chosen over the gains
    fitted without it, with a refitted current within 15 % of the truth's, and the gains
    the truth also has (its thrusters at 0.75-1.25 of their maps) found beside it (the
    nested step, Schwarz 1978); on a clean truth
    (the same seed, thrusters at 0.75-1.25 of their maps, no current) a current of the same
    size is not chosen over the gains."""
    from stripcoef.diagnose.regains import MAX_VIF, explain
    from stripcoef.diagnose.settings import DiagnoseSettings
    from stripcoef.effects.windows import window_data
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    settings = DiagnoseSettings(window=4.0)
    for effect, want in (("current", "current"), (None, "gains")):
        log, truth = generate(prior.to_dict(), effect, 9, duration=150.0, rate=20.0)
        data = window_data(log, prior, window=4.0)
        excited, _ = select_dofs(data)
        gains = fit_thruster_gains(data, excited, settings, excited=excited)
        vc = ({"current_north": 0.12, "current_east": -0.14} if effect is None else
              {"current_north": float(truth.current[0]),
               "current_east": float(truth.current[1])})
        water = prior.with_effects({"name": "current", "dof": "all", "parameters": vc})
        out = explain(gains, water, data, log, excited, excited, settings)
        assert out["vif"] <= MAX_VIF, out["text"]
        if want == "current":       # the truth's thrusters are off their maps too
            assert out["choice"] == "current and gains", out["text"]
            got = np.array([out["current_north"], out["current_east"]])
            ref = np.asarray(truth.current[:2], float)
            assert np.linalg.norm(got - ref) < 0.15 * np.linalg.norm(ref), (got, ref)
        else:
            assert out["choice"] != "current", out["text"]
