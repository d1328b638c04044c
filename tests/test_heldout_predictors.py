"""The trivial predictors of the held-out table (issue 33): hold-last-velocity and zero
velocity, with exact errors on logs whose velocities are known in closed form."""

import numpy as np

from stripcoef.diagnose.heldout import (TRIVIAL_PREDICTORS, compare, segments,
                                        zero_velocity_errors)
from stripcoef.diagnose.report import text_summary
from stripcoef.logfile import Log


def test_zero_velocity_error_is_the_rms_velocity():
    t = np.arange(0.0, 30.0, 0.1)
    log = Log({"t": t, "u": np.full(t.size, 0.3), "v": np.sin(t)})
    e = zero_velocity_errors(log, [0, 1, 5], horizon=10.0)
    idx = np.concatenate([np.arange(a, b) for a, b in segments(t, 10.0)])
    np.testing.assert_allclose(e[0], 0.3, rtol=1e-12)
    np.testing.assert_allclose(e[1], np.sqrt(np.mean(np.sin(t[idx]) ** 2)), rtol=1e-12)
    assert e[2] == 0.0                                       # r is not in the log: 0


def test_compare_lists_every_trivial_predictor():
    t = np.arange(0.0, 25.0, 0.1)
    log = Log({"t": t, "u": 0.2 + 0.01 * t})
    out = compare(log, {}, [0], horizon=10.0)
    assert set(out["surge"]) == set(TRIVIAL_PREDICTORS)
    # u > 0.2 everywhere: holding the first value beats predicting zero
    assert out["surge"]["hold_last_velocity"] < out["surge"]["zero_velocity"]


def test_text_summary_prints_the_zero_velocity_column():
    hold = {"held_out_s": [70.0, 100.0], "horizon_s": 10.0,
            "errors": {"surge": {"prior": 0.05, "calibrated": 0.01,
                                 "hold_last_velocity": 0.03, "zero_velocity": 0.2468}}}
    text = text_summary({"holdout": hold, "per_dof": {}, "log": "x.csv", "vehicle": "v.yaml",
                         "metric": "velocity", "units": "m/s"})
    assert "zero velocity" in text and "0.2468" in text


def test_a_lag_restarted_mid_log_carries_the_commands_before_it():
    """A free-simulation segment that starts mid-log starts its thruster lag from the logged
    commands before it (the lag's state is the first-order filter of those commands;
    Fossen 2011 sec. 9.3), not in equilibrium with its own first command: on a log that
    ``simulate`` wrote with a 0.8-s lag and a command step just before the segment's start,
    the segment reproduces the logged velocities to the integrators' tolerance."""
    import warnings

    from stripcoef.diagnose.freesim import batch_free_velocities
    from stripcoef.logfile import log_inputs
    from stripcoef.simulate import simulate
    from validation.synthetic import rov_model

    model = rov_model().with_effects({"name": "thruster_lag", "dof": "all",
                                      "parameters": {"time_constant": 0.8}})
    t = np.arange(0.0, 12.0 + 1e-9, 0.1)
    step = np.where(t < 5.8, 60.0, -80.0)            # the step 0.2 s before the restart at 6 s
    cmds = {"port": step, "starboard": 0.5 * step, "vertical": np.zeros(t.size),
            "lateral": np.zeros(t.size)}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        log = simulate(model, t, commands=cmds)
    k = int(np.searchsorted(t, 6.0 - 1e-9))
    runs = batch_free_velocities(model, log, [(0, k), (k, t.size)], log_inputs(log, model),
                                 tolerances=(1e-8, 1e-10))
    logged = np.column_stack([log[c] for c in ("u", "v", "w", "p", "q", "r")])
    np.testing.assert_allclose(runs[1], logged[k:], atol=2e-5)
