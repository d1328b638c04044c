r"""Effects of the inputs' timing: a first-order thruster lag and an actuation delay, with
the exact integrals of a held input they rest on (the force laws of
:mod:`stripcoef.effects.laws`' registry).

Depends on: effects.base, effects.windows.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import lfilter

from stripcoef.errors import InputError
from stripcoef.effects.base import Effect, _unit_vec


def _held_history(inputs):
    """(t, tau) of the whole run from the simulation's inputs (``input_history``)."""
    hist = inputs.get("input_history")
    if hist is None:
        raise InputError("this effect needs the input history of the simulation",
                         key="effects", expected="stripcoef.simulate.simulate")
    return hist


def lagged_held(t, u, time_constant):
    r"""First-order lag of a zero-order-hold input, exactly.

    .. math:: T\dot y = u - y,\quad y_{k+1} = u_k + (y_k - u_k)e^{-\Delta t_k/T},\quad
              \int_{t_k}^{t_{k+1}} y\,dt = u_k\Delta t_k + (y_k - u_k)\,T(1 - e^{-\Delta t_k/T})

    with :math:`y_0 = u_0` (in equilibrium at the start). ``t`` (n,) [s], ``u`` (n,) or
    (n, c), ``time_constant`` T [s]. Returns ``(y, integral)``: y at the samples and the
    exact integral of y over each interval (n - 1) [units of u times s].

    Source: Fossen (2011) sec. 9.3 (first-order actuator dynamics); Yoerger, Cooke &
    Slotine (1990), IEEE JOE 15 (thruster dynamics).
    """
    u = np.asarray(u, float)
    dt = np.diff(t)
    y = np.empty_like(u)
    y[0] = u[0]
    tc = max(float(time_constant), 1e-9)
    a = np.exp(-dt / tc)
    if dt.size and np.ptp(dt) <= 1e-9 * abs(float(dt[0])):
        # evenly sampled: the same recursion, y_{k+1} - a y_k = (1 - a) u_k, as a first-order
        # IIR filter (scipy.signal.lfilter, direct form II transposed; its initial state
        # a y_0 starts it in equilibrium) instead of a loop over the samples
        ak = float(a[0])
        y[1:] = lfilter([1.0 - ak], [1.0, -ak], u[:-1], axis=0,
                        zi=(ak * u[:1]).reshape((1,) + u.shape[1:]))[0]
    else:
        for k in range(dt.size):
            y[k + 1] = u[k] + (y[k] - u[k]) * a[k]
    w = tc * (1.0 - a)
    if u.ndim > 1:
        dt, w = dt[:, None], w[:, None]
    integral = u[:-1] * dt + (y[:-1] - u[:-1]) * w
    return y, integral


def delayed_integral(t, u, delay, s):
    r"""Integral of a held input delayed by ``delay`` up to the times ``s``.

    .. math:: \int_{t_0}^{s} u(\sigma - d)\,d\sigma = C(s - d) - C(t_0 - d),\quad
              C(x) = \int_{t_0}^{x} u,\ u(x < t_0) = u_0

    ``t`` (n,) [s], ``u`` (n,) zero-order hold, ``delay`` d [s] >= 0, ``s`` (m,) [s].
    """
    u = np.asarray(u, float)
    dt = np.diff(t)
    cum = np.concatenate([[0.0], np.cumsum(u[:-1] * dt)])

    def c(x):
        x = np.asarray(x, float)
        k = np.clip(np.searchsorted(t, x, side="right") - 1, 0, t.size - 1)
        return np.where(x < t[0], u[0] * (x - t[0]), cum[k] + u[k] * (x - t[k]))
    return c(np.asarray(s) - delay) - c(t[0] - delay)


def _resolvable(effect, value, data, samples):
    """'' if a time [s] is plausible and longer than ``samples`` sampling intervals of the
    log (a shorter lag or delay is not resolvable from it: it absorbs the quadrature error
    of the window integrals at input steps instead), else the reason."""
    if not effect.plausible({next(iter(effect.parameters)): value}):
        return "implausible parameters"
    if data is not None:
        dt = float(np.median(np.diff(data.t)))
        if value < samples * dt:
            return (f"{value:.3g} s is shorter than {samples:g} sampling interval(s) "
                    f"({samples * dt:.3g} s): not resolvable from this log")
    return ""


