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

import math

import numpy as np

from stripcoef.conventions import DOF, VELOCITIES
from stripcoef.effects.windows import white_noise_sd  # noqa: F401  (the log's noise)
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


#: ``logged`` of :func:`segment_squared_errors`: each DOF simulated on its own, the five
#: others following the log (the equation decoupling of the one-DOF validation applied to
#: every DOF of a whole-log diagnosis; :data:`stripcoef.diagnose.settings.VALIDATION_OTHERS`).
EACH = "each"


def free_simulation_errors(log, model, dofs, *, horizon: float = HORIZON,
                           tolerances=TOLERANCES, logged=()):
    """RMS free-simulation error of each DOF in ``dofs`` (list of indices) [m/s or rad/s]
    (module docstring), or None when a simulation diverges; ``logged`` as for
    :func:`segment_squared_errors`."""
    got = segment_squared_errors(log, model, dofs, horizon=horizon, tolerances=tolerances,
                                 logged=logged)
    if got is None:
        return None
    sse, counts = got
    return [float(np.sqrt(v)) for v in np.sum(sse, axis=0) / np.sum(counts)]


def segment_squared_errors(log, model, dofs, *, horizon: float = HORIZON,
                           tolerances=TOLERANCES, bounds=None, logged=()):
    r"""``(sse, counts)``: per segment s of :func:`segments` the sum of the squared
    free-simulation errors of each DOF of ``dofs``,
    :math:`\sum_{k \in s}(\hat\nu_i(t_k) - \nu_i(t_k))^2` [(m/s)^2 or (rad/s)^2], an
    array (segments, DOFs), and the samples of each segment; None when a simulation
    diverges. The segments restart from the logged state, so they are the independent
    units of a paired comparison of two models (Hastie, Tibshirani & Friedman 2009,
    sec. 7.10: the standard error of a cross-validated difference);
    :func:`free_simulation_errors` is their pooled RMS. ``bounds``: other segments
    (e.g. :func:`rolling_segments`) instead of :func:`segments`. ``logged``: DOFs whose
    velocity (and, for roll and pitch together, attitude) follows the log instead of the
    model (:func:`stripcoef.diagnose.freesim.batch_free_velocities`; a model the batch
    integrator does not replay, one with control surfaces, is simulated in every DOF);
    :data:`EACH`: each DOF of ``dofs`` simulated alone, the five others logged."""
    from stripcoef.diagnose.freesim import batch_free_velocities, supported
    from stripcoef.logfile import log_inputs
    from stripcoef.simulate import replay

    if isinstance(logged, str) and logged == EACH:   # each DOF alone, the others logged
        parts = [segment_squared_errors(log, model, [i], horizon=horizon,
                                        tolerances=tolerances, bounds=bounds,
                                        logged=[j for j in range(6) if j != i])
                 for i in dofs]
        if any(p is None for p in parts):
            return None
        return np.hstack([p[0] for p in parts]), parts[0][1]
    t = log["t"]
    try:
        inputs = log_inputs(log, model)       # the one replay rule (simulate --from-log's)
    except StripcoefError:
        return None
    bounds = segments(t, horizon) if bounds is None else list(bounds)
    sse = np.zeros((len(bounds), len(dofs)))
    counts = np.array([b - a for a, b in bounds], float)
    if supported(model, inputs):        # all segments at once (diagnose/freesim.py)
        runs = batch_free_velocities(model, log, bounds, inputs, tolerances=tolerances,
                                     logged=logged)
        if runs is None:
            return None
        zeros = np.zeros(t.size)
        for s, ((a, b), nu) in enumerate(zip(bounds, runs)):
            for k, i in enumerate(dofs):
                sse[s, k] = np.sum((nu[:, i] - log.get(VELOCITIES[i], zeros)[a:b]) ** 2)
        return sse, counts
    for s, (a, b) in enumerate(bounds):
        part = log.slice(a, b)
        try:
            sim = replay(model, part, inputs=inputs.window(a, b),
                         rtol=tolerances[0], atol=tolerances[1])
        except StripcoefError:
            return None
        zeros = np.zeros(b - a)
        for k, i in enumerate(dofs):
            v = VELOCITIES[i]
            sse[s, k] = np.sum((np.asarray(sim[v]) - part.get(v, zeros)) ** 2)
    return sse, counts


