"""Paired tests of the held-out comparison (diagnose/heldout.py, issue 33): rolling forecast
origins, the Diebold-Mariano test for overlapping forecasts, and the verdict per cell
(win / loss / not distinguishable) instead of a bare comparison of two RMS errors."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from stripcoef.diagnose.heldout import (diebold_mariano, hold_last_velocity_errors,
                                        overlap_steps, paired_verdicts, rolling_segments,
                                        segment_losses, segments, zero_velocity_errors)
from stripcoef.errors import ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model


def test_rolling_segments_are_whole_and_restart_every_step():
    t = np.arange(0.0, 90.0 + 1e-9, 0.05)                # a 90-s held-out part at 20 Hz
    bounds = rolling_segments(t, 10.0, 2.0)
    assert len(bounds) == 41 and len(segments(t, 10.0)) == 9
    assert all(b - a == 200 for a, b in bounds)          # 10 s each, none cut at the end
    assert [a for a, _ in bounds][:3] == [0, 40, 80]
    assert bounds[-1][1] <= t.size
    assert overlap_steps(10.0, 2.0) == 5 and overlap_steps(10.0, 10.0) == 1
    # a step of one horizon: the consecutive segments (the whole ones)
    assert rolling_segments(t, 10.0, 10.0) == [(a, a + 200) for a in range(0, 1800, 200)]


def test_diebold_mariano_without_overlap_is_the_one_step_statistic():
    rng = np.random.default_rng(5)
    a, b = rng.normal(1.0, 0.3, 30), rng.normal(1.2, 0.3, 30)
    got = diebold_mariano(a, b)
    d = a - b
    lags = int(np.floor(4.0 * (30 / 100.0) ** (2.0 / 9.0)))
    c = d - d.mean()
    var = c @ c / 30 + sum(2 * (1 - k / (lags + 1)) * (c[k:] @ c[:-k]) / 30
                           for k in range(1, lags + 1))
    assert got["statistic"] == pytest.approx(d.mean() / math.sqrt(var / 30)
                                             * math.sqrt(29 / 30), rel=1e-12)
    assert got["lags"] == lags and got["segments"] == 30


def test_overlapping_diebold_mariano_keeps_its_size():
    """Under equal accuracy, losses of forecasts whose windows overlap (an MA(h-1)
    differential, h = 5, 41 segments) reject at about the nominal 5 % (8 % measured,
    the small-sample excess Harvey et al. 1997 report); the one-step statistic, which
    ignores the overlap, rejects far more often (seeded)."""
    rng = np.random.default_rng(11)
    h, n, reps = 5, 41, 1000
    rejected = {"overlap": 0, "one-step": 0}
    for _ in range(reps):
        e = rng.normal(size=n + h - 1)
        d = np.convolve(e, np.ones(h), "valid")          # MA(4), mean zero
        if diebold_mariano(d, np.zeros(n), overlap=h)["p_value"] < 0.05:
            rejected["overlap"] += 1
        if diebold_mariano(d, np.zeros(n))["p_value"] < 0.05:
            rejected["one-step"] += 1
    assert rejected["overlap"] / reps < 0.10
    assert rejected["one-step"] / reps > rejected["overlap"] / reps + 0.03


def test_paired_verdicts_win_loss_and_not_distinguishable():
    rng = np.random.default_rng(2)
    s = 40
    base = rng.gamma(4.0, 0.25, (s, 3))
    losses = {"prior": base * 2.0, "hold_last_velocity": base * 1.5,
              "zero_velocity": base * 1.8,
              # DOF 0 clearly better than all; DOF 1 clearly worse than hold; DOF 2 the
              # best baseline's loss plus zero-mean noise
              "calibrated": np.column_stack([base[:, 0] * 0.5, base[:, 1] * 3.0,
                                             base[:, 2] * 1.5
                                             + rng.normal(0.0, 0.05, s)])}
    got = paired_verdicts(losses, [0, 1, 2])
    assert got["surge"]["verdict"] == "win"
    assert got["sway"]["verdict"] == "loss"
    assert got["heave"]["verdict"] == "not distinguishable"
    assert set(got["surge"]["tests"]) == {"prior", "hold_last_velocity", "zero_velocity"}
    # a candidate identical to the prior is a tie, never a loss to it
    tie = dict(losses, calibrated=losses["prior"])
    assert paired_verdicts(tie, [0], against=("prior",))["surge"]["verdict"] == \
        "not distinguishable"
    # a diverged candidate loses
    assert paired_verdicts(dict(losses, calibrated=None), [0])["surge"]["verdict"] == "loss"


@pytest.mark.slow
def test_segment_losses_of_the_trivial_predictors_pool_to_their_errors():
    model = rov_model()
    t = np.arange(0.0, 30.0, 0.2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        tau = np.zeros((t.size, 6))
        tau[:, 0] = np.where(t % 8 < 4, 20.0, -10.0)
        log = add_noise(simulate(model, t, forces=tau), np.random.default_rng(3))
        bounds = segments(t, 10.0)
        got = segment_losses(log, {"model": model}, [0, 5], bounds)
    counts = np.array([b - a for a, b in bounds], float)
    for name, ref in (("hold_last_velocity", hold_last_velocity_errors(log, [0, 5])),
                      ("zero_velocity", zero_velocity_errors(log, [0, 5]))):
        pooled = np.sqrt(counts @ got[name] / counts.sum())
        assert pooled == pytest.approx(ref, rel=1e-12)
    assert got["model"].shape == (len(bounds), 2)
    # the model that made the log (noise aside) beats zero velocity in surge
    assert np.mean(got["model"][:, 0]) < np.mean(got["zero_velocity"][:, 0])


@pytest.mark.slow
def test_diagnose_records_the_paired_tests_of_the_written_model():
    """The held-out record holds the verdicts of the written model (recomputed here from
    the model read back); the validation's per-DOF test is recorded for every DOF it scored."""
    import json

    from conftest import ROOT  # noqa: F401  (the tests' package root)
    from test_diagnose_closedloop import make_log

    from stripcoef.conventions import DOF
    from stripcoef.diagnose.heldout import paired_record, split
    from stripcoef.diagnose.pipeline import diagnose
    from stripcoef.model import HydroModel

    log, prior, _ = make_log(9, duration=150.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        res = diagnose(log, prior, dof="all", effects=["tether_drag"], holdout=0.3)
        written = HydroModel.from_dict(json.loads(json.dumps(res.model.to_dict())))
        test_log = split(log, 0.3)[1]
        dofs = [DOF.index(d) for d in res.holdout["errors"]]
        again = paired_record(test_log, {"prior": prior, "calibrated": written}, dofs)
    got = res.holdout["paired_tests"]
    assert got["segments"] == len(rolling_segments(np.asarray(test_log["t"]))) > \
        len(segments(np.asarray(test_log["t"])))
    for d in res.holdout["errors"]:
        assert got[d]["verdict"] == again[d]["verdict"] in ("win", "loss",
                                                           "not distinguishable")
        assert got[d]["statistic"] == pytest.approx(again[d]["statistic"], rel=1e-6)
    per = res.validation["per_dof_test"]
    assert all(per[d]["segments"] >= 2 for d in res.validation["prior"])
