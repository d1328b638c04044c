r"""6-DOF time simulation of a :class:`~stripcoef.model.HydroModel`.

Equations of motion with a water current (Fossen 2011, eq. 10.1 and sec. 10.3;
Wang & Clark 2006, eqs. 1-2):

.. math::
    M_{RB}\dot\nu + C_{RB}(\nu)\nu + M_A\dot\nu_r + C_A(\nu_r)\nu_r + D(\nu_r)\nu_r
    + g(\eta) = \tau + \tau_{extra}, \qquad \dot\eta = J(\eta)\nu

where :math:`\nu` is the body velocity over ground, :math:`\nu_r = \nu - \nu_c` the
velocity relative to the water and :math:`\nu_c = [R(\Theta)^T V_c;\ 0]` the current
expressed in body axes (the current :math:`V_c` is given in the earth-fixed NED frame
and is irrotational).  Its body-axes rate is

.. math::
    \dot\nu_c = [-S(\omega) R^T V_c + R^T \dot V_c;\ 0]

so the state equation solved for :math:`\dot\nu` is

.. math::
    (M_{RB} + M_A)\dot\nu = \tau + \tau_{extra} - C_{RB}(\nu)\nu - C_A(\nu_r)\nu_r
    - D(\nu_r)\nu_r - g(\eta) + M_A\dot\nu_c

The applied force :math:`\tau = B\,T(n) + \tau_{forces}` is the thrust of every
thruster through the allocation matrix ``B`` (``Thruster.thrust``: forward/backward
coefficients, efficiencies, dead band, limits) plus the given generalized forces.
:math:`\tau_{extra}` gathers the calibrated effects of the model
(``model.effects``, see :mod:`stripcoef.effects.laws`) and a user hook.

The state is integrated with :func:`scipy.integrate.solve_ivp`; with zero-order-hold
inputs the integration restarts at every sample where an input jumps, so the
integrator never steps across a discontinuity.
"""

from __future__ import annotations

from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp

from stripcoef.conventions import FORCES, POSE, VELOCITIES, kinematics, rotation_matrix, skew
from stripcoef.errors import InputError, UnreachableError, unknown_name
from stripcoef.logfile import COMMAND_PREFIX, Log

INTERPOLATIONS = ("previous", "linear")


def _as_time(t) -> np.ndarray:
    t = np.asarray(t, dtype=float).reshape(-1)
    if t.size < 2:
        raise InputError("too few time samples", key="t", value=int(t.size),
                         expected="at least 2 increasing times [s]")
    if not np.all(np.isfinite(t)):
        k = int(np.nonzero(~np.isfinite(t))[0][0])
        raise InputError(f"non-finite time at index {k}", key="t", value=float(t[k]),
                         expected="finite times [s]")
    d = np.diff(t)
    if np.any(d <= 0):
        k = int(np.nonzero(d <= 0)[0][0])
        raise InputError(f"time not strictly increasing at index {k + 1}", key="t",
                         value=float(t[k + 1]), expected=f"a time after {t[k]!r} [s]")
    return t


def _as_series(values, n: int, width: int, key: str) -> np.ndarray:
    a = np.asarray(values, dtype=float)
    if width == 1:
        a = a.reshape(-1)
        shape_ok = a.shape == (n,)
    else:
        if a.ndim == 1 and a.size == width:
            a = np.tile(a, (n, 1))
        shape_ok = a.shape == (n, width)
    if not shape_ok:
        raise InputError("wrong shape", key=key, value=list(np.shape(values)),
                         expected=f"{n} samples" + (f" x {width}" if width > 1 else ""))
    if not np.all(np.isfinite(a)):
        k = int(np.nonzero(~np.isfinite(a.reshape(n, -1)).any(axis=1))[0][0])
        raise InputError(f"NaN or infinite value at sample {k}", key=key,
                         expected="finite numbers")
    return a