#: Spacing of the rolling origins of the held-out comparison (:func:`rolling_segments`) [s]:
#: a restart every 2 s, each simulated over the whole :data:`HORIZON`.
ROLLING_STEP = 2.0


def rolling_segments(t, horizon: float = HORIZON, step: float = ROLLING_STEP) -> list:
    """Index bounds ``[(a, b), ...]`` of segments of ``horizon`` seconds [s] restarted every
    ``step`` seconds (rolling forecast origins: Hyndman & Athanasopoulos 2021, sec. 5.10,
    time-series cross-validation; Tashman 2000, Int. J. Forecasting 16: 437-450), each
    whole (none runs past the log's end). With ``step`` < ``horizon`` consecutive
    segments overlap by ``horizon - step``: their losses are serially correlated up to
    ``ceil(horizon/step) - 1`` lags, which :func:`diebold_mariano`'s ``overlap`` accounts
    for. On a held-out part of 90 s, :func:`segments` gives 9 segments, this 41."""
    t = np.asarray(t, float)
    out, s = [], float(t[0])
    while s + horizon <= t[-1] + 1e-9:
        a = int(np.searchsorted(t, s - 1e-9))
        b = int(np.searchsorted(t, t[a] + horizon - 1e-9))
        if b - a >= 2:
            out.append((a, b))
        s += step
    return out


def overlap_steps(horizon: float = HORIZON, step: float = ROLLING_STEP) -> int:
    """h of :func:`diebold_mariano` for :func:`rolling_segments`: ``ceil(horizon / step)``,
    the number of origins whose segments share samples with one segment's (1: none)."""
    return max(1, int(math.ceil(horizon / step - 1e-9)))


def diebold_mariano(loss_a, loss_b, *, overlap: int = 1) -> dict:
    r"""The Diebold-Mariano test of equal accuracy of two predictors from their losses on the
    same units (here the 10-s free-simulation segments of :func:`segment_squared_errors`,
    one DOF: each segment's sum of squared errors [(m/s)^2 or (rad/s)^2]).

    With :math:`d_s = L^a_s - L^b_s` over S segments, :math:`\bar d` its mean and
    :math:`\hat\sigma^2` its long-run variance by the Newey-West (1987) estimator (Bartlett
    weights, lag truncation :math:`\lfloor 4 (S/100)^{2/9} \rfloor`, Newey & West 1994: the
    segments restart from the logged state, but slow disturbances, a current or a tether,
    can carry over from one segment to the next),

    .. math:: DM = \frac{\bar d}{\sqrt{\hat\sigma^2 / S}}
              \sqrt{\frac{S - 1}{S}}

    (Diebold & Mariano 1995, J. Business & Economic Statistics 13: 253-263; the factor is
    Harvey, Leybourne & Newbold's 1997 small-sample correction for one-step, i.e.
    non-overlapping, forecasts), compared with Student's t with S - 1 degrees of freedom.
    Returns ``{"statistic", "p_value"`` (one-sided: a's loss below b's), ``"mean_difference",
    "segments", "lags"}``; a negative statistic favours a. Few segments (a validation part of
    one or two minutes holds 5-6) give the test little power: its value says how strong the
    evidence for a decision is.

    ``overlap`` = h > 1: the units are h-step forecasts whose windows overlap
    (:func:`rolling_segments`), so d is serially correlated to lag h - 1 even for a correct
    model; the long-run variance is then Diebold & Mariano's (1995, sec. 1.1): the
    autocovariances to lag h - 1 with uniform weights (Bartlett's where that sum is not
    positive), and the small-sample factor Harvey et al.'s for h steps,
    :math:`\sqrt{(S + 1 - 2h + h(h-1)/S)/S}`. Measured (test_heldout_paired, MA(4)
    differential, S = 41): about 8 % rejections at a nominal 5 % (Harvey et al. 1997 report
    the same mild excess), against 10-12 % with Bartlett weights to lag 8-12."""
    from scipy.stats import t as student

    d = np.asarray(loss_a, float) - np.asarray(loss_b, float)
    n = d.size
    h = max(1, int(overlap))
    lags = h - 1 if h > 1 else int(np.floor(4.0 * (n / 100.0) ** (2.0 / 9.0)))
    lags = min(lags, max(n - 1, 0))
    mean = float(np.mean(d)) if n else float("nan")
    if n < 2:
        return {"statistic": float("nan"), "p_value": float("nan"), "mean_difference": mean,
                "segments": n, "lags": lags}
    var = -1.0
    if h > 1:
        gamma = _autocovariances(d, lags)
        var = gamma[0] + 2.0 * sum(gamma[1:])
    if not var > 0.0:
        var = long_run_variance(d, lags)
    if not var > 0.0:
        stat = 0.0 if mean == 0.0 else math.copysign(math.inf, mean)
    else:
        factor = (n + 1.0 - 2.0 * h + h * (h - 1.0) / n) / n
        stat = mean / math.sqrt(var / n) * math.sqrt(max(factor, 1.0 / n))
    return {"statistic": float(stat), "p_value": float(student.cdf(stat, n - 1)),
            "mean_difference": mean, "segments": n, "lags": lags}


