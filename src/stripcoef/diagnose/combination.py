r"""The validation's reference forecast in a DOF the open-loop replay cannot predict: the best
linear combination of the prior's simulation and the trivial predictors (issue 33, cut33f).

Under the whole-log validation with each DOF simulated alone
(:func:`stripcoef.diagnose.validate.validate_changes`, ``logged`` ``"each"``), a DOF's own
changes stay only where its simulation has skill over a reference forecast (Murphy 1988,
1992): the best of the prior and the trivial predictors (the velocity held from the
segment's start, zero velocity). A DOF whose prior simulation is worse than a trivial
predictor is one the log's pilot holds by feedback (a level, depth or heading hold): its
logged commands answer the logged state, replayed open loop they do not, and the error is
the missing loop's (Ljung 1999, System Identification, sec. 13.4). There, a change that
scales the replayed commands down (a thrust scale below 1, an asymmetry that damps one
branch) moves the simulation toward the trivial predictors and can beat them by a little
without being a better model of the vehicle: under feedback the command is correlated with
the output's disturbances, and a gain on a held DOF's command fits the hold's action, the
direct method's bias in closed loop (Forssell & Ljung 1999, Automatica 35, 1215-1241;
Söderström & Stoica 1989, System Identification, sec. 10.2: a DOF driven by a fixed linear
feedback of its own state, without an external excitation, does not identify its input's
gain). Measured (closed33d): BlueROV2-like log 1795930174, pitch at its 1.34-s horizon,
prior 0.230 rad/s, zero velocity 0.191, the model with a pitch thrust scale 0.667 0.188.

To first order such a change is a combination of forecasts that is already available
without it: on a segment starting at :math:`\nu_0`, a scale :math:`s` on the replayed
commands gives :math:`\hat\nu \approx \nu_0 + s\,(\hat\nu^{prior} - \nu_0)`. So the reference
here is the combination of the prior and the trivial predictors with least-squares weights
on the same segments (the regression method of combining forecasts: Granger & Ramanathan
1984, J. Forecasting 3, 197-204; Bates & Granger 1969, Oper. Res. Q. 20, 451-468),

.. math:: \hat\nu^{c} = a\,\hat\nu^{prior} + b\,\nu_0, \qquad
          (a, b) = \arg\min \sum_{s}\sum_{k \in s} (\nu_k - a\,\hat\nu^{prior}_k - b\,\nu_{0,s})^2,

(zero velocity is the combination a = b = 0, hold-last-velocity a = 0, b = 1, the prior
a = 1, b = 0, so its error is never above the current reference's), and a change in the DOF
stays only if its simulation beats this: it must predict what no rescaling of the prior's
forecast toward the trivial ones predicts, a forecast-encompassing requirement (Chong &
Hendry 1986, Rev. Econ. Stud. 53, 671-690; Harvey, Leybourne & Newbold 1998, J. Business &
Economic Statistics 16, 254-259). The weights are fitted on the validation part itself, an
in-sample advantage of two parameters over some hundreds of samples. No threshold.

It applies only where the prior has no skill (its error not below the trivial predictors'):
where the open-loop replay predicts the DOF, a thrust scale is judged on its own simulation
as before, since there a scale that the combination imitates is the right model (a thrust
effectiveness in an open-loop surge).

The default (``validation_reference="combination"`` of
:class:`~stripcoef.diagnose.settings.DiagnoseSettings`) since adopt33h, with five other
validation options (:data:`~stripcoef.diagnose.settings.ADOPTED_TOGETHER`, where the
evidence is). Built with
``validation_others="each"``, ``validation_horizon="correlation"`` and
``validation_judge="own"`` on traced whole-log rows (benchmarks/data/cut33f_trace.md,
docs/performance.md): on seed 1795929171's 13 it removes the pitch scale above (spurious kept
2 -> 1 of 13; the one left, a VideoRay heave linear drag the default keeps too, is in a DOF
whose prior has skill) and one true roll thrust asymmetry (roll held; not the effect's DOF),
with no cut, named-first or magnitude changed; on the newest seed 1795938998's 14 it changes
nothing (the three options alone already keep none of the default's two spurious steps there).
Not the default because the issue-size runs (clean and dry-friction logs, every row of the
three seeds) were not run with it.

Depends on: diagnose.heldout, diagnose.horizon, diagnose.freesim, logfile, conventions.
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import VELOCITIES
from stripcoef.errors import StripcoefError

#: :attr:`~stripcoef.diagnose.settings.DiagnoseSettings.validation_reference`'s values: the
#: best of the prior and the trivial predictors (default), or their least-squares
#: combination where the prior has no skill (:func:`combination_errors`).
TRIVIAL = "trivial"
COMBINATION = "combination"
REFERENCES = (TRIVIAL, COMBINATION)


def segment_velocities(log, model, dofs, *, horizon: float, logged=()):
    """Per DOF of ``dofs``: ``(simulated, logged, start)``, the concatenated simulated and
    logged velocities over the segments of ``horizon`` [s] and each sample's segment-start
    logged velocity [m/s or rad/s] (the segments and simulation of
    :func:`stripcoef.diagnose.heldout.segment_squared_errors`, ``logged`` as there); None
    when a simulation diverges or the model is not one the batch integrator replays."""
    from stripcoef.diagnose.freesim import batch_free_velocities, supported
    from stripcoef.diagnose.heldout import EACH, TOLERANCES, segments
    from stripcoef.logfile import log_inputs

    if isinstance(logged, str) and logged == EACH:   # each DOF alone, the others logged
        out = []
        for i in dofs:
            got = segment_velocities(log, model, [i], horizon=horizon,
                                     logged=[j for j in range(6) if j != i])
            if got is None:
                return None
            out.extend(got)
        return out
    t = log["t"]
    try:
        inputs = log_inputs(log, model)
    except StripcoefError:
        return None
    if not supported(model, inputs):
        return None
    bounds = segments(t, horizon)
    runs = batch_free_velocities(model, log, bounds, inputs, tolerances=TOLERANCES,
                                 logged=logged)
    if runs is None:
        return None
    zeros = np.zeros(t.size)
    out = []
    for i in dofs:
        v = np.asarray(log.get(VELOCITIES[i], zeros), float)
        sim = np.concatenate([nu[:, i] for nu in runs])
        obs = np.concatenate([v[a:b] for a, b in bounds])
        start = np.concatenate([np.full(b - a, v[a]) for a, b in bounds])
        out.append((sim, obs, start))
    return out


def combined_rms(simulated, logged, start) -> float:
    """The RMS error of the least-squares combination ``a simulated + b start`` of
    ``logged`` (module docstring) [m/s or rad/s]."""
    x = np.column_stack([np.asarray(simulated, float), np.asarray(start, float)])
    y = np.asarray(logged, float)
    coef = np.linalg.lstsq(x, y, rcond=None)[0]
    return float(np.sqrt(np.mean((y - x @ coef) ** 2)))


def combination_errors(log, prior, dofs, *, horizon, logged=()):
    """Per DOF of ``dofs`` the RMS error of the combination of the prior's simulation and the
    trivial predictors (:func:`combined_rms`) on the segments of its horizon (one number [s]
    or one per DOF, :func:`stripcoef.diagnose.horizon.per_dof`) [m/s or rad/s]; None when
    the prior's simulation diverges or cannot be replayed in batch."""
    from stripcoef.diagnose.horizon import per_dof

    hs = per_dof(horizon, dofs)
    out = [None] * len(dofs)
    for h in sorted(set(hs)):
        idx = [k for k, x in enumerate(hs) if x == h]
        got = segment_velocities(log, prior, [dofs[k] for k in idx], horizon=h,
                                 logged=logged)
        if got is None:
            return None
        for k, parts in zip(idx, got):
            out[k] = combined_rms(*parts)
    return out
