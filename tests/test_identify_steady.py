"""Steady-state regression (Indiveri 1998): ROMEO heave reproduction, yaw model comparison, segmenter."""

import numpy as np
import pytest

from stripcoef.errors import InputError
from validation.experiments import ROMEO_TRUTH, romeo_experiment, romeo_weights
from stripcoef.identify.steady import (SteadyPoints, compare_models, fit_steady, predicted_force,
                                       steady_points)
from stripcoef.logfile import Log


def _five(rep):
    return [romeo_experiment(i, seed=1000 * rep + i) for i in range(1, 6)]


def test_romeo_weights_are_one_lead_apart_and_exp3_neutral():
    w = romeo_weights()
    assert w[2] == 0.0 and w[0] < w[1] < 0 < w[3] < w[4]
    np.testing.assert_allclose(np.diff(w), 0.25 * 9.81 * (1 - 1025 / 11340))


def test_standard_model_buoyancy_is_biased_positive_in_all_five():
    """The chapter (Fig. 4.12): standard-model W > 0 in all 5 tests, while truth is -,-,0,+,+.

    Rate tested: all five positive in at least 19 of 20 repetitions of the five experiments.
    """
    ok = 0
    for rep in range(20):
        ws = [fit_steady(p, "standard").value("W") for p, _ in _five(rep)]
        ok += all(w > 0 for w in ws)
    assert ok >= 19


def test_eta_model_recovers_truth_within_error_bars():
    """|estimate - truth| <= 2 sigma for >= 85 % of 100 experiments, for each parameter."""
    hits = {k: 0 for k in ("k_w", "k_ww", "W", "eta")}
    for rep in range(20):
        for pts, w_true in _five(rep):
            fit = fit_steady(pts, "eta")
            truth = dict(ROMEO_TRUTH, W=w_true)
            for k in hits:
                hits[k] += abs(fit.value(k) - truth[k]) <= 2 * fit.std[k]
    assert min(hits.values()) >= 85, hits


def test_standard_model_residuals_are_3_to_10_times_larger_and_drag_scattered():
    ratios, k_std, k_eta = [], [], []
    for pts, _ in _five(0) + _five(1):
        s, e = fit_steady(pts, "standard"), fit_steady(pts, "eta")
        ratios.append(np.sqrt(s.sigma2 / e.sigma2))
        k_std.append(s.value("k_w"))
        k_eta.append(e.value("k_w"))
    assert 3.0 <= np.median(ratios) <= 10.0        # the chapter: "from 3 to 10 times larger"
    assert np.ptp(k_std) > 1.5 * np.ptp(k_eta)      # standard k_w scatters more


def test_eta_md_momentum_drag_is_collinear_with_linear_drag():
    """n_h nearly constant: k_w of eta-md much less precise than in the eta model (Table I)."""
    worse = 0
    for pts, _ in _five(2):
        e, m = fit_steady(pts, "eta"), fit_steady(pts, "eta-md")
        worse += m.relative_error_percent["k_w"] > 3 * e.relative_error_percent["k_w"]
        assert "alpha" in m.parameters
    assert worse >= 4


def test_sname_derivatives_and_predicted_force():
    pts, _ = romeo_experiment(3, seed=5)
    fit = fit_steady(pts, "eta")
    assert fit.value("Z_w") == -fit.value("k_w")
    assert fit.std["Z_ww"] == pytest.approx(fit.std["k_ww"], rel=1e-8)
    exact = SteadyPoints("heave", pts.velocity, predicted_force(fit, pts))
    refit = fit_steady(exact, "eta")
    np.testing.assert_allclose(refit.theta, fit.theta, rtol=1e-8, atol=1e-9)


def _yaw_points(seed, k_r=40.0, k_rr=0.0, rmax=10.0, sigma=0.5):
    rng = np.random.default_rng(seed)
    r = np.radians(np.r_[np.linspace(2, rmax, 7), -np.linspace(2, rmax, 8)])
    tau = k_r * r + k_rr * r * np.abs(r) + rng.normal(0, sigma, r.size)
    return SteadyPoints("yaw", r, tau)


def test_comparison_recommends_lnb_for_linear_truth():
    """Truth tau = 40 r (Indiveri 1998's conclusion at <= 10 deg/s): LNB chosen in >= 80 of 100 seeds."""
    picks = [compare_models(_yaw_points(s)).recommended.model for s in range(100)]
    assert picks.count("LNB") >= 80, {m: picks.count(m) for m in set(picks)}


def test_comparison_finds_quadratic_drag_at_high_rates():
    picks = [compare_models(_yaw_points(s, k_r=10.0, k_rr=60.0, rmax=60.0, sigma=0.3))
             .recommended.model for s in range(30)]
    assert picks.count("LQNB") >= 24, {m: picks.count(m) for m in set(picks)}