def _autocovariances(d, lags: int) -> list:
    """The autocovariances of ``d`` about its mean to lag ``lags``, each sum over n
    [units of d squared]."""
    d = np.asarray(d, float)
    n = d.size
    c = d - float(np.mean(d))
    return [float(c[k:] @ c[:n - k]) / n for k in range(lags + 1)]


def long_run_variance(d, lags: int | None = None) -> float:
    r"""The long-run variance of the series ``d`` by the Newey-West (1987, Econometrica 55,
    703-708) estimator, :math:`\hat\gamma_0 + 2 \sum_{k=1}^{L} (1 - k/(L+1)) \hat\gamma_k`
    (Bartlett weights), ``lags`` L by default Newey & West's (1994, Rev. Econ. Stud. 61,
    631-653) :math:`\lfloor 4 (n/100)^{2/9} \rfloor`, at most n - 1 [units of d squared]; not
    clipped at zero. The variance of :func:`diebold_mariano` and of the Vuong test of
    :mod:`stripcoef.diagnose.regains`."""
    n = np.asarray(d).size
    if lags is None:
        lags = int(np.floor(4.0 * (n / 100.0) ** (2.0 / 9.0)))
    lags = min(int(lags), max(n - 1, 0))
    gamma = _autocovariances(d, lags)
    return gamma[0] + sum(2.0 * (1.0 - k / (lags + 1.0)) * gamma[k]
                          for k in range(1, lags + 1))


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

#: Significance level of :func:`paired_verdicts` (one-sided per comparison).
ALPHA = 0.05


def segment_losses(log, models: dict, dofs, bounds, *, tolerances=TOLERANCES) -> dict:
    r"""Per segment of ``bounds`` and DOF of ``dofs`` the mean squared free-simulation error
    of each model of ``models`` and of the trivial predictors (:data:`TRIVIAL_PREDICTORS`),
    :math:`\frac{1}{n_s}\sum_{k\in s}(\hat\nu_i(t_k) - \nu_i(t_k))^2`
    [(m/s)^2 or (rad/s)^2]: ``{name: (segments, DOFs) array or None}`` (None: diverged).
    The trivial predictors know at a segment's start what the models know, the logged
    velocity there (hold-last-velocity) or nothing (zero velocity), and nothing after it."""
    t = np.asarray(log["t"], float)
    zeros = np.zeros(t.size)
    out = {}
    counts = np.array([b - a for a, b in bounds], float)
    for name, m in models.items():
        got = segment_squared_errors(log, m, dofs, bounds=bounds, tolerances=tolerances)
        out[name] = None if got is None else got[0] / counts[:, None]
    hold = np.zeros((len(bounds), len(dofs)))
    zero = np.zeros((len(bounds), len(dofs)))
    for k, i in enumerate(dofs):
        v = log.get(VELOCITIES[i], zeros)
        for s, (a, b) in enumerate(bounds):
            hold[s, k] = np.mean((v[a:b] - v[a]) ** 2)
            zero[s, k] = np.mean(v[a:b] ** 2)
    out["hold_last_velocity"], out["zero_velocity"] = hold, zero
    return out


