"""The calibration's identifiability with the noise level fitted beside a free constant
(``DiagnoseSettings.noise_with_bias``, option; issue 33, spur33f): a constant force the prior
misses is not noise (Ljung 1999 sec. 9.2), so a coefficient the log determines is not kept at
the prior because of it. Seeded known truths; measured text: benchmarks/data/spur33f_trace.md.
"""
from __future__ import annotations

import types

import numpy as np
import pytest

from stripcoef.diagnose.fit import _identifiability, _sigma, sigma_beside_bias
from stripcoef.diagnose.settings import DiagnoseSettings

BIAS, NOISE = 2.0, 0.1     # [N]


def _log(n=3000, seed=5):
    """A residual = bias + white noise + 0.05 x a column, the column zero-mean."""
    rng = np.random.default_rng(seed)
    col = rng.standard_normal(n)
    y = BIAS + 0.05 * col + rng.normal(0.0, NOISE, n)
    return y, col[:, None]


def test_the_noise_level_beside_a_bias_is_the_noise():
    y, H = _log()
    assert sigma_beside_bias(y, H) == pytest.approx(NOISE, rel=0.05)
    assert _sigma(y, H) == pytest.approx(np.hypot(BIAS, NOISE), rel=0.05)


def test_a_determined_coefficient_is_calibrated_beside_a_bias():
    y, H = _log()
    data = types.SimpleNamespace(e0=np.column_stack([y] + [np.zeros_like(y)] * 5))
    # [N per unit of the column]; the log determines it to NOISE / sqrt(n) = 0.0018, or with
    # the bias counted as noise to 0.037: information ratios 2.7 and 0.14 against 0.3
    band = [0.005]
    off = _identifiability(data, 0, H, band, ["D_Q"], [0],
                           DiagnoseSettings(noise_with_bias=False))
    on = _identifiability(data, 0, H, band, ["D_Q"], [0], DiagnoseSettings(noise_with_bias=True))
    assert "D_Q" in off["kept_at_prior"]
    assert "D_Q" not in on["kept_at_prior"]
    assert on["information_ratio"]["D_Q"] == pytest.approx(
        off["information_ratio"]["D_Q"] * np.hypot(BIAS, NOISE) / NOISE, rel=0.1)
