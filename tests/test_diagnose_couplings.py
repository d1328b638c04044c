"""Issue 33 (drag33c): a moment DOF's quadratic drag couplings as calibration columns
(:mod:`stripcoef.diagnose.couplings`, option ``drag_couplings``).

The prior builds :math:`D_Q[i, j]` (i roll, pitch, yaw; j surge, sway, heave) as the moment of
DOF j's strip forces (assembly/damping.py; Fossen 2011 sec. 6.4.3). On the independent
simulator's BlueROV2-like log 29113031 (linear_drag, seed 29112026's issue-size run) the
truth's D_Q[roll, sway] is -3.835 against the file's -3.239, and the whole-log roll
calibration, without a column for it, named a roll thrust scale 0.871
(benchmarks/data/roll33b_trace.md). The logs are generated from seeded known truths.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest

from conftest import shipped_model

ROLL, SWAY = 3, 1


@lru_cache(maxsize=None)
def _log(effect: str, seed: int, duration: float):
    """``(prior, log, truth)``: the shipped BlueROV2 Heavy and a log of the independent
    simulator (seeded truth and noise)."""
    from validation.independent import generate
    prior = shipped_model("bluerov2_heavy.yaml")
    log, truth = generate(prior.to_dict(), effect, seed, duration=duration)
    return prior, log, truth


def test_bounds_keep_the_coupling_sign_within_its_band():
    from stripcoef.diagnose.couplings import coupling_bounds
    from stripcoef.diagnose.priors import ADDED_MASS_BAND_Z
    for prior in (-3.239, 0.598):
        lo, hi = coupling_bounds(prior, 0.3)
        values = sorted((prior + lo, prior + hi), key=abs)
        assert values[0] == pytest.approx(prior * math.exp(-ADDED_MASS_BAND_Z * 0.3))
        assert values[1] == pytest.approx(prior * math.exp(ADDED_MASS_BAND_Z * 0.3))
        assert lo < 0.0 < hi
        assert np.sign(prior + lo) == np.sign(prior + hi) == np.sign(prior)


def test_only_moment_dofs_hold_couplings_of_moving_translations():
    from stripcoef.diagnose.couplings import coupling_dof, coupling_keys
    prior = shipped_model("bluerov2_heavy.yaml")
    assert all(coupling_keys(prior, i, None) == [] for i in range(3))
    keys = coupling_keys(prior, ROLL, None)
    assert "D_Q_sway" in keys and coupling_dof("D_Q_sway") == SWAY
    assert coupling_keys(prior, ROLL, [0, 2]) == [k for k in keys if k != "D_Q_sway"]
    assert coupling_dof("M_sway") is None and coupling_dof("D_Q") is None


def test_the_column_is_minus_the_residuals_derivative():
    """The window column of ``D_Q_sway`` in roll is minus the derivative of the prior's
    roll window residual with respect to D_Q[roll, sway] (the residual is linear in it)."""
    from dataclasses import replace

    from stripcoef.effects.windows import coefficient_column, prior_residual, window_data
    prior, log, _ = _log("linear_drag", 29113031, 30.0)
    data = window_data(log, prior, window=1.0)
    dq = np.array(prior.quadratic_damping, float)
    dq[ROLL, SWAY] += 0.5
    moved = window_data(log, replace(prior, quadratic_damping=dq), window=1.0)
    derivative = (prior_residual(moved, moved.model)[:, ROLL]
                  - prior_residual(data, data.model)[:, ROLL]) / 0.5
    col = coefficient_column(data, ROLL, "D_Q_sway")
    assert np.max(np.abs(col)) > 0.0
    np.testing.assert_allclose(col, -derivative, rtol=1e-7, atol=1e-9 * np.max(np.abs(col)))


def test_the_option_adds_the_columns_with_the_translations_band():
    from stripcoef.diagnose.fit import _calibration, _Config
    from stripcoef.diagnose.settings import DiagnoseSettings
    from stripcoef.effects.windows import window_data
    prior, log, _ = _log("linear_drag", 29113031, 30.0)
    data = window_data(log, prior, window=1.0)
    off = _calibration(data, ROLL, DiagnoseSettings())
    on_settings = DiagnoseSettings(drag_couplings=True)
    on = _calibration(data, ROLL, on_settings)
    assert not any(n.startswith("D_Q_") for n in off.names)
    assert "D_Q_sway" in on.names
    k = on.names.index("D_Q_sway")
    band = on_settings.band_table()["translational"]["D_Q"]
    assert on.band["D_Q_sway"] == band
    assert on.sd[k] == pytest.approx(band * abs(prior.quadratic_damping[ROLL, SWAY]))
    cfg = _Config(data, ROLL, on, [], settings=on_settings)
    assert cfg.cal_lower[k] < 0.0 < cfg.cal_upper[k]
    # a translation's calibration is the same with the option on
    assert _calibration(data, SWAY, on_settings).names == _calibration(data, SWAY).names


@pytest.mark.slow
def test_the_sway_drags_roll_moment_is_calibrated_and_written():
    """29113031 whole-log with the option: the roll thrust scale of roll33b is not named,
    the coupling is calibrated within 10 % of the truth's (-4.06 against -3.835, the file's
    -3.239), and the value reported is the one written."""
    import warnings

    from stripcoef.diagnose.pipeline import diagnose
    prior, log, truth = _log("linear_drag", 29113031, 300.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", time_limit=float("inf"), drag_couplings=True)
    roll = res.per_dof["roll"]
    assert [s.effect for s in roll.steps] == []
    written = roll.calibration.written["D_Q_sway"]
    assert written == pytest.approx(float(res.model.quadratic_damping[ROLL, SWAY]), rel=1e-12)
    assert written == pytest.approx(float(truth.d_q[ROLL, SWAY]), rel=0.10)
    assert abs(written - truth.d_q[ROLL, SWAY]) < abs(prior.quadratic_damping[ROLL, SWAY]
                                                     - truth.d_q[ROLL, SWAY])