def paired_verdicts(losses: dict, dofs, *, candidate: str = "calibrated",
                    against=("prior",) + TRIVIAL_PREDICTORS, overlap: int = 1,
                    alpha: float = ALPHA) -> dict:
    """Per DOF of ``dofs`` (indices, the columns of :func:`segment_losses`' arrays):
    ``{dof_name: {"verdict": "win" | "loss" | "not distinguishable", "tests": {name:
    diebold_mariano(candidate, name)}}}``.

    "win": the candidate's loss is below every one of ``against``'s, each by a one-sided
    Diebold-Mariano test at level ``alpha`` (an intersection-union test, whose level is
    ``alpha`` without a multiplicity correction: Berger 1982, Technometrics 24: 295-300);
    "loss": above at least one of them at level ``alpha / len(against)`` (Bonferroni: a
    union of tests); otherwise "not distinguishable" (the segments do not tell the
    difference from the noise). A diverged candidate loses."""
    out = {}
    for k, i in enumerate(dofs):
        c = losses.get(candidate)
        if c is None:
            out[DOF[i]] = {"verdict": "loss", "tests": {}}
            continue
        tests = {name: diebold_mariano(c[:, k], losses[name][:, k], overlap=overlap)
                 for name in against if losses.get(name) is not None}
        better = all(v["p_value"] < alpha for v in tests.values()) and len(tests) == len(against)
        worse = any(1.0 - v["p_value"] < alpha / max(1, len(against)) for v in tests.values())
        out[DOF[i]] = {"verdict": "win" if better else "loss" if worse else
                       "not distinguishable", "tests": tests}
    return out


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


def paired_record(log, models: dict, dofs, *, candidate: str = "calibrated",
                  horizon: float = HORIZON, step: float = ROLLING_STEP) -> dict:
    """The paired tests of ``candidate`` against the other models of ``models`` and the
    trivial predictors on ``log`` (:func:`segment_losses` on :func:`rolling_segments`,
    :func:`paired_verdicts` with their overlap) as a JSON-ready record: ``{"description",
    "segments", "horizon_s", "step_s", dof_name: {"verdict", "statistic": {name: DM},
    "p_value": {name: one-sided p}}}``; ``{"segments": 0, ...}`` when the log is shorter
    than one horizon."""
    t = np.asarray(log["t"], float)
    bounds = rolling_segments(t, horizon, step)
    out = {"description": f"Diebold-Mariano tests of the {candidate} model's {horizon:g}-s "
                          f"free-simulation losses against each other predictor's, "
                          f"restarted every {step:g} s (overlapping: Diebold-Mariano's "
                          "h-step variance, Harvey et al.'s factor); a negative statistic "
                          f"favours the {candidate} model; verdict 'win' (below all, one-sided "
                          f"{ALPHA:g} each), 'loss' (above one, Bonferroni) or 'not "
                          "distinguishable'",
           "segments": len(bounds), "horizon_s": horizon, "step_s": step}
    if not bounds:
        return out
    losses = segment_losses(log, models, dofs, bounds)
    against = tuple(n for n in models if n != candidate) + TRIVIAL_PREDICTORS
    got = paired_verdicts(losses, dofs, candidate=candidate, against=against,
                          overlap=overlap_steps(horizon, step))
    for d, v in got.items():
        out[d] = {"verdict": v["verdict"],
                  "statistic": {n: x["statistic"] for n, x in v["tests"].items()},
                  "p_value": {n: x["p_value"] for n, x in v["tests"].items()}}
    return out


#: State columns a twin start is perturbed in (:func:`twin_spread`): the velocities and the
#: angles the restoring forces depend on.
TWIN_COLUMNS = ("u", "v", "w", "p", "q", "r", "phi", "theta")
#: Noise draws of the twin experiment (:func:`twin_spread`): the spread is the RMS over them.
TWIN_DRAWS = 3


def _batch_inputs(log, model):
    """The log's inputs (:func:`stripcoef.logfile.log_inputs`) when the batch simulator
    (:mod:`.freesim`) replays them for ``model``, else None."""
    from stripcoef.diagnose.freesim import supported
    from stripcoef.logfile import log_inputs

    try:
        inputs = log_inputs(log, model)
    except StripcoefError:
        return None
    return inputs if supported(model, inputs) else None


def _with_noise(cols: dict, sd: dict, rng) -> dict:
    """``cols`` with normal white noise of standard deviation ``sd[c]`` added to each column
    c of ``sd`` (drawn in ``sd``'s order); the other columns as they are."""
    out = dict(cols)
    for c, s in sd.items():
        out[c] = out[c] + rng.normal(0.0, s, out[c].size)
    return out


