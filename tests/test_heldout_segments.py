"""Per-segment free-simulation errors (diagnose/heldout.py): the independent units of a
paired comparison of two models on held-out data (issue 33)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from _rov_logs import square_wave_log

from stripcoef.diagnose.heldout import free_simulation_errors, segment_squared_errors
from stripcoef.errors import ModelWarning
from stripcoef.simulate import simulate
from validation.synthetic import add_noise, rov_model


def test_segment_squared_errors_pool_to_the_free_simulation_errors():
    _, log, other = square_wave_log()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        sse, counts = segment_squared_errors(log, other, [0, 5], horizon=10.0)
        pooled = free_simulation_errors(log, other, [0, 5], horizon=10.0)
    assert sse.shape == (3, 2) and counts.sum() == len(log)
    assert np.sqrt(sse.sum(axis=0) / counts.sum()) == pytest.approx(pooled, rel=1e-12)


def test_logged_dofs_follow_the_log_and_leave_the_others_to_the_model():
    """The validation's equation decoupling (``logged``, diagnose.settings.VALIDATION_OTHERS):
    a model whose yaw is wrong (N_r x 3) simulates surge and yaw off on a log of the true
    model; with yaw taken from the log its yaw error is nil (the logged velocity at every
    sample), and surge, whose own coefficients are right, is simulated as the truth does
    (within the interpolation's error); the true model with every other DOF logged
    reproduces surge (gentle inputs, 20 Hz: the light ROV's roll and pitch are fast)."""
    model = rov_model()
    t = np.arange(0.0, 25.0, 0.05)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        tau = np.zeros((t.size, 6))
        tau[:, 0] = np.where(t % 8 < 4, 4.0, -2.0)
        tau[:, 5] = np.where(t % 6 < 3, 0.1, -0.1)
        log = simulate(model, t, forces=tau)
        d = model.to_dict()
        dl = np.array(d["linear_damping"], float)
        dl[5, 5] *= 3.0
        wrong = model.__class__.from_dict({**d, "linear_damping": dl.tolist()})
        free = free_simulation_errors(log, wrong, [0, 5], horizon=10.0)
        logged = free_simulation_errors(log, wrong, [0, 5], horizon=10.0, logged=[5])
        true_free = free_simulation_errors(log, model, [0], horizon=10.0)
        true_logged = free_simulation_errors(log, model, [0], horizon=10.0,
                                             logged=[1, 2, 3, 4, 5])
    assert free[1] > 10.0 * logged[0]
    assert logged[1] < 1e-12
    assert logged[0] < 0.2 * free[0]
    # the logged velocities are linear between the samples: an error of second order in
    # the sample interval (0.006 m/s at 0.2 s, 0.0004 m/s at 0.05 s on this light ROV)
    assert true_free[0] < 1e-5 and true_logged[0] < 1e-3


def test_each_dof_alone_is_every_dof_simulated_with_the_other_five_logged():
    """``logged=EACH`` (diagnose.settings.VALIDATION_OTHERS "each", issue 33,
    benchmarks/data/val33_trace.md): each DOF's column is that DOF simulated alone with the
    five others from the log; on a log of the true model the truth's own error stays at the
    noise in both DOFs while the wrong yaw damping shows only in yaw."""
    from stripcoef.diagnose.heldout import EACH
    from stripcoef.diagnose.settings import DiagnoseSettings
    model = rov_model()
    t = np.arange(0.0, 12.0, 0.1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        tau = np.zeros((t.size, 6))
        tau[:, 0] = np.where(t % 8 < 4, 20.0, -10.0)
        tau[:, 5] = np.where(t % 6 < 3, 2.0, -2.0)
        log = add_noise(simulate(model, t, forces=tau), np.random.default_rng(5))
        d = model.to_dict()
        d["linear_damping"] = np.array(d["linear_damping"], float)
        d["linear_damping"][5, 5] *= 3.0
        wrong = model.__class__.from_dict(d)
        each, counts = segment_squared_errors(log, wrong, [0, 5], horizon=6.0, logged=EACH)
        for k, i in enumerate((0, 5)):
            alone, n = segment_squared_errors(log, wrong, [i], horizon=6.0,
                                              logged=[j for j in range(6) if j != i])
            assert each[:, k] == pytest.approx(alone[:, 0], rel=1e-12)
            assert counts == pytest.approx(n)
        truth = free_simulation_errors(log, model, [0, 5], horizon=6.0, logged=EACH)
        off = free_simulation_errors(log, wrong, [0, 5], horizon=6.0, logged=EACH)
    assert off[0] == pytest.approx(truth[0], rel=0.05)       # surge's own model is right
    assert off[1] > 2.0 * truth[1]
    settings = DiagnoseSettings(validation_others="each")
    assert settings.logged_dofs([0, 5]) == EACH and settings.logged_dofs([0]) == EACH


def test_each_validates_the_thruster_gains_by_the_joint_simulation():
    """With ``validation_others="each"`` a whole-log diagnosis judges each DOF's changes on
    that DOF alone but the thrusters' gains, the prior of every DOF's selection, by the joint
    simulation (none logged), as "logged" does: 'each' changes what the validation keeps,
    not what the selection names (each33c, benchmarks/data/each33c_trace.md)."""
    from stripcoef.diagnose.heldout import EACH
    from stripcoef.diagnose.settings import DiagnoseSettings
    each, default = DiagnoseSettings(), DiagnoseSettings(validation_others="logged")
    assert each.validation_others == EACH                 # the default since adopt33h
    assert each.gains_logged_dofs([0, 2, 5]) == [] == default.gains_logged_dofs([0, 2, 5])
    assert each.logged_dofs([0, 2, 5]) == EACH
    # one DOF: the gains (dof_gains) are judged as its changes are
    assert each.gains_logged_dofs([2]) == each.logged_dofs([2])
    assert default.gains_logged_dofs([2]) == [0, 1, 3, 4, 5]


def test_a_written_current_is_simulated_in_every_segment_from_its_logged_heading():
    """The held-out and validation segments restart from the logged pose, so a written
    current (the diagnosis's ``current`` effect, ``dof: all``, constant in NED) acts in
    each segment along that segment's own heading (Fossen 2011 sec. 10.3, eq. 10.34-10.35):
    on a noise-free log of a turning vehicle in a 0.15 m/s current (simulate's own current,
    eq. 10.1) the model with the written current replays every segment (errors at the
    integrator's tolerance), the model without it does not (issue 33, real33e)."""
    model = rov_model()
    t = np.arange(0.0, 40.0, 0.2)
    tau = np.zeros((t.size, 6))
    tau[:, 0] = np.where(t % 8 < 4, 20.0, -10.0)
    tau[:, 5] = np.where(t % 12 < 6, 3.0, -1.0)         # it turns: the heading changes
    vc = {"current_north": 0.1, "current_east": -0.11}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        log = simulate(model, t, forces=tau,
                       current=[vc["current_north"], vc["current_east"], 0.0])
        water = model.with_effects({"name": "current", "dof": "all", "parameters": vc})
        with_current = free_simulation_errors(log, water, [0, 1, 5], horizon=10.0)
        without = free_simulation_errors(log, model, [0, 1, 5], horizon=10.0)
    assert np.ptp(np.unwrap(log["psi"])) > np.pi            # the log turns
    assert max(with_current) < 1e-4, with_current
    assert max(without[:2]) > 100 * max(with_current), (without, with_current)
