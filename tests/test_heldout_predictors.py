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


def _steady_log(u0, seed=1, duration=15.0):
    """A log of the synthetic ROV in steady straight motion at ``u0`` [m/s]: the applied force
    the drag at u0 (an equilibrium), the states with white noise of the independent
    simulator's sensor levels."""
    from validation.synthetic import rov_model

    model = rov_model()
    t = np.arange(0.0, duration + 1e-9, 0.1)
    rng = np.random.default_rng(seed)
    cols = {"t": t}
    for c, s in (("u", 0.01), ("v", 0.01), ("w", 0.01), ("p", 0.003), ("q", 0.003),
                 ("r", 0.003), ("phi", 0.005), ("theta", 0.005), ("psi", 0.005)):
        cols[c] = (u0 if c == "u" else 0.0) + rng.normal(0.0, s, t.size)
    nu0 = np.array([u0, 0.0, 0.0, 0.0, 0.0, 0.0])
    drag = model.linear_damping @ nu0 + model.quadratic_damping @ (np.abs(nu0) * nu0)
    for k, f in enumerate("XYZKMN"):
        cols[f] = np.full(t.size, drag[k])
    return model, Log(cols)


def test_white_noise_sd_reads_the_noise_under_a_smooth_signal_in_the_library():
    """The twin experiment's noise (second differences, MAD): 0.01 of white noise on a slow
    sine is read back to 5 %; a straight line has none."""
    from stripcoef.diagnose.heldout import white_noise_sd

    t = np.arange(0.0, 300.0, 0.05)
    rng = np.random.default_rng(1)
    assert abs(white_noise_sd(0.4 * np.sin(0.2 * t) + rng.normal(0.0, 0.01, t.size))
               - 0.01) < 5e-4
    assert abs(white_noise_sd(2.0 * t + 1.0)) < 1e-9


def test_start_noise_grows_where_the_vehicle_is_unstable_under_way():
    """Issue 33: on the BlueROV2-Heavy-like logs even the simulator's own vehicle, restarted
    from the noisy logged state, lost to zero velocity in pitch and yaw. The reason is the
    vehicle, not the replay: under way, the Munk moment (Y_vdot - X_udot) u v of a vehicle
    whose sway added mass exceeds its surge one turns it away from a straight course (no
    restoring moment in yaw). The noise on the starting state, carried along the logged
    motion (noise_growth) and along the model's own (twin_spread), shows it from the log and
    the model alone: at rest the synthetic ROV's yaw stays at the noise (below 0.01 rad/s);
    at 0.5 m/s it grows more than 50-fold, past both trivial predictors, so yaw is not
    predictable over 10 s there."""
    from stripcoef.diagnose.heldout import noise_growth, predictable, twin_spread

    model, rest = _steady_log(0.0)
    _, ahead = _steady_log(0.5)
    assert model.added_mass[1, 1] > model.added_mass[0, 0]      # the Munk moment destabilises
    for spread in (noise_growth, twin_spread):
        s_rest = spread(rest, model, [0, 2, 5])
        s_ahead = spread(ahead, model, [0, 2, 5])
        assert s_rest[2] < 0.01, spread.__name__
        assert s_ahead[2] > 50.0 * s_rest[2], spread.__name__
        ok = predictable(compare(ahead, {}, [0, 2, 5]), s_ahead)
        assert ok["yaw"] is False, spread.__name__
    assert predictable(compare(ahead, {}, [0, 2, 5]), None) == \
        {"surge": True, "heave": True, "yaw": True}          # a diverged model is judged


def test_noise_growth_along_the_log_is_the_noise_free_replay_of_a_stable_vehicle():
    """At rest (a stable equilibrium) the start-state noise carried along the log decays: the
    surge spread is at most the noise put on u (0.01 m/s) and shrinks with the noise."""
    from stripcoef.diagnose.heldout import noise_growth

    model, rest = _steady_log(0.0)
    s = noise_growth(rest, model, [0])[0]
    assert 0.0 < s < 0.01
    quiet = Log({c: (rest[c] if c == "t" or c in "XYZKMN" else 0.1 * rest[c])
                 for c in rest.columns})
    assert noise_growth(quiet, model, [0])[0] < 0.2 * s


def test_predictable_compares_the_spread_with_the_better_trivial_predictor():
    errors = {"surge": {"calibrated": 0.1, "hold_last_velocity": 0.3, "zero_velocity": 0.2},
              "pitch": {"calibrated": 0.5, "hold_last_velocity": 0.15, "zero_velocity": 0.1}}
    from stripcoef.diagnose.heldout import predictable

    assert predictable(errors, [0.19, 0.09]) == {"surge": True, "pitch": True}
    assert predictable(errors, [0.21, 0.11]) == {"surge": False, "pitch": False}
    assert predictable(errors, [0.05, None]) == {"surge": True, "pitch": True}


def test_predictable_exempts_a_dof_only_where_every_model_says_so():
    """issue 33: a prior whose dynamics are wrong (its noise growth past the trivial
    predictors' errors) must not exempt a DOF the calibrated model's dynamics predict, nor a
    calibrated model exempt itself where the prior predicts the DOF."""
    from stripcoef.diagnose.heldout import predictable

    errors = {"surge": {"calibrated": 0.1, "hold_last_velocity": 0.3, "zero_velocity": 0.2},
              "roll": {"calibrated": 0.8, "hold_last_velocity": 0.26, "zero_velocity": 0.19}}
    prior, calibrated = [0.07, 0.54], [0.008, 0.045]
    assert predictable(errors, prior) == {"surge": True, "roll": False}
    assert predictable(errors, prior, calibrated) == {"surge": True, "roll": True}
    assert predictable(errors, calibrated, prior) == {"surge": True, "roll": True}
    assert predictable(errors, [0.07, 0.54], [0.3, 0.6]) == {"surge": True, "roll": False}
    assert predictable(errors, [0.25, 0.54], [0.3, None]) == {"surge": False, "roll": True}