def twin_spread(log, model, dofs, *, horizon: float = HORIZON, seed: int = 0,
                draws: int = TWIN_DRAWS):
    r"""Identical-twin spread of ``model`` on ``log`` per DOF of ``dofs`` [m/s or rad/s], or
    None where a simulation diverges or the model is outside the batch simulator.

    The free simulations of :func:`free_simulation_errors` (segments of ``horizon`` s) are run
    from the logged states and again from those states with each of :data:`TWIN_COLUMNS`
    perturbed by a draw of the log's own white noise (:func:`white_noise_sd`, normal, seeded);
    the spread of DOF i is

    .. math:: S_i = \sqrt{\frac{1}{D N}\sum_{d=1}^{D}\sum_{s}\sum_{k \in s}
              \big(\hat\nu_i^{(d)}(t_k) - \hat\nu_i(t_k)\big)^2}

    over ``draws`` = D draws: the error the sensors' noise on the starting state alone puts
    on the model's own predictions, grown by the model's dynamics over the horizon (Lorenz
    1965, Tellus 17: 321-333, the identical-twin experiment). Needs no truth: it uses the
    log and the model only."""
    from stripcoef.diagnose.freesim import batch_free_velocities
    from stripcoef.logfile import Log

    rng = np.random.default_rng(seed)
    inputs = _batch_inputs(log, model)
    if inputs is None:
        return None
    bounds = segments(np.asarray(log["t"], float), horizon)
    base = batch_free_velocities(model, log, bounds, inputs)
    if base is None:
        return None
    sd = {c: white_noise_sd(log[c]) for c in TWIN_COLUMNS if c in log.columns}
    sq = np.zeros(len(dofs))
    n = 0
    for _ in range(max(1, int(draws))):
        cols = _with_noise({c: np.asarray(log[c], float) for c in log.columns}, sd, rng)
        twin = batch_free_velocities(model, Log(cols, source=f"{log.source} (twin)"),
                                     bounds, inputs)
        if twin is None:
            return None
        diff = np.concatenate([a - b for a, b in zip(twin, base)])[:, list(dofs)]
        sq += np.sum(diff ** 2, axis=0)
        n += diff.shape[0]
    return [float(v) for v in np.sqrt(sq / n)]


def noise_growth(log, model, dofs, *, horizon: float = HORIZON, seed: int = 0,
                 draws: int = TWIN_DRAWS, tolerances=TOLERANCES):
    r"""How far the sensors' noise on a segment's starting state grows within the horizon
    under ``model``'s dynamics *along the logged motion*, per DOF of ``dofs`` [m/s or
    rad/s]; None where the model is outside the batch simulator or a step diverges.

    The identical twin of :func:`twin_spread` follows the model's own free simulation, which
    leaves the logged motion as soon as the model is wrong (a prior's yaw twin on the
    BlueROV2-Heavy-like tether log: 0.09 rad/s, the truth's own 0.41). Here the perturbation
    is carried along the log instead: for each segment, a perturbation
    :math:`\delta_0` drawn from the log's own white noise (:func:`white_noise_sd` of each of
    :data:`TWIN_COLUMNS`) is propagated sample by sample,

    .. math:: \delta_{k+1} = \Phi_k(x_k + \delta_k) - \Phi_k(x_k),

    with :math:`x_k` the logged state and :math:`\Phi_k` the model's flow over the sample
    interval with the logged input held (the integrator of :mod:`.freesim`): the error
    dynamics of the model linearised (to the noise's size) about the logged trajectory, the
    tangent-linear growth of a predictability study (Lorenz 1965, Tellus 17: 321-333; Kalnay
    2003, Atmospheric Modeling, Data Assimilation and Predictability, sec. 6.3). The result
    is the RMS of the velocity part of :math:`\delta` over the samples and ``draws`` draws.
    The model's effects are left out (the vehicle's matrices, restoring forces and Coriolis
    terms set the growth)."""
    from stripcoef.diagnose.freesim import BatchRightHandSide, integrate_interval
    from stripcoef.simulate import InputSampler, attitude_quaternion

    t = np.asarray(log["t"], float)
    inputs = _batch_inputs(log, model)
    if inputs is None:
        return None
    sampler = InputSampler(model, t, forces=inputs.forces, commands=inputs.commands or None,
                           deflections=None, channels=inputs.channels or None, current=None,
                           interpolation="previous", history=True)
    tau_all = sampler.tau_history

    def states(cols):
        """(n, 13) states [p; q (x, y, z, w); nu] of pose and velocity columns."""
        n = len(next(iter(cols.values())))
        get = [np.asarray(cols[c], float) if c in cols else np.zeros(n)
               for c in ("x", "y", "z", "phi", "theta", "psi") + VELOCITIES]
        quat = attitude_quaternion(np.column_stack(get[:6]))
        return np.column_stack([*get[:3], quat, *get[6:]])

    cols = {c: np.asarray(log[c], float) for c in log.columns}
    base = states(cols)
    rng = np.random.default_rng(seed)
    sd = {c: white_noise_sd(cols[c]) for c in TWIN_COLUMNS if c in cols}
    bounds = segments(t, horizon)
    starts = np.array([a for a, _ in bounds])
    lengths = np.array([b - a for a, b in bounds])
    n_seg, d = len(bounds), max(1, int(draws))
    delta = np.empty((d, n_seg, 13))
    for j in range(d):
        noisy = _with_noise(cols, sd, rng)
        delta[j] = states({c: v[starts] for c, v in noisy.items()}) - base[starts]
    f = BatchRightHandSide(model)
    sq = np.sum(delta[:, :, 7:] ** 2, axis=(0, 1))
    count, ds = d * n_seg, 1.0           # ds: the step the error control proposes next
    for k in range(int(lengths.max()) - 1):
        act = np.nonzero(lengths > k + 1)[0]
        rows = starts[act] + k
        x0 = base[rows]
        stack = np.concatenate([x0] + [x0 + delta[j, act] for j in range(d)])
        f.tau = np.tile(tau_all[rows], (d + 1, 1))
        h = np.tile(t[rows + 1] - t[rows], d + 1)
        got = integrate_interval(f, np.tile(t[rows], d + 1), h, stack, *tolerances, ds)
        if got is None:
            return None
        end, ds = got
        ds = min(ds, 1.0)
        m = act.size
        new = end[m:].reshape(d, m, 13) - end[:m]
        # the next logged state's quaternion may be the other sign of the same attitude
        flip = np.sum(base[rows + 1, 3:7] * end[:m, 3:7], axis=1) < 0.0
        new[:, flip, 3:7] *= -1.0
        delta[:, act] = new
        sq += np.sum(new[:, :, 7:] ** 2, axis=(0, 1))
        count += d * m
    return [float(np.sqrt(sq[i] / count)) for i in dofs]