class _Sampler:
    """Evaluate sampled inputs at any time: zero-order hold or linear interpolation."""

    def __init__(self, t: np.ndarray, values: np.ndarray, interpolation: str):
        self.t = t
        self.values = values
        self.linear = interpolation == "linear"

    def __call__(self, time: float) -> np.ndarray:
        t = self.t
        if self.linear:
            k = int(np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 2))
            s = (time - t[k]) / (t[k + 1] - t[k])
            s = min(max(s, 0.0), 1.0)
            return self.values[k] * (1.0 - s) + self.values[k + 1] * s
        k = int(np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 1))
        return self.values[k]

    def rate(self, time: float) -> np.ndarray:
        """Time derivative (piecewise constant for linear, zero for zero-order hold)."""
        if not self.linear:
            return np.zeros_like(self.values[0])
        t = self.t
        k = int(np.clip(np.searchsorted(t, time, side="right") - 1, 0, t.size - 2))
        return (self.values[k + 1] - self.values[k]) / (t[k + 1] - t[k])


def _current_function(current, t, interpolation):
    """Return f(time) -> (V_c [m/s], dV_c/dt [m/s^2]) in NED, or None."""
    if current is None:
        return None
    if callable(current):
        def f(time, _c=current):
            v = np.asarray(_c(time), dtype=float).reshape(3)
            h = 1e-6
            dv = (np.asarray(_c(time + h), float).reshape(3)
                  - np.asarray(_c(time - h), float).reshape(3)) / (2 * h)
            return v, dv
        return f
    c = np.asarray(current, dtype=float)
    if c.shape == (3,):
        if not np.all(np.isfinite(c)):
            raise InputError("non-finite current", key="current", value=c.tolist(),
                             expected="three finite numbers [m/s] (north, east, down)")
        zero = np.zeros(3)
        return lambda time: (c, zero)
    series = _as_series(c, t.size, 3, "current")
    sampler = _Sampler(t, series, "linear" if interpolation == "linear" else "previous")
    return lambda time: (sampler(time), sampler.rate(time))


