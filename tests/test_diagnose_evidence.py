"""Issue 33, false positives: a step's evidence counted on the effective number of windows
(autocorrelated residuals), Holm over the step's candidates, Bonferroni over the DOFs of a
whole-log diagnosis (stripcoef.diagnose.evidence); a seeded clean log names nothing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stripcoef.diagnose.compare import ALPHA
from stripcoef.diagnose.evidence import (effective_fraction, family_level, judge_family,
                                         step_test, supported)


def _ar1(rng, n, rho):
    x = np.empty(n)
    x[0] = rng.standard_normal() / math.sqrt(1.0 - rho ** 2)
    for i in range(1, n):
        x[i] = rho * x[i - 1] + rng.standard_normal()
    return x


def _fits(y, x):
    """The reference (a constant) and the candidate (a constant and x) fitted to y, as
    _evaluate's records (full residuals; the held-out ones are the same, unused here)."""
    e0 = y - y.mean()
    h = np.column_stack([np.ones_like(x), x])
    e1 = y - h @ np.linalg.lstsq(h, y, rcond=None)[0]
    return ({"full": {"resid": e0}, "held_out_resid": e0},
            {"full": {"resid": e1}, "held_out_resid": e1})


def test_effective_fraction_is_bretherton_eq_31_and_never_above_one():
    assert effective_fraction(0.0, 0.9) == 1.0
    assert effective_fraction(-0.5, 0.8) == 1.0        # never more windows than the log has
    assert effective_fraction(0.5, 0.8) == pytest.approx(0.6 / 1.4, rel=1e-12)
    assert 0.0 < effective_fraction(0.999, 0.999) < 2e-3


def test_on_coloured_noise_the_test_holds_its_level_where_the_iid_one_does_not():
    """An unrelated smooth regressor (AR(1), 0.9) on coloured noise (AR(1), 0.7), 60
    windows: the likelihood ratio counted on every window rejects far more often than its
    5 %; on the effective windows it stays near it (seeded Monte Carlo, 600 draws)."""
    from scipy.stats import chi2

    rng = np.random.default_rng(20261128)
    n, draws = 60, 600
    naive = corrected = 0
    for _ in range(draws):
        ref, cand = _fits(_ar1(rng, n, 0.7), _ar1(rng, n, 0.9))
        t = step_test(ref, cand, 1)
        lam = n * math.log(np.sum(ref["full"]["resid"] ** 2)
                           / np.sum(cand["full"]["resid"] ** 2))
        naive += chi2.sf(lam, 1) <= ALPHA
        corrected += t["p_value"] <= ALPHA
        assert t["effective_windows"] <= n
    assert naive / draws > 0.15
    assert corrected / draws < 0.09


def test_a_real_regressor_is_still_found_on_coloured_noise():
    rng = np.random.default_rng(7)
    x = _ar1(rng, 60, 0.9)
    ref, cand = _fits(0.8 * x + _ar1(rng, 60, 0.7), x)
    t = step_test(ref, cand, 1)
    assert t["p_value"] < 1e-3
    assert t["effective_windows"] < 60


def _trial(name, p):
    return {"effect": name, "significant": True, "rejected_because": [],
            "evidence": {"statistic": float(chi2_isf(p)), "p_value": p, "windows": 56,
                         "effective_windows": 30.0}}


def chi2_isf(p):
    from scipy.stats import chi2
    return chi2.isf(p, 1)


def test_holm_over_the_candidates_and_bonferroni_over_the_dofs():
    # ten candidates: the best at p = 0.004 passes Holm at 5 % (0.04) in one DOF ...
    trials = [_trial("a", 0.004)] + [_trial(f"x{k}", 0.5) for k in range(9)]
    judge_family(trials, n_dofs=1)
    assert trials[0]["significant"]
    assert trials[0]["evidence"]["p_adjusted"] == pytest.approx(0.04)
    assert all(not t["significant"] for t in trials[1:])
    assert "Holm-adjusted over 10 candidates" in trials[1]["rejected_because"][0]
    # ... not in a whole-log run of six DOFs, whose level is 5 % / 6
    trials = [_trial("a", 0.004)] + [_trial(f"x{k}", 0.5) for k in range(9)]
    judge_family(trials, n_dofs=6)
    assert not trials[0]["significant"]
    assert trials[0]["evidence"]["level"] == pytest.approx(family_level(6)) == ALPHA / 6
    # a candidate already rejected keeps its reasons and gets no new one
    t = {**_trial("b", 0.9), "significant": False, "rejected_because": ["z < 3"]}
    judge_family([t])
    assert t["rejected_because"] == ["z < 3"]
    # a joint pair's member, judged outside the family: Bonferroni over the step
    assert supported(_trial("c", 0.004), 10)
    assert not supported(_trial("c", 0.006), 10)
    assert not supported(_trial("c", 0.004), 10, n_dofs=6)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="issue 33, branch tether33c: with the other moving DOFs' "
                   "added masses calibrated in each DOF (stripcoef.diagnose.cross) this clean "
                   "log names a pitch buoyancy offset of 0.0017 N m (p_adjusted within the "
                   "level; the validation does not keep it) besides the heave one; the truth's "
                   "0.90 N buoyancy change at the CB (x_b = -8e-6 m, z_b = -0.01 m) makes no "
                   "such moment at level: not traced")
def test_a_seeded_clean_log_names_nothing_outside_its_background():
    """A clean VideoRay log of the independent simulator (seed 531988, 120 s; every
    coefficient family of the truth x U(0.75, 1.25), no effect), diagnosed whole-log: no
    step outside the truth's background (its buoyancy, drawn U(0.98, 1.02) x the prior's, is
    0.9 N lighter: a true buoyancy offset in heave), and none in surge, where the selection
    before this test named an added-mass error with a 1 % held-out gain (a released
    coefficient: 2.5 bands from the prior, p = 0.06 on the effective windows)."""
    from conftest import shipped_model
    from stripcoef.diagnose.pipeline import diagnose
    from validation.independent import generate

    prior = shipped_model("videoray_pro3.yaml")
    log, _ = generate(prior.to_dict(), None, 531988, duration=120.0)
    res = diagnose(log, prior, dof="all", time_limit=float("inf"))
    named = [(d, s.effect) for d, r in res.per_dof.items() for s in r.steps]
    assert set(named) <= {("heave", "buoyancy_offset")}, named
    for d, r in res.per_dof.items():
        for s in r.steps:
            ev = s.evidence
            assert ev is not None and ev["p_adjusted"] <= ev["level"], (d, s.effect, ev)