def predictable(errors: dict, spread, *others) -> dict:
    r"""Which DOFs of ``errors`` (:func:`compare`'s dictionary) a model can be judged on over
    the horizon: ``{dof_name: True/False}``, True when the model's twin spread ``spread``
    (:func:`noise_growth` or :func:`twin_spread`, one value per DOF in the order of
    ``errors``) is below the smaller
    of the trivial predictors' errors (:data:`TRIVIAL_PREDICTORS`).

    Where it is not, the sensors' noise on the logged starting state alone, grown by the
    model's own dynamics (an open-loop vehicle that is unstable under way, e.g. by the Munk
    moment of its added mass, :math:`(Y_{\dot v} - X_{\dot u})uv` in yaw: the C_A of Fossen
    2011, eq. 6.43; Ferreira et al. 2009, sec. V.D), moves its
    predictions farther from the data than predicting no change or no motion: whatever the
    model's coefficients, its comparison with the trivial predictors then measures the noise,
    not the model (a simulation error is judged over a horizon on which the process is
    predictable from the data: Ljung 1999, sec. 16.4; Lorenz 1965). A diverged model
    (``spread`` None) is never exempted: every DOF counts as predictable.

    ``others``: the spreads of other models of the same vehicle (e.g. the prior's and the
    calibrated model's). Predictability is the vehicle's, and each model's spread estimates
    it through that model's dynamics: a DOF is exempted only where *every* model's spread
    reaches the trivial predictors' error (an intersection: no single model's dynamics
    excuses a DOF). With the prior's alone, a prior whose dynamics are wrong exempts the
    DOFs it is worst in (issue 33, seed-7 current log, forward: the prior's roll growth
    0.54 rad/s, the calibrated model's 0.045 and the truth's 0.10 against zero velocity's
    0.19; the truth's own error there 0.042); with the calibrated model's alone, a
    calibration would exempt itself."""
    spreads = (spread, *others)
    out = {}
    for k, (dof, e) in enumerate(errors.items()):
        trivial = min(e[name] for name in TRIVIAL_PREDICTORS)
        out[dof] = not all(s is not None and s[k] is not None and not bool(s[k] < trivial)
                           for s in spreads)
    return out


def _rms(x):
    return float(np.sqrt(np.mean(np.asarray(x) ** 2))) if np.size(x) else float("nan")
