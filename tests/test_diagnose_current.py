"""One water current for the whole vehicle (issue 33): the earth-frame current fitted jointly
over the DOFs it acts in (stripcoef.diagnose.current), on logs of the independent simulator
(validation.independent: its own equations, integrator, pilot and seeded noise) with an
undeclared current."""

import numpy as np
import pytest

from conftest import shipped_model
from stripcoef.conventions import DOF
from stripcoef.diagnose.calibrate import calibrated_model
from stripcoef.diagnose.current import CURRENT, KEYS, share_current
from stripcoef.diagnose.select import diagnose_dof, excited_dofs
from stripcoef.diagnose.settings import DEFAULT_WINDOW, DiagnoseSettings
from stripcoef.diagnose.validate import partners
from stripcoef.effects.windows import window_data


def test_the_current_is_one_change_in_all_its_dofs():
    """The validation removes the one current from every DOF at once, and not with one
    DOF's calibration (it belongs to the water, not to that DOF's coefficients)."""
    changes = [("calibration", "surge"), ("effect", "surge", CURRENT),
               ("calibration", "sway"), ("effect", "sway", CURRENT),
               ("effect", "sway", "linear_drag")]
    out = partners({("effect", "surge", CURRENT)}, changes)
    assert ("effect", "sway", CURRENT) in out
    out = partners({("calibration", "sway")}, changes)
    assert ("effect", "sway", "linear_drag") in out
    assert ("effect", "sway", CURRENT) not in out and ("effect", "surge", CURRENT) not in out
    # a one-DOF diagnosis's current is that DOF's: it goes with its calibration
    alone = [("calibration", "surge"), ("effect", "surge", CURRENT)]
    assert partners({("calibration", "surge")}, alone) == set(alone)


def _surge_and_sway(log, prior):
    """Surge and sway diagnosed on the same windows (the whole-log path of
    diagnose.pipeline.run for those two DOFs, without its validation), then the shared
    current: (per before, per after, fits after)."""
    data = window_data(log, prior, window=DEFAULT_WINDOW)
    excited = excited_dofs(data)
    cross = [j for j in excited if j not in (0, 1)]
    per, fits = {}, {}
    for i in (0, 1):
        per[DOF[i]], fits[DOF[i]] = diagnose_dof(data, i, DiagnoseSettings(),
                                                 excited=excited, cross=cross)
    after, fits_after = share_current(per, fits)
    return per, after, fits_after


def _written_currents(model) -> dict:
    return {e["dof"]: np.array([e["parameters"][k] for k in KEYS])
            for e in model.effects if e["name"] == CURRENT}


@pytest.mark.slow
def test_the_current_acts_in_all_six_dofs_as_one_law():
    """One current of the water: the force law of a ``dof: all`` entry is the six per-DOF
    laws stacked (the Munk moments of C_A(nu_r) nu_r included), and the window force of
    each DOF (vectorised, Current.offset) is the window mean of its law."""
    from conftest import synthetic
    from stripcoef.effects.base import Effect
    from stripcoef.effects.laws import get_effect

    log, prior, _ = synthetic("current", 11)
    eff = get_effect(CURRENT)
    params = {"current_north": 0.15, "current_east": -0.08}
    data = window_data(log.slice(0, 400), prior, window=2.0)
    n = 37
    eta, nu = data.eta[n], data.nu[n]
    inputs = {"model": prior, "nu_r": nu}
    whole = eff.force_law(params, None)(data.t[n], eta, nu, inputs)
    each = np.array([eff.force_law(params, i)(data.t[n], eta, nu, inputs)[i] for i in range(6)])
    assert np.allclose(whole, each, rtol=1e-12, atol=1e-12)
    assert np.any(np.abs(whole[3:]) > 1e-6)          # the water turns the vehicle too
    for i in (0, 5):
        fast = eff.window_force(data, params, i)
        slow = Effect.window_force(eff, data, params, i)
        # M_A nu_c_dot: its window mean by the end-point difference of M_A nu_c (offset)
        # against the trapezoidal mean of the sampled -S(omega) R^T V_c (the law): the same
        # integral to the quadrature's error (0.15 % of the force on this log)
        assert np.max(np.abs(fast - slow)) <= 5e-3 * np.max(np.abs(slow))


