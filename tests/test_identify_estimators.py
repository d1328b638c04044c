"""Linear least-squares core, tested the scipy way: known truth, seeded noise."""

import json
import math

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.identify import linear_lstsq, residual_autocorrelation, runs_test_z

TRUTH = np.array([50.0, 424.0, -3.0])


def _data(n, seed, sigma=2.0):
    rng = np.random.default_rng(seed)
    w = rng.uniform(-0.35, 0.35, n)
    H = np.column_stack([w, w * np.abs(w), -np.ones(n)])
    return H, H @ TRUTH + rng.normal(0.0, sigma, n)


def test_exact_data_recovers_truth_and_zero_cost():
    H, _ = _data(30, 0)
    fit = linear_lstsq(H, H @ TRUTH, ["k_w", "k_ww", "W"])
    np.testing.assert_allclose(fit.theta, TRUTH, rtol=1e-10)
    assert fit.cost < 1e-18
    assert fit.degrees_of_freedom == 27


def test_matches_numpy_and_textbook_covariance():
    H, y = _data(40, 1)
    fit = linear_lstsq(H, y, ["a", "b", "c"])
    ref, res, *_ = np.linalg.lstsq(H, y, rcond=None)
    np.testing.assert_allclose(fit.theta, ref, rtol=1e-9)
    assert fit.cost == pytest.approx(float(res[0]), rel=1e-9)
    cov = fit.cost / 37 * np.linalg.inv(H.T @ H)
    np.testing.assert_allclose(fit.cov, cov, rtol=1e-8)
    rel = fit.relative_error_percent
    assert rel["a"] == pytest.approx(100 * math.sqrt(cov[0, 0]) / abs(ref[0]), rel=1e-8)


def test_coverage_over_100_seeds():
    """|theta - truth| <= 2 sigma: expected 95.4 %; we require >= 88 % of 300 (3 params x 100)."""
    hits = 0
    for seed in range(100):
        H, y = _data(25, seed)
        fit = linear_lstsq(H, y, ["a", "b", "c"])
        hits += int(np.sum(np.abs(fit.theta - TRUTH) <= 2.0 * fit.estimated_std))
    assert hits >= 264, hits


def test_sigma_shrinks_as_one_over_sqrt_n():
    s = []
    for n in (50, 200, 800):
        s.append(np.mean([linear_lstsq(*_data(n, seed), ["a", "b", "c"]).estimated_std
                          for seed in range(20)], axis=0))
    ratio = s[0] / s[2]          # N grows 16x -> sigma shrinks 4x
    np.testing.assert_allclose(ratio, 4.0, rtol=0.1)


def test_wrong_model_shows_in_residuals():
    H, y = _data(200, 3, sigma=0.5)
    order = np.argsort(H[:, 0])
    H, y = H[order], y[order]
    good = linear_lstsq(H, y, ["a", "b", "c"])
    bad = linear_lstsq(H[:, [0, 2]], y, ["a", "c"])   # quadratic term missing
    assert runs_test_z(bad.residuals) < -4.0
    assert abs(runs_test_z(good.residuals)) < 3.0
    assert residual_autocorrelation(bad.residuals, 1)[1] > 0.5
    assert bad.bic > good.bic and bad.aicc > good.aicc


def test_hac_covers_correlated_noise_where_iid_does_not():
    """AR(1) noise rho=0.9: iid std is ~4x too small; Newey-West with 20 lags is honest."""
    rng = np.random.default_rng(7)
    hits_iid = hits_hac = 0
    for seed in range(100):
        rng = np.random.default_rng(seed)
        n = 400
        t = np.linspace(0, 40, n)
        x = np.sin(0.3 * t)
        e = np.zeros(n)
        for k in range(1, n):
            e[k] = 0.9 * e[k - 1] + rng.normal(0, 0.1)
        H = np.column_stack([x, np.ones(n)])
        y = H @ [2.0, 0.5] + e
        a = linear_lstsq(H, y, ["a", "b"])
        b = linear_lstsq(H, y, ["a", "b"], covariance="hac", lags=40)
        hits_iid += int(abs(a.theta[0] - 2.0) <= 2 * a.estimated_std[0])
        hits_hac += int(abs(b.theta[0] - 2.0) <= 2 * b.estimated_std[0])
    assert hits_iid < 70
    assert hits_hac >= 80


def test_derived_quantity_delta_method():
    H, y = _data(60, 4)
    fit = linear_lstsq(H, y, ["a", "b", "c"])
    fit.derive("ratio", lambda p: p["b"] / p["a"])
    a, b = fit.theta[:2]
    g = np.array([-b / a ** 2, 1 / a])
    var = g @ fit.cov[:2, :2] @ g
    assert fit.std["ratio"] == pytest.approx(math.sqrt(var), rel=1e-5)


def test_to_dict_contract_is_json():
    fit = linear_lstsq(*_data(20, 5), ["k_w", "k_ww", "W"], method="steady", model="standard",
                       dof="heave")
    d = json.loads(json.dumps(fit.to_dict()))
    for key in ("method", "model", "dof", "parameters", "std", "relative_error_percent",
                "cost", "degrees_of_freedom", "rms_error"):
        assert key in d
    assert d["degrees_of_freedom"] == 17 and set(d["parameters"]) == {"k_w", "k_ww", "W"}


def test_errors_name_the_parameter():
    H, y = _data(20, 6)
    H[:, 2] = 0.0
    with pytest.raises(InputError, match="'c'"):
        linear_lstsq(H, y, ["a", "b", "c"])
    H, y = _data(20, 6)
    H = np.column_stack([H, 2 * H[:, 0]])
    with pytest.raises(InputError, match="'d'"):
        linear_lstsq(H, y, ["a", "b", "c", "d"])
    with pytest.raises(InputError, match="too few"):
        linear_lstsq(H[:3, :3], y[:3], ["a", "b", "c"])
    with pytest.raises(InputError, match="covariance"):
        linear_lstsq(H[:, :3], y, ["a", "b", "c"], covariance="robust")