class _TimedInputEffect(Effect):
    """An effect of the inputs with one time parameter [s] (a lag, a delay), profiled by a
    one-dimensional search over :meth:`grid`: its design is the window mean of
    :meth:`offset`, the input as it acts minus the input as logged, and it has no linear
    coefficient.  Subclasses give ``hyper = (NAME,)``, ``GRID_MAX`` [s], ``GRID_LOG``
    (search points spaced geometrically, else evenly, from a tenth of the median sampling
    interval to ``GRID_MAX``), ``RESOLVE`` (how many sampling intervals make the parameter
    resolvable) and :meth:`offset`."""

    input_driven = True
    GRID_MAX = 1.0
    GRID_LOG = False
    RESOLVE = 1.0

    def grid(self, data, dof):
        dt = float(np.median(np.diff(data.t)))
        return (np.geomspace if self.GRID_LOG else np.linspace)(0.1 * dt, self.GRID_MAX, 12)

    def applicable(self, data, dof):
        if not np.any(data.tau[:, dof] != 0):
            return False, "no applied force in this DOF"
        return True, ""

    def hyper_start(self, data, dof):
        return np.array([0.0])

    def offset(self, data, dof, value):  # pragma: no cover - abstract
        raise NotImplementedError

    def own_design(self, data, dof, hyper=None):
        value = 0.0 if hyper is None else float(np.atleast_1d(hyper)[0])
        off = np.zeros(data.n_windows) if value <= 0 else self.offset(data, dof, value)
        return off, np.zeros((data.n_windows, 0))

    def to_parameters(self, theta, hyper, nuisance=None):
        return {self.hyper[0]: float(np.atleast_1d(hyper)[0])}

    def window_force(self, data, params, dof):
        return self.own_design(data, dof, [params[self.hyper[0]]])[0]

    all_dofs = True

    @property
    def admits(self) -> str:
        return f"0 < {self.hyper[0]} <= {self.GRID_MAX:g} s"

    def plausible(self, params):
        return 0.0 < params[self.hyper[0]] <= self.GRID_MAX

    def implausible(self, params, data=None, dof=None):
        return _resolvable(self, params[self.hyper[0]], data, self.RESOLVE)