def simulate(model, t, *, forces=None, commands=None, current=None, eta0=None, nu0=None,
             interpolation: str = "previous", rtol: float = 1e-8, atol: float = 1e-10,
             method: str = "RK45", max_step: float | None = None,
             extra_force: Callable | None = None, effects: bool = True,
             munk: bool = True, channels: dict | None = None,
             controller: Callable | None = None) -> Log:
    r"""Simulate the 6-DOF motion of ``model`` and return it as a log.

    .. math::
        M\dot\nu = \tau + \tau_{extra} - C_{RB}(\nu)\nu - C_A(\nu_r)\nu_r
        - D(\nu_r)\nu_r - g(\eta) + M_A\dot\nu_c,\qquad \dot\eta = J(\eta)\nu

    (module docstring; Fossen 2011 eqs. 10.1, 10.3; Wang & Clark 2006 eqs. 1-2).

    Parameters
    ----------
    model : HydroModel
        The vehicle; matrices about ``model.reference_point``, FRD body axes.
    t : (n,) array
        Strictly increasing output times [s]; the log has one row per time.
    forces : (n, 6) array, (6,) array or callable, optional
        Applied generalized forces ``[X, Y, Z, K, M, N]`` [N, N m] in body axes, sampled
        at ``t`` (interpolated as ``interpolation`` says), constant, or a function of
        time ``forces(time) -> (6,)``.
    commands : dict, optional
        Thruster name -> commands over ``t`` (array of n) or a constant; thrust is
        ``Thruster.thrust(n)`` [N] (forward/backward coefficients, efficiency, dead band,
        limits). Thrusters not named get command 0.
    current : (3,) array, (n, 3) array or callable, optional
        Water current in the earth-fixed NED frame [m/s] (north, east, down): constant,
        sampled at ``t``, or ``current(time) -> (3,)``. Irrotational (no angular part).
    eta0, nu0 : (6,) arrays, optional
        Initial pose [m, rad] and body velocity over ground [m/s, rad/s] (zeros).
    interpolation : {"previous", "linear"}
        How sampled inputs are held between samples: ``previous`` is a zero-order hold
        (the value at sample k applies on [t_k, t_{k+1}), like a controller's command);
        ``linear`` interpolates linearly between samples.
    rtol, atol : float
        Integrator tolerances (``solve_ivp``).
    method : str
        ``solve_ivp`` method (``RK45``, ``DOP853``, ``LSODA``...).
    max_step : float, optional
        Largest integrator step [s].
    extra_force : callable, optional
        ``extra_force(time, eta, nu, inputs) -> (6,)`` [N, N m], added to the right-hand
        side but not to the logged applied forces (an undeclared effect). ``inputs`` is
        a dict with ``commands`` (name -> command), ``thrust`` (name -> [N]), ``tau``
        (applied force, (6,)), ``nu_c`` (current in body axes, (6,)), ``nu_r`` ((6,)),
        ``model``, ``allocation`` (its thruster allocation matrix B, (6, n), computed once per
        run), ``columns`` (the ``channels`` at that time) and ``input_history`` (``(t,
        tau)``: the applied force at every sample, for effects with a memory of the inputs).
    effects : bool
        Apply ``model.effects`` (calibrated effects, :mod:`stripcoef.effects.laws`).
    munk : bool
        Keep the Munk moment in C_A (``HydroModel.coriolis``).
    channels : dict, optional
        Other logged signals over ``t`` (e.g. ``tether_length`` [m]) that effects read;
        held like the inputs and copied into the output log.
    controller : callable, optional
        Feedback: ``controller(time, eta, nu, commands) -> {thruster: command}`` is called at
        every sample with the state and the open-loop commands of that sample; the commands
        it returns replace them until the next sample (zero-order hold) and are logged (an
        autopilot, e.g. the heading autopilot of Indiveri 1998's heave trials).

    Returns
    -------
    Log
        Columns ``t``, ``x y z phi theta psi`` [m, rad], ``u v w p q r`` [m/s, rad/s]
        (over ground), ``X Y Z K M N`` (applied thrust + forces) [N, N m] and
        ``n_<thruster>`` for each commanded thruster.

    Raises
    ------
    InputError
        Bad time vector, wrong shapes, NaN inputs, unknown thruster names.
    UnreachableError
        The integration failed (the motion diverged).

    References
    ----------
    Fossen, Handbook of Marine Craft Hydrodynamics and Motion Control (2011), eqs. 7.190,
    10.1 and sec. 10.3 (current); Wang & Clark (Wang & Clark 2006), eqs. 1-2.
    """
    if interpolation not in INTERPOLATIONS:
        raise unknown_name("interpolation", interpolation, INTERPOLATIONS, key="interpolation")
    t = _as_time(t)
    n = t.size

    # --- inputs --------------------------------------------------------------
    thrusters = list(model.thrusters)
    names = [th.name for th in thrusters]
    cmd = np.zeros((n, len(thrusters)))
    commanded = []
    for name, values in (commands or {}).items():
        if name not in names:
            raise unknown_name("thruster", name, names, key=COMMAND_PREFIX + str(name))
        k = names.index(name)
        v = np.asarray(values, dtype=float)
        cmd[:, k] = np.full(n, float(v)) if v.ndim == 0 else _as_series(v, n, 1,
                                                                          COMMAND_PREFIX + name)
        if not np.all(np.isfinite(cmd[:, k])):
            raise InputError("NaN or infinite command", key=COMMAND_PREFIX + name,
                             expected="finite numbers")
        commanded.append(name)
    force_fn = None
    force_series = np.zeros((n, 6))
    if callable(forces):
        force_fn = forces
    elif forces is not None:
        force_series = _as_series(forces, n, 6, "forces")
    inputs_series = np.hstack([cmd, force_series])
    sampler = _Sampler(t, inputs_series, interpolation)
    current_fn = _current_function(current, t, interpolation)
    chan_names = list(channels or {})
    chan_sampler = None
    if chan_names:
        chan_series = np.column_stack([_as_series(channels[k], n, 1, k) for k in chan_names])
        chan_sampler = _Sampler(t, chan_series, interpolation)

    eta0 = np.zeros(6) if eta0 is None else _as_series(eta0, 1, 6, "eta0").reshape(6)
    nu0 = np.zeros(6) if nu0 is None else _as_series(nu0, 1, 6, "nu0").reshape(6)

    # --- model constants -----------------------------------------------------
    m_total = model.mass_matrix
    m_added = np.asarray(model.added_mass, dtype=float)
    try:
        m_inv = np.linalg.inv(m_total)
    except np.linalg.LinAlgError:
        raise InputError("singular mass matrix M_RB + M_A", key="model",
                         expected="a positive definite inertia matrix") from None
    alloc = model.allocation()
    effect_terms = []
    if effects and model.effects:
        from stripcoef.effects.laws import effect_forces  # calibrated effects (issue 7)
        effect_terms = effect_forces(model)
    nthr = len(thrusters)
    # the applied force at every sample (updated by a controller as it runs): effects with
    # a memory of the inputs (thruster lag, actuation delay) read it as ``input_history``
    tau_history = np.zeros((n, 6))
    if effect_terms or extra_force is not None:
        thr_all = (np.column_stack([np.asarray(th.thrust(cmd[:, k]), float).reshape(-1)
                                    for k, th in enumerate(thrusters)]) if nthr
                   else np.zeros((n, 0)))
        f_all = (np.array([np.asarray(force_fn(ti), float).reshape(6) for ti in t])
                 if force_fn else force_series)
        tau_history = (thr_all @ alloc.T if nthr else 0.0) + f_all

    hold = {"values": None}  # inputs held constant over a zero-order-hold segment

    def applied(time):
        vals = hold["values"] if hold["values"] is not None else sampler(time)
        c = vals[:nthr]
        thrust = np.array([th.thrust(ci) for th, ci in zip(thrusters, c)]) if nthr else c
        f = np.asarray(force_fn(time), dtype=float).reshape(6) if force_fn else vals[nthr:]
        tau = (alloc @ thrust if nthr else np.zeros(6)) + f
        return c, thrust, tau

    def rhs(time, y):
        eta, nu = y[:6], y[6:]
        c, thrust, tau = hold["applied"] if hold["values"] is not None else applied(time)
        nu_c = np.zeros(6)
        nu_c_dot = np.zeros(6)
        if current_fn is not None:
            vc_ned, dvc_ned = current_fn(time)
            rt = rotation_matrix(eta[3], eta[4], eta[5]).T
            vc = rt @ vc_ned
            nu_c[:3] = vc
            nu_c_dot[:3] = -skew(nu[3:]) @ vc + rt @ dvc_ned
        nu_r = nu - nu_c
        rhs_force = (tau
                     - model.coriolis(nu, added_mass=False) @ nu
                     - model.coriolis(nu_r, rigid_body=False, munk=munk) @ nu_r
                     - model.damping(nu_r) @ nu_r
                     - model.restoring(eta)
                     + m_added @ nu_c_dot)
        if effect_terms or extra_force is not None:
            inputs = {"commands": dict(zip(names, c)), "thrust": dict(zip(names, thrust)),
                      "tau": tau, "nu_c": nu_c, "nu_r": nu_r, "model": model,
                      "allocation": alloc, "input_history": (t, tau_history),
                      "columns": (dict(zip(chan_names, chan_sampler(time)))
                                  if chan_sampler is not None else {})}
            for term in effect_terms:
                rhs_force = rhs_force + term(time, eta, nu, inputs)
            if extra_force is not None:
                rhs_force = rhs_force + np.asarray(extra_force(time, eta, nu, inputs),
                                                   dtype=float).reshape(6)
        nu_dot = m_inv @ rhs_force
        eta_dot = kinematics(eta) @ nu
        return np.concatenate([eta_dot, nu_dot])

    # --- integrate, restarting at input discontinuities ----------------------
    if controller is not None:
        if interpolation != "previous" or force_fn is not None:
            raise InputError("a controller needs sampled inputs held between samples",
                             key="controller", expected="interpolation='previous' and "
                             "forces given as samples (not a function)")
        bounds = list(range(n))  # commands change at every sample
    elif interpolation == "previous" and force_fn is None:
        jumps = np.nonzero(np.any(np.diff(inputs_series, axis=0) != 0.0, axis=1))[0] + 1
        bounds = [0, *[int(j) for j in jumps], n - 1]
    else:
        bounds = [0, n - 1]
    y = np.concatenate([eta0, nu0])
    states = np.empty((n, 12))
    states[0] = y
    opts = {"rtol": rtol, "atol": atol, "method": method}
    if max_step is not None:
        opts["max_step"] = max_step
    def control(k, state):
        out = controller(t[k], state[:6].copy(), state[6:].copy(), dict(zip(names, cmd[k])))
        for name, value in dict(out).items():
            if name not in names:
                raise unknown_name("thruster", name, names, key="controller")
            value = float(value)
            if not np.isfinite(value):
                raise InputError("controller returned a non-finite command", key=name,
                                 value=value, expected="a finite command")
            cmd[k, names.index(name)] = value
            if name not in commanded:
                commanded.append(name)
        inputs_series[k, :nthr] = cmd[k]
        if effect_terms or extra_force is not None:
            thr_k = np.array([float(th.thrust(c)) for th, c in zip(thrusters, cmd[k])])
            tau_history[k] = (alloc @ thr_k if nthr else 0.0) + force_series[k]

    for a, b in zip(bounds[:-1], bounds[1:]):
        if b <= a:
            continue
        if controller is not None:
            control(a, y)
        # Hold the inputs of sample a over [t_a, t_b] (no jump inside the segment).
        hold["values"] = inputs_series[a] if interpolation == "previous" and force_fn is None \
            else None
        if hold["values"] is not None:
            hold["applied"] = applied(t[a])
        sol = solve_ivp(rhs, (t[a], t[b]), y, t_eval=t[a:b + 1], **opts)
        if sol.status != 0 or sol.y.shape[1] != b - a + 1 or not np.all(np.isfinite(sol.y)):
            raise UnreachableError(f"simulation failed between t = {t[a]:g} s and "
                                   f"{t[b]:g} s: {sol.message} (motion diverged?)")
        states[a:b + 1] = sol.y.T
        y = sol.y[:, -1]
        # at t_b the new inputs take over (zero-order hold), so the state carries on.

    if controller is not None:
        control(n - 1, y)  # the command issued at the last sample (logged)
    hold["values"] = None
    taus = np.array([applied(ti)[2] for ti in t])
    cols = {"t": t}
    for i, name in enumerate(POSE):
        cols[name] = states[:, i]
    for i, name in enumerate(VELOCITIES):
        cols[name] = states[:, 6 + i]
    for i, name in enumerate(FORCES):
        cols[name] = taus[:, i]
    for name in commanded:
        cols[COMMAND_PREFIX + name] = cmd[:, names.index(name)]
    for k, name in enumerate(chan_names):
        cols[name] = chan_series[:, k]
    meta = {"model": model.name, "interpolation": interpolation}
    if current is not None and not callable(current):
        meta["current"] = np.asarray(current, dtype=float).tolist()
    return Log(cols, source=f"simulate({model.name})", meta=meta)


def kinetic_energy(model, nu) -> np.ndarray:
    r"""Kinetic energy of the vehicle and its added mass.

    .. math:: T = \tfrac12 \nu^T (M_{RB} + M_A) \nu

    Parameters
    ----------
    model : HydroModel
    nu : (6,) or (n, 6) array
        Body velocity [m/s, rad/s]

    Returns
    -------
    float or (n,) array
        Kinetic energy [J]

    References
    ----------
    Fossen (2011), eq. 6.43 (kinetic energy of the fluid) and sec. 3.3.
    """
    nu = np.atleast_2d(np.asarray(nu, dtype=float))
    e = 0.5 * np.einsum("ni,ij,nj->n", nu, model.mass_matrix, nu)
    return e if e.size > 1 else float(e[0])