def test_comparison_tables_have_every_direction():
    cmp = compare_models(_yaw_points(0))
    labels = {f.model for f in cmp.single}
    assert {"LQB positive", "LQB negative", "LNB positive", "LNB negative"} <= labels
    assert len(cmp.candidates) == 8
    aicc = [c.aicc for c in cmp.candidates]
    assert aicc == sorted(aicc)
    assert "LNB" in cmp.explanation


def test_steady_points_from_time_series_velocity_and_pose():
    """Constant-input segments with a first-order transient: mean after settle, or pose slope."""
    t = np.arange(0, 120, 0.1)
    seg = (t // 20).astype(int)
    f = np.array([10, -10, 20, -20, 30, -30.0])[seg]
    w_ss = np.array([0.1, -0.08, 0.15, -0.12, 0.2, -0.16])[seg]
    tau = t - 20 * seg
    w = w_ss + (np.r_[0, w_ss[:-1]] - w_ss) * 0 + (-w_ss) * np.exp(-tau / 1.5)
    z = np.cumsum(w) * 0.1
    log = Log({"t": t, "w": w, "z": z, "Z": f})
    pts = steady_points(log, "heave", settle=8.0)
    np.testing.assert_allclose(pts.velocity, [0.1, -0.08, 0.15, -0.12, 0.2, -0.16], atol=2e-4)
    np.testing.assert_allclose(pts.force, [10, -10, 20, -20, 30, -30])
    pose = steady_points(Log({"t": t, "z": z, "Z": f}), "heave", settle=8.0, trim=5)
    np.testing.assert_allclose(pose.velocity, pts.velocity, atol=1e-3)


def test_bad_inputs_name_the_problem():
    pts = SteadyPoints("heave", [0.1, 0.2, 0.3, 0.25, 0.15], [10, 20, 30, 25, 15])
    with pytest.raises(InputError, match="'eta'"):
        fit_steady(pts, "eta")                       # no upward-thrust points
    with pytest.raises(InputError, match="n_h"):
        fit_steady(SteadyPoints("heave", [0.1, -0.1, 0.2, -0.2, 0.3, -0.3],
                                [10, -10, 20, -20, 30, -30]), "eta-md")
    with pytest.raises(InputError, match="standard"):
        fit_steady(pts, "cubic")
    with pytest.raises(InputError, match="too few"):
        fit_steady(SteadyPoints("heave", [0.1, 0.2, -0.1], [1, 2, -1]), "standard")
    with pytest.raises(InputError, match="'Z'"):
        steady_points(Log({"w": [0.1, 0.2]}, source="x.csv"), "heave")


_DISAGREE = ("the bias b is beyond 2 sigma in the chapter's LB fit ({}) and LB has the lower "
             "AICc: the rule keeps the bias where the chapter drops it as 'unnecessary'")


@pytest.mark.parametrize("exp,sensor", [
    ("A", "kvh"), ("B", "watson"),
    pytest.param("A", "watson", marks=pytest.mark.xfail(
        strict=True, reason=_DISAGREE.format("relative error 42.8 %"))),
    pytest.param("B", "kvh", marks=pytest.mark.xfail(
        strict=True, reason=_DISAGREE.format("relative error 29.2 %")))])
def test_rule_reproduces_chapter_choice_of_lnb_on_printed_tables(exp, sensor):
    from stripcoef.identify.steady import recommend
    from validation.identification import printed_yaw_candidates
    _, rec, _ = recommend(printed_yaw_candidates(exp, sensor, separate=False))
    assert rec.label == "LNB together"


def test_printed_tables_are_consistent_and_per_direction_preferred_for_a_watson():
    """N = nu + p is the same for every model of a table; A Watson: per-direction LNB wins."""
    from stripcoef.identify.steady import recommend
    from validation.identification import printed_yaw_candidates
    for exp in "AB":
        for sensor in ("watson", "kvh"):
            together = printed_yaw_candidates(exp, sensor, separate=False)
            assert len({c.n_obs for c in together}) == 1
    ranked, rec, _ = recommend(printed_yaw_candidates("A", "watson"))
    assert rec.label == "LNB +/- separately" and ranked[0] is rec


def test_yaw_rate_from_wrapped_heading():
    """ROMEO's yaw trials turn about one full circle per torque: psi wraps at +-pi."""
    t = np.arange(0, 300, 0.1)
    seg = (t // 60).astype(int)
    rate = np.array([0.1, -0.1, 0.15, -0.15, 0.05])[seg]
    psi = np.cumsum(rate) * 0.1
    wrapped = (psi + np.pi) % (2 * np.pi) - np.pi
    pts = steady_points(Log({"t": t, "psi": wrapped, "N": 40 * rate}), "yaw", settle=1.0)
    np.testing.assert_allclose(pts.velocity, [0.1, -0.1, 0.15, -0.15, 0.05], atol=1e-3)
