r"""Free-simulation error of a model on a log, and the trivial predictor it must beat.

A model is judged where it is used: simulated forward from a logged state with the logged
inputs. The log is cut into segments of ``horizon`` seconds; each segment is re-simulated
from the logged pose and velocity at its start (an open-loop simulation of a whole log of a
directionally unstable vehicle drifts away whatever the model), and the error of DOF i is

.. math:: E_i = \sqrt{\frac{1}{N}\sum_{s}\sum_{k \in s}
          \big(\hat\nu_i(t_k \mid \nu(t_{s,0})) - \nu_i(t_k)\big)^2}
          \quad\text{[m/s or rad/s]}

The hold-last-velocity predictor :math:`\hat\nu(t_k) = \nu(t_{s,0})` on the same segments is
the baseline a model must beat to be worth simulating (issue 16: on real logs the
calibrated model beat it in only 2 of 6 DOFs). The zero-velocity predictor
:math:`\hat\nu(t_k) = 0` is the other trivial one (issue 33: on real pool logs the calibrated
model lost to it in 5 of 6 DOFs): its error is the RMS velocity itself, so a model that does
not beat it predicts the motion worse than predicting none. Held-out use: the model is fitted on one
part of the log (time-block split, :func:`split`) and these errors are measured on another.

References: Ljung, System Identification (1999), sec. 16.4 (simulation error, cross
validation on fresh data); Hyndman & Athanasopoulos, Forecasting (2021), sec. 5.2 (the
naive "last value" benchmark forecast).
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import DOF, VELOCITIES
from stripcoef.errors import InputError, StripcoefError

#: Horizon of the free simulations [s].
HORIZON = 10.0


def segments(t, horizon: float = HORIZON) -> list:
    """Index bounds ``[(a, b), ...]`` of consecutive segments of ``horizon`` seconds [s]."""
    starts = [0]
    while True:
        nxt = int(np.searchsorted(t, t[starts[-1]] + horizon))
        if nxt >= t.size - 2:
            break
        starts.append(nxt)
    bounds = starts + [t.size]
    return [(a, b) for a, b in zip(bounds[:-1], bounds[1:]) if b - a >= 2]


def split(log, fraction: float, *, key: str = "holdout"):
    """``(head, tail)``: the log cut in time so that ``tail`` holds the last ``fraction``
    of its duration (a time-block split: no sample of the tail is used for fitting)."""
    if not (0.0 < fraction < 1.0):
        raise InputError("not a fraction in (0, 1)", key=key, value=fraction,
                         expected="a number between 0 and 1, e.g. 0.3")
    t = log["t"]
    k = int(np.searchsorted(t, t[0] + (1.0 - fraction) * (t[-1] - t[0])))
    if k < 3 or t.size - k < 3:
        raise InputError("the split leaves too few samples", key=key, value=fraction,
                         expected="a fraction that leaves samples on both sides")
    head, tail = log.slice(0, k), log.slice(k, t.size)
    return head, tail


#: Integrator tolerances of the free simulations (relative, absolute): the errors compared
#: are 1e-3..1e-1 m/s, so 1e-5 relative integration error is invisible in them.
TOLERANCES = (1e-5, 1e-7)


def free_simulation_errors(log, model, dofs, *, horizon: float = HORIZON,
                           tolerances=TOLERANCES):
    """RMS free-simulation error of each DOF in ``dofs`` (list of indices) [m/s or rad/s]
    (module docstring), or None when a simulation diverges."""
    from stripcoef.diagnose.freesim import batch_free_velocities, supported
    from stripcoef.logfile import log_inputs
    from stripcoef.simulate import replay

    t = log["t"]
    try:
        inputs = log_inputs(log, model)       # the one replay rule (simulate --from-log's)
    except StripcoefError:
        return None
    err = {i: [] for i in dofs}
    bounds = segments(t, horizon)
    if supported(model, inputs):        # all segments at once (diagnose/freesim.py)
        runs = batch_free_velocities(model, log, bounds, inputs, tolerances=tolerances)
        if runs is None:
            return None
        zeros = np.zeros(t.size)
        for (a, b), nu in zip(bounds, runs):
            for i in dofs:
                err[i].append(nu[:, i] - log.get(VELOCITIES[i], zeros)[a:b])
        return [_rms(np.concatenate(err[i])) for i in dofs]
    for a, b in bounds:
        part = log.slice(a, b)
        try:
            sim = replay(model, part, inputs=inputs.window(a, b),
                         rtol=tolerances[0], atol=tolerances[1])
        except StripcoefError:
            return None
        zeros = np.zeros(b - a)
        for i in dofs:
            v = VELOCITIES[i]
            err[i].append(sim[v] - part.get(v, zeros))
    return [_rms(np.concatenate(err[i])) for i in dofs]


def hold_last_velocity_errors(log, dofs, *, horizon: float = HORIZON):
    """RMS error of the predictor nu_hat(t) = nu(t_segment_start) [m/s or rad/s]."""
    t = log["t"]
    zeros = np.zeros(t.size)
    out = []
    for i in dofs:
        v = log.get(VELOCITIES[i], zeros)
        out.append(_rms(np.concatenate([v[a:b] - v[a] for a, b in segments(t, horizon)])))
    return out


def zero_velocity_errors(log, dofs, *, horizon: float = HORIZON):
    r"""RMS error of the predictor :math:`\hat\nu(t) = 0` on the same segments as the other
    predictors [m/s or rad/s]: the RMS of the logged velocity over them (a DOF the log lacks
    is 0)."""
    t = log["t"]
    zeros = np.zeros(t.size)
    out = []
    for i in dofs:
        v = log.get(VELOCITIES[i], zeros)
        out.append(_rms(np.concatenate([v[a:b] for a, b in segments(t, horizon)])))
    return out


#: The trivial predictors every model is compared with (:func:`compare`), by name.
TRIVIAL_PREDICTORS = ("hold_last_velocity", "zero_velocity")


def compare(log, models: dict, dofs, *, horizon: float = HORIZON) -> dict:
    """Free-simulation errors of several models and of the trivial predictors
    (hold-last-velocity, zero velocity) on one log.

    Returns ``{dof_name: {model_name: error or None, ..., "hold_last_velocity": error,
    "zero_velocity": error}}`` [m/s or rad/s]."""
    rows = {name: free_simulation_errors(log, m, dofs, horizon=horizon)
            for name, m in models.items()}
    rows["hold_last_velocity"] = hold_last_velocity_errors(log, dofs, horizon=horizon)
    rows["zero_velocity"] = zero_velocity_errors(log, dofs, horizon=horizon)
    return {DOF[i]: {name: (None if r is None else float(r[k])) for name, r in rows.items()}
            for k, i in enumerate(dofs)}


def _rms(x):
    return float(np.sqrt(np.mean(np.asarray(x) ** 2))) if np.size(x) else float("nan")