#: The truths' seed of the two property tests below (fixed: CI must not fail by chance)
FIXED_SEED = 100


@pytest.mark.slow
def test_one_current_within_its_band_of_the_truth_in_both_dofs():
    """A property, on a fixed seed (a fresh one per run fails by chance at the band's own 1 %
    and more, the truth's other coefficients perturbed by +-25 %): a BlueROV2-Heavy-like log
    with a current of 0.1-0.25 m/s. Every DOF that names the current names the same one,
    the model writes that one value once (``dof: all``), and the truth lies within its
    reported 99 % band (the Mahalanobis distance under chi-squared with 2 degrees of freedom,
    9.21), its speed within 3 standard deviations."""
    from validation.independent import generate

    seed = FIXED_SEED
    prior = shipped_model("bluerov2_heavy.yaml")
    log, truth = generate(prior.to_dict(), CURRENT, seed, duration=120.0)
    _, per, fits = _surge_and_sway(log, prior)
    steps = {d: next((s for s in r.steps if s.effect == CURRENT), None) for d, r in per.items()}
    assert all(s is not None for s in steps.values()), f"seed {seed}: {steps}"
    record = dict(steps["surge"].comparison["shared_current"])
    assert record["dofs"] == ["surge", "sway"]
    assert record["joint_test"]["dof"] == 2        # the two components counted once
    value = np.array([record[k] for k in KEYS])
    for s in steps.values():
        assert np.allclose([s.final_parameters[k] for k in KEYS], value, rtol=0, atol=1e-12)
    written = _written_currents(calibrated_model(prior, per, fits))
    assert set(written) == {"all"}                   # one current, acting in every DOF
    assert np.allclose(written["all"], value, rtol=0, atol=1e-12)
    err = value - np.asarray(truth.current[:2])
    cov = np.array(record["covariance"])
    d2 = float(err @ np.linalg.solve(cov, err))
    assert d2 <= 9.21, f"seed {seed}: {value} against {truth.current[:2]}, d2 {d2:.3g}"
    assert abs(record["speed"] - truth.strength) <= 3 * record["speed_std"], f"seed {seed}"


@pytest.mark.slow
def test_a_clean_log_gets_no_shared_current():
    """A clean BlueROV2-Heavy-like log (a fixed seed: a fresh one per run would fail at the
    test's false-positive rate): no current in either DOF after the shared fit."""
    from validation.independent import generate

    seed = FIXED_SEED
    prior = shipped_model("bluerov2_heavy.yaml")
    log, _ = generate(prior.to_dict(), None, seed, duration=120.0)
    _, per, fits = _surge_and_sway(log, prior)
    named = {d: [s.effect for s in r.steps] for d, r in per.items()}
    assert not any(CURRENT in e for e in named.values()), f"seed {seed}: {named}"
    assert not _written_currents(calibrated_model(prior, per, fits))


@pytest.mark.slow
def test_a_current_the_dofs_do_not_support_together_is_removed_from_all(monkeypatch):
    """When the joint likelihood ratio does not reject "no current" (here forced: a level
    no p-value is under), the current leaves every DOF that selected it; each DOF's
    candidates say why, and the model writes none."""
    from stripcoef.diagnose import current
    from validation.independent import generate

    prior = shipped_model("bluerov2_heavy.yaml")
    log, _ = generate(prior.to_dict(), CURRENT, 4242, duration=120.0)
    monkeypatch.setattr(current, "ALPHA", -1.0)
    before, per, fits = _surge_and_sway(log, prior)
    assert all(any(s.effect == CURRENT for s in r.steps) for r in before.values())
    for d, r in per.items():
        assert not any(s.effect == CURRENT for s in r.steps)
        assert not any(e.name == CURRENT for e, _ in fits[d].config.terms)
        why = [c for c in r.candidates if "shared_current" in c]
        assert why and "not supported" in why[0]["rejected_because"][0]
    assert not _written_currents(calibrated_model(prior, per, fits))
