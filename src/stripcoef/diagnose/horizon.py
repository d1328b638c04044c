r"""The validation's prediction horizon from the log's own correlation time: a multi-step
prediction error in the place of the 10-s free simulation, for logs flown in closed loop.

The validation (:func:`stripcoef.diagnose.validate.validate_changes`) replays the logged
inputs from the logged state over segments of a horizon :math:`H` and compares the
simulated velocities with the logged ones (:mod:`stripcoef.diagnose.heldout`). A log flown
with a pilot's holds (level, heading, depth) carries commands computed from the logged
state; replayed open loop they stay fixed while the simulated state departs, so past the
time over which the logged state itself stays predictable the error measures the missing
feedback, not the model (Ljung 1999, System Identification, sec. 13.4; the
``val33``/``each33c`` traces of issue 33: the truth's own model 0.13, 0.36, 1.9, 2.7 rad/s
off in pitch rate after 1, 2, 5, 9 s on a BlueROV2-like log). The k-step-ahead prediction
error, each segment restarted from the logged state after :math:`k` samples, is the
criterion between the one-step prediction error and the free simulation (Ljung 1999, sec.
3.2, eq. 3.31, the k-step-ahead predictor; the multi-step criterion: Farina & Piroddi 2008,
Proc. 47th IEEE CDC, 'Some convergence properties of multi-step prediction error
identification criteria'), and :math:`k` is chosen here from the log, not tuned.

The horizon of DOF i is the integral time scale of its logged velocity on the part judged,

.. math:: T_i = \Delta t\,\Big(\tfrac12 + \sum_{k=1}^{K-1} \rho_i(k)\Big)
          \quad\text{[s]},

:math:`\rho_i(k) = c_k / c_0` the sample autocorrelation at lag k (:math:`c_k = N^{-1}
\sum_t (\nu_t - \bar\nu)(\nu_{t+k} - \bar\nu)`, the estimate of Box & Jenkins 1976, Time
Series Analysis, sec. 2.1), integrated by the trapezoidal rule up to its first zero crossing K (Taylor
1921, Proc. London Math. Soc. s2-20, 196-212: the integral scale
:math:`\int_0^\infty \rho\,d\tau`, the time over which a stationary signal remembers its
value; the first zero crossing as the finite record's upper limit: O'Neill, Nicolaides,
Honnery & Soria 2004, Proc. 15th Australasian Fluid Mech. Conf., sec. 3). For a DOF held
by feedback it is the loop's memory: within it the logged commands still answer a state
close to the simulated one. It is bounded below by two sample intervals (a segment needs a
predicted sample) and above by :data:`~stripcoef.diagnose.heldout.HORIZON`, the free
simulation it replaces.

The default (``validation_horizon="correlation"``) since adopt33h, with five other
validation options (:data:`~stripcoef.diagnose.settings.ADOPTED_TOGETHER`, where the
evidence is). Built with ``validation_others="each"`` and ``validation_judge="own"`` on
whole-log rows of the independent simulator: the error cut >= 3x rose 4 -> 15 of 17 (seed
29112026) and 13 -> 18 of 22 (fresh seed 1795929171), spurious steps kept 2 -> 1 and 1 -> 3 (the level hold's
feed-forward taken as a pitch thrust scale that beats zero velocity by 2 %; a heave
asymmetry): benchmarks/data/closed33d_trace.md, docs/performance.md.

Depends on: diagnose.heldout, conventions.
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import VELOCITIES

#: :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.validation_horizon`'s word for the
#: horizons of :func:`correlation_horizons`.
CORRELATION = "correlation"


def integral_time_scale(t, v) -> float:
    """The integral time scale of the series ``v`` sampled at ``t`` [s] (module docstring);
    0 for a constant series."""
    t = np.asarray(t, float)
    v = np.asarray(v, float)
    n = v.size
    # constant: judged on the values, not on their deviations from the mean, which the
    # mean's round-off (its summation order, CPU-dependent) can leave non-zero
    if n < 3 or np.ptp(v) == 0.0:
        return 0.0
    x = v - float(np.mean(v))
    dt = float(t[-1] - t[0]) / (n - 1)
    f = np.fft.rfft(x, 2 * n)
    c = np.fft.irfft(f * np.conj(f))[:n]          # N c_k, the biased estimate (N c_0 > 0)
    rho = c / c[0]
    below = np.nonzero(rho <= 0.0)[0]
    k = int(below[0]) if below.size else n
    return dt * (float(np.sum(rho[1:k])) + 0.5)


def correlation_horizons(log, dofs) -> list:
    """Per DOF of ``dofs`` (indices) the horizon of its validation segments [s]: its
    velocity's integral time scale on ``log`` (:func:`integral_time_scale`), between two
    sample intervals and :data:`~stripcoef.diagnose.heldout.HORIZON`; HORIZON for a DOF the
    log lacks."""
    from stripcoef.diagnose.heldout import HORIZON

    t = np.asarray(log["t"], float)
    dt = float(np.median(np.diff(t)))
    out = []
    for i in dofs:
        name = VELOCITIES[int(i)]
        if name not in log:
            out.append(HORIZON)
            continue
        out.append(float(min(HORIZON, max(2.0 * dt, integral_time_scale(t, log[name])))))
    return out


def per_dof(horizon, dofs) -> list:
    """``horizon`` (a number [s] or one per DOF) as one number per DOF of ``dofs``."""
    if np.ndim(horizon) == 0:
        return [float(horizon)] * len(dofs)
    out = [float(h) for h in horizon]
    if len(out) != len(dofs):
        raise ValueError(f"{len(out)} horizons for {len(dofs)} DOFs")
    return out


def dof_losses(log, model, dofs, *, horizon, logged=()):
    """Per DOF of ``dofs``: ``(losses, counts)``, the sum of squared prediction errors of
    each segment of its horizon [(m/s)^2 or (rad/s)^2] and the samples of each
    (:func:`stripcoef.diagnose.heldout.segment_squared_errors`, simulated with ``logged``
    as there); None when a simulation diverges. ``horizon``: one number [s] or one per DOF
    (:func:`per_dof`); the DOFs sharing a horizon are simulated together."""
    from stripcoef.diagnose import heldout

    hs = per_dof(horizon, dofs)
    out = [None] * len(dofs)
    for h in sorted(set(hs)):
        idx = [k for k, x in enumerate(hs) if x == h]
        got = heldout.segment_squared_errors(log, model, [dofs[k] for k in idx], horizon=h,
                                             logged=logged)
        if got is None:
            return None
        for col, k in enumerate(idx):
            out[k] = (got[0][:, col], got[1])
    return out


def rms(losses) -> list:
    """The pooled RMS error of each DOF of :func:`dof_losses`' result [m/s or rad/s]."""
    return [float(np.sqrt(np.sum(sse) / np.sum(n))) for sse, n in losses]


def trivial_errors(log, dofs, horizon) -> tuple:
    """``(hold, zero)``: the hold-last-velocity and zero-velocity errors of each DOF of
    ``dofs`` on the segments of its horizon [m/s or rad/s]
    (:func:`stripcoef.diagnose.heldout.hold_last_velocity_errors`, ``zero_velocity_errors``)."""
    from stripcoef.diagnose import heldout

    hs = per_dof(horizon, dofs)
    hold, zero = [None] * len(dofs), [None] * len(dofs)
    for h in sorted(set(hs)):
        idx = [k for k, x in enumerate(hs) if x == h]
        sub = [dofs[k] for k in idx]
        for out, got in ((hold, heldout.hold_last_velocity_errors(log, sub, horizon=h)),
                         (zero, heldout.zero_velocity_errors(log, sub, horizon=h))):
            for k, e in zip(idx, got):
                out[k] = float(e)
    return hold, zero