class ThrusterLag(_TimedInputEffect):
    r"""Thruster dynamics: the thrust follows the command with a first-order lag.

    .. math:: T_l\,\dot{\tau}_{l} = \tau - \tau_{l},\qquad \Delta F_i = \tau_{l,i} - \tau_i

    with :math:`\tau` the applied force the prior predicts from the commands [N or N m],
    :math:`\tau_l` the force that acts and :math:`T_l` [s] the time constant, profiled by a
    one-dimensional search (one value for the vehicle's thrusters). The signature: a force
    that follows every step of the input and decays with the time constant; an inflated
    added mass (the confusion issue 16 measured in 6 of 6 logs) acts on the acceleration of
    the vehicle instead, whose time constant is M/D.

    Source: Yoerger, Cooke & Slotine (1990), IEEE JOE 15 (thruster dynamics); Fossen (2011)
    sec. 9.3 (first-order actuator model).
    """

    name = "thruster_lag"
    summary = "first-order lag of the thrust behind the command"
    source = "Yoerger et al. (1990); Fossen (2011) sec. 9.3"
    parameters = {"time_constant": "s"}
    hyper = ("time_constant",)
    #: search range of the time constant [s]: from a tenth of a sample to 2 s, geometric
    GRID_MAX = 2.0
    GRID_LOG = True
    RESOLVE = 0.5

    def signature(self, data, dof):
        return "a force that follows the steps of the input and decays"

    def offset(self, data, dof, tc):
        tau = data.tau[:, dof]
        _, integral = lagged_held(data.t, tau, tc)
        cum = np.concatenate([[0.0], np.cumsum(integral)])
        lagged = (cum[data.i1] - cum[data.i0]) / data.T
        return lagged - data.mean_held(tau)

    def force_law(self, params, dof):
        """Simulation force law: Delta F = tau_l - tau with T_l dtau_l/dt = tau - tau_l, exact
        for held inputs, T_l [s], tau [N, N m], in DOF ``dof`` (all six for None); returns
        f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        tc = params["time_constant"]
        e = np.ones(6) if dof is None else _unit_vec(dof)
        state = {"k": 0, "y": None}

        def f(time, eta, nu, inputs):
            t, taus = _held_history(inputs)
            # min/max, not np.clip: this runs at every evaluation of the right-hand side
            k = min(max(int(np.searchsorted(t, time, side="right")) - 1, 0), t.size - 1)
            if state["y"] is None or k < state["k"]:
                state["k"], state["y"] = 0, np.array(taus[0], float)
            while state["k"] < k:  # advance the lag state sample by sample (exact, held)
                j = state["k"]
                a = math.exp(-(t[j + 1] - t[j]) / tc)
                state["y"] = taus[j] + (state["y"] - taus[j]) * a
                state["k"] = j + 1
            u = np.asarray(inputs["tau"], float)
            y = u + (state["y"] - u) * math.exp(-max(time - t[k], 0.0) / tc)
            return (y - u) * e
        return f

    def batch_force_law(self, params, dof, history):
        r""":meth:`force_law` for many segments of one log at once (the free simulations of
        :mod:`stripcoef.diagnose.freesim`), the same numbers: the lag state
        :math:`y_{j+1} = \tau_j + (y_j - \tau_j)e^{-\Delta t_j/T_l}` from the log's first
        sample, :math:`y_0 = \tau_0`, is the same for every segment, so it is computed once
        per sample (the recursion and the rounding of :meth:`force_law`) instead of once per
        segment from the log's start, and once for the lag of every DOF (one time constant).
        ``history``: ``t`` (n,) [s] and ``tau`` (n, 6) [N, N m] of the log, and a dict that
        the laws of one simulation share. Returns g(times (S,), rows (S,), last (S,)) ->
        (S, 6) [N, N m]: segment s at time ``times[s]`` [s], holding the input of sample
        ``rows[s]``, its input history ending at sample ``last[s]``."""
        tc = params["time_constant"]
        e = np.ones(6) if dof is None else _unit_vec(dof)
        t, taus = history["t"], history["tau"]
        shared = history.setdefault(("thruster_lag", tc), {"at": None})
        if "y" not in shared:
            y = np.empty((t.size, 6))
            y[0] = np.array(taus[0], float)
            for j in range(t.size - 1):          # force_law's recursion, sample by sample
                y[j + 1] = taus[j] + (y[j] - taus[j]) * math.exp(-(t[j + 1] - t[j]) / tc)
            shared["y"] = y
        y = shared["y"]

        def g(times, rows, last):
            at = shared["at"]
            if at is None or at[0] is not times or at[1] is not rows:
                # the lag of every DOF at these times: once per evaluation
                k = np.minimum(np.maximum(np.searchsorted(t, times, side="right") - 1, 0),
                               last)
                decay = np.array([math.exp(-max(tm - tk, 0.0) / tc)
                                  for tm, tk in zip(times.tolist(), t[k].tolist())])
                u = taus[rows]
                shared["at"] = at = (times, rows, u + (y[k] - u) * decay[:, None] - u)
            return at[2] * e
        return g


class ActuationDelay(_TimedInputEffect):
    r"""A pure delay between the logged command and the force it produces.

    .. math:: \Delta F_i = \tau_i(t - d) - \tau_i(t)

    with d [s] profiled by a one-dimensional search: communication and driver latency, a
    command logged before it is sent. The signature: a force that precedes the response
    by a fixed time at every step of the input.

    Source: Fossen (2011) sec. 9.3 (actuator dynamics and time delays); Yoerger, Cooke &
    Slotine (1990), IEEE JOE 15.
    """

    name = "actuation_delay"
    summary = "pure time delay between command and thrust"
    source = "Fossen (2011) sec. 9.3; Yoerger et al. (1990)"
    parameters = {"delay": "s"}
    hyper = ("delay",)
    GRID_MAX = 1.0
    RESOLVE = 1.0

    def signature(self, data, dof):
        return "a force that precedes the response by a fixed time"

    def offset(self, data, dof, delay):
        tau = data.tau[:, dof]
        a = delayed_integral(data.t, tau, delay, data.t[data.i0])
        b = delayed_integral(data.t, tau, delay, data.t[data.i1])
        return (b - a) / data.T - data.mean_held(tau)

    def force_law(self, params, dof):
        """Simulation force law: Delta F = tau(t - d) - tau(t), d [s], tau [N, N m], in DOF
        ``dof`` (all six for None); returns f(time, eta, nu, inputs) -> (6,) [N, N m]."""
        d = params["delay"]
        e = np.ones(6) if dof is None else _unit_vec(dof)

        def f(time, eta, nu, inputs):
            t, taus = _held_history(inputs)
            k = min(max(int(np.searchsorted(t, time - d, side="right")) - 1, 0), t.size - 1)
            return (np.asarray(taus[k], float) - np.asarray(inputs["tau"], float)) * e
        return f

    def batch_force_law(self, params, dof, history):
        r""":meth:`force_law` for many segments of one log at once (as
        :meth:`ThrusterLag.batch_force_law`, the same numbers, once per evaluation for the
        delay of every DOF): g(times (S,), rows (S,), last (S,)) -> (S, 6) [N, N m],
        :math:`\tau(t - d) - \tau(t)` of each segment."""
        d = params["delay"]
        e = np.ones(6) if dof is None else _unit_vec(dof)
        t, taus = history["t"], history["tau"]
        shared = history.setdefault(("actuation_delay", d), {"at": None})

        def g(times, rows, last):
            at = shared["at"]
            if at is None or at[0] is not times or at[1] is not rows:
                k = np.minimum(np.maximum(np.searchsorted(t, times - d, side="right") - 1, 0),
                               last)
                shared["at"] = at = (times, rows, taus[k] - taus[rows])
            return at[2] * e
        return g


