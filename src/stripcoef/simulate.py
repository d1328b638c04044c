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
    - D(\nu_r)\nu_r - g(\eta) + M_A\dot\nu_c + u_r|u_r| B_\delta \delta

:math:`D(\nu_r)` includes the lift terms :math:`u_r L` (:meth:`HydroModel.damping`) and the
last term is the force of the control surfaces deflected by :math:`\delta` [rad]
(:meth:`HydroModel.control_force`; Prestero 2001, secs. 3.6-3.7).

The applied force :math:`\tau = B\,T(n) + \tau_{forces}` is the thrust of every
thruster through the allocation matrix ``B`` (``Thruster.thrust``: forward/backward
coefficients, efficiencies, dead band, limits) plus the given generalized forces.
:math:`\tau_{extra}` gathers the calibrated effects of the model
(``model.effects``, see :mod:`stripcoef.effects.laws`) and a user hook.

The state is integrated with :func:`scipy.integrate.solve_ivp`; with zero-order-hold
inputs the integration restarts at every sample where an input jumps, so the
integrator never steps across a discontinuity. The attitude is integrated as a unit
quaternion (Fossen 2011, eqs. 2.72 and 2.86; no singularity at +-90 deg of pitch); Euler
angles are only its output (:func:`pose`). :func:`simulate` is three pieces: the
inputs at any time (:class:`InputSampler`), the state equation (:class:`RightHandSide`)
and the integrator (:func:`integrate`); :func:`replay` runs it on a log's own inputs.
"""

from __future__ import annotations

from dataclasses import dataclass, field
import math
import time as _time
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from stripcoef.conventions import FORCES, POSE, VELOCITIES, skew
from stripcoef.errors import InputError, UnreachableError, unknown_name
from stripcoef.model import restoring_from_down, velocity_product
from stripcoef.logfile import COMMAND_PREFIX, DEFLECTION_PREFIX, Log, LogInputs, log_inputs
from stripcoef.progress import TimeBar

INTERPOLATIONS = ("previous", "linear")
#: Right-hand-side evaluations one simulation may spend (a smooth 100 s run of a shipped
#: vehicle takes ~6,000; a stiff or divergent one would take forever) [-].
MAX_EVALUATIONS = 1_000_000
#: CPU-time budget of one simulation [s] (:func:`time.process_time`; docs/simulate.md): past it
#: the run stops with an error saying where it got to, instead of grinding. CPU time, not the
#: wall clock, so that the verdict does not depend on what else the machine runs.
TIME_LIMIT = 120.0


class _OverBudget(Exception):
    """Raised inside the right-hand side to stop the integrator (converted below)."""

    def __init__(self, time, why):
        super().__init__(why)
        self.time, self.why = time, why


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
        k = int(np.searchsorted(t, time, side="right")) - 1   # min/max: np.clip of a
        if self.linear:                                         # scalar is slow
            k = min(max(k, 0), t.size - 2)
            s = (time - t[k]) / (t[k + 1] - t[k])
            s = min(max(s, 0.0), 1.0)
            return self.values[k] * (1.0 - s) + self.values[k + 1] * s
        return self.values[min(max(k, 0), t.size - 1)]

    def rate(self, time: float) -> np.ndarray:
        """Time derivative (piecewise constant for linear, zero for zero-order hold)."""
        if not self.linear:
            return np.zeros_like(self.values[0])
        t = self.t
        k = min(max(int(np.searchsorted(t, time, side="right")) - 1, 0), t.size - 2)
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


def _attitude_euler(rot) -> np.ndarray:
    """(phi, theta, psi) [rad] of Rotation(s) ``rot`` (zyx convention, Fossen 2011 eq. 2.18);
    at +-90 deg of pitch the angles are not unique and scipy's choice (psi = 0) is taken."""
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", UserWarning)       # "Gimbal lock detected"
        return rot.as_euler("ZYX")[..., ::-1]


def _matrix_euler(rmat, quat) -> np.ndarray:
    r"""(phi, theta, psi) [rad] of R = R_zyx (Fossen 2011 eq. 2.18):

    .. math:: \phi = \operatorname{atan2}(R_{32}, R_{33}),\quad \theta = -\arcsin R_{31},
              \quad \psi = \operatorname{atan2}(R_{21}, R_{11})

    (Fossen 2011, sec. 2.2.3, Euler angles from a unit quaternion); within 1e-9 of +-90 deg of
    pitch, where phi and psi are not unique, scipy's choice (:func:`_attitude_euler`).
    """
    s = -rmat[2, 0]
    if abs(s) > 1.0 - 1e-9:
        return _attitude_euler(Rotation.from_quat(quat))
    return np.array([np.arctan2(rmat[2, 1], rmat[2, 2]), np.arcsin(s),
                     np.arctan2(rmat[1, 0], rmat[0, 0])])


def attitude_quaternion(eta) -> np.ndarray:
    r"""The unit quaternion(s) (scipy's order: vector part, then scalar) of :math:`R(\Theta)`
    of a pose ``eta`` (6,) or poses (n, 6) = (x, y, z [m], phi, theta, psi [rad]): the
    zyx-convention rotation psi about z, then theta about y, then phi about x (Fossen 2011,
    eq. 2.18)."""
    return Rotation.from_euler("ZYX", np.asarray(eta, dtype=float)[..., 5:2:-1]).as_quat()


def state_vector(eta, nu) -> np.ndarray:
    r"""The integrated state :math:`x = [p;\ q;\ \nu]` (13,) of a pose ``eta`` = (x, y, z [m],
    phi, theta, psi [rad]) and a body velocity ``nu`` [m/s, rad/s]: position in NED, the unit
    quaternion of :math:`R(\Theta)` (:func:`attitude_quaternion`) and nu."""
    eta = np.asarray(eta, dtype=float)
    return np.concatenate([eta[:3], attitude_quaternion(eta), np.asarray(nu, dtype=float)])


def pose(states, eta0=None) -> np.ndarray:
    """Poses (n, 6) [m, rad] of integrated states (n, 13) (:func:`state_vector`): Euler angles
    from the quaternions, roll and heading made continuous in time (unwrapped, starting at
    ``eta0``'s angles: a heading that turns twice reads 4 pi)."""
    states = np.atleast_2d(states)
    angles = _attitude_euler(Rotation.from_quat(states[:, 3:7]))
    for i in (0, 2):
        a = np.unwrap(angles[:, i])
        start = 0.0 if eta0 is None else float(np.asarray(eta0, float)[3 + i])
        angles[:, i] = a + 2 * np.pi * np.round((start - a[0]) / (2 * np.pi))
    return np.column_stack([states[:, :3], angles])


class InputSampler:
    r"""The inputs of a run at any time: thruster commands, generalized forces, control-surface
    deflections, other channels and the water current, checked once and then held (zero-order
    hold) or interpolated between the samples ``t``.

    .. math:: \tau(t) = B\,T(n(t)) + \tau_{forces}(t)

    (:meth:`Thruster.thrust`; Fossen 2011 eq. 11.3, Wang & Clark 2006 eq. 6) [N, N m].
    ``history``: keep the applied force of every sample (``tau_history``) for effects with a
    memory of the inputs (thruster lag, actuation delay).
    """

    def __init__(self, model, t, *, forces, commands, deflections, channels, current,
                 interpolation, history):
        n = t.size
        self.t, self.model, self.interpolation = t, model, interpolation
        self.thrusters = thrusters = list(model.thrusters)
        self.names = names = [th.name for th in thrusters]
        self.cmd = cmd = np.zeros((n, len(thrusters)))
        self.commanded = []
        for name, values in (commands or {}).items():
            if name not in names:
                raise unknown_name("thruster", name, names, key=COMMAND_PREFIX + str(name))
            k = names.index(name)
            v = np.asarray(values, dtype=float)
            cmd[:, k] = np.full(n, float(v)) if v.ndim == 0 else _as_series(
                v, n, 1, COMMAND_PREFIX + name)
            if not np.all(np.isfinite(cmd[:, k])):
                raise InputError("NaN or infinite command", key=COMMAND_PREFIX + name,
                                 expected="finite numbers")
            self.commanded.append(name)
        self.surfaces = surfaces = list(getattr(model, "control_surfaces", ()))
        self.snames = snames = [sf.name for sf in surfaces]
        self.defl = defl = np.zeros((n, len(surfaces)))
        self.deflected = []
        for name, values in (deflections or {}).items():
            if name not in snames:
                raise unknown_name("control surface", name, snames,
                                   key=DEFLECTION_PREFIX + str(name))
            k = snames.index(name)
            v = np.asarray(values, dtype=float)
            defl[:, k] = np.full(n, float(v)) if v.ndim == 0 else _as_series(
                v, n, 1, DEFLECTION_PREFIX + name)
            lim = surfaces[k].max_deflection
            bad = np.nonzero(~(np.abs(defl[:, k]) <= lim * (1 + 1e-12)))[0]
            if bad.size:
                raise InputError(
                    f"deflection beyond the limit at sample {int(bad[0])}",
                    key=DEFLECTION_PREFIX + name, value=float(defl[bad[0], k]),
                    expected=f"|delta| <= {lim:.6g} rad ({np.degrees(lim):.4g} deg, "
                             f"stall at {np.degrees(surfaces[k].stall_angle):.4g} deg)")
            self.deflected.append(name)
        self.force_fn = None
        self.force_series = np.zeros((n, 6))
        if callable(forces):
            self.force_fn = forces
        elif forces is not None:
            self.force_series = _as_series(forces, n, 6, "forces")
        self.series = np.hstack([cmd, self.force_series, defl])
        self.sampler = _Sampler(t, self.series, interpolation)
        self.current_fn = _current_function(current, t, interpolation)
        self.chan_names = list(channels or {})
        self.chan_sampler = None
        if self.chan_names:
            self.chan_series = np.column_stack([_as_series(channels[k], n, 1, k)
                                                for k in self.chan_names])
            self.chan_sampler = _Sampler(t, self.chan_series, interpolation)
        self.nthr = nthr = len(thrusters)
        self.alloc = alloc = model.allocation()
        self.history = history
        # the applied force at every sample (updated by a controller as it runs)
        self.tau_history = np.zeros((n, 6))
        if history:
            thr_all = (np.column_stack([np.asarray(th.thrust(cmd[:, k]), float).reshape(-1)
                                        for k, th in enumerate(thrusters)]) if nthr
                       else np.zeros((n, 0)))
            f_all = (np.array([np.asarray(self.force_fn(ti), float).reshape(6) for ti in t])
                     if self.force_fn else self.force_series)
            self.tau_history = (thr_all @ alloc.T if nthr else 0.0) + f_all
        self.values = None  # the inputs held constant over a zero-order-hold segment
        self.held = None

    @property
    def held_between_samples(self) -> bool:
        """Zero-order hold of sampled inputs (no force function): inputs jump only at samples."""
        return self.interpolation == "previous" and self.force_fn is None

    def segments(self) -> list:
        """Sample indices where a held input jumps (with the first and the last): the
        integrator restarts there and never steps across a discontinuity."""
        n = self.t.size
        if self.held_between_samples:
            jumps = np.nonzero(np.any(np.diff(self.series, axis=0) != 0.0, axis=1))[0] + 1
            return [0, *[int(j) for j in jumps], n - 1]
        return [0, n - 1]

    def applied(self, time):
        """(commands, thrust [N], tau [N, N m], deflections [rad]) at ``time``."""
        vals = self.values if self.values is not None else self.sampler(time)
        nthr = self.nthr
        c = vals[:nthr]
        thrust = np.array([th.thrust(ci) for th, ci in zip(self.thrusters, c)]) if nthr else c
        f = np.asarray(self.force_fn(time), dtype=float).reshape(6) if self.force_fn \
            else vals[nthr:nthr + 6]
        tau = (self.alloc @ thrust if nthr else np.zeros(6)) + f
        return c, thrust, tau, vals[nthr + 6:]

    def __call__(self, time):
        """The inputs at ``time``: those held over the segment, else sampled."""
        return self.held if self.values is not None else self.applied(time)

    def hold(self, k: int) -> None:
        """Hold the inputs of sample k over the next segment (zero-order hold), or sample them
        at every time (interpolated inputs, a force function)."""
        self.values = self.series[k] if self.held_between_samples else None
        if self.values is not None:
            self.held = self.applied(self.t[k])

    def release(self) -> None:
        self.values = None

    def channels(self, time) -> dict:
        return dict(zip(self.chan_names, self.chan_sampler(time))) \
            if self.chan_sampler is not None else {}

    def commands_at(self, k: int) -> dict:
        return dict(zip(self.names, self.cmd[k]))

    def command(self, k: int, commands) -> None:
        """Replace the commands of sample k (a controller's), checked; logged."""
        names = self.names
        for name, value in dict(commands).items():
            if name not in names:
                raise unknown_name("thruster", name, names, key="controller")
            value = float(value)
            if not np.isfinite(value):
                raise InputError("controller returned a non-finite command", key=name,
                                 value=value, expected="a finite command")
            self.cmd[k, names.index(name)] = value
            if name not in self.commanded:
                self.commanded.append(name)
        self.series[k, :self.nthr] = self.cmd[k]
        if self.history:
            thr_k = np.array([float(th.thrust(c)) for th, c in zip(self.thrusters, self.cmd[k])])
            self.tau_history[k] = (self.alloc @ thr_k if self.nthr else 0.0) \
                + self.force_series[k]


class RightHandSide:
    r"""The state equation :math:`\dot x = f(t, x)` of :math:`x = [p;\ q;\ \nu]` (position
    in NED, unit quaternion, body velocity: :func:`state_vector`; module docstring; Fossen 2011
    eqs. 2.86, 7.190, 10.1, sec. 10.3):

    .. math::
        \dot\nu = M^{-1}\big(\tau + \tau_{extra} - C_{RB}(\nu)\nu - C_A(\nu_r)\nu_r
        - D(\nu_r)\nu_r - g(\eta) + M_A\dot\nu_c + u_r|u_r| B_\delta\delta\big),
        \qquad \dot p = R(q)\,v, \qquad
        \dot\varepsilon = \tfrac12 (q_0 I + S(\varepsilon))\,\omega,\quad
        \dot q_0 = -\tfrac12 \varepsilon^T\omega

    [m/s, rad/s, m/s^2, rad/s^2].
    """

    def __init__(self, model, inputs: InputSampler, *, effects=True, munk=True, coriolis=True,
                 extra_force=None):
        self.model, self.inputs = model, inputs
        self.munk, self.coriolis, self.extra_force = munk, coriolis, extra_force
        self.m_added = np.asarray(model.added_mass, dtype=float)
        try:
            self.m_inv = np.linalg.inv(model.mass_matrix)
        except np.linalg.LinAlgError:
            raise InputError("singular mass matrix M_RB + M_A", key="model",
                             expected="a positive definite inertia matrix") from None
        self.b_delta = model.control_matrix if inputs.surfaces else None
        # the model's matrices and restoring constants read once per run, not per evaluation
        # floats: the restoring force's arithmetic on numpy scalars cost a tenth of f
        self.gravity = {"weight": float(model.weight), "buoyancy": float(model.buoyancy),
                        "r_g": tuple(map(float, model.r_g)), "r_b": tuple(map(float, model.r_b))}
        # HydroModel.velocity_forces' tables for these options, read once: (table, D_L) of
        # the still-water rule, of the water-relative terms and of C_RB on nu (with a current)
        self.terms_still = model._velocity_terms(coriolis, coriolis, munk and coriolis, True)
        self.terms_water = model._velocity_terms(False, coriolis, munk and coriolis, True)
        self.terms_body = model._velocity_terms(True, False, munk, False) if coriolis else None
        self.effect_terms = []
        if effects and model.effects:
            from stripcoef.effects.laws import effect_forces  # calibrated effects (issue 7)
            self.effect_terms = effect_forces(model)

    def current(self, time, rmat, nu):
        """(nu_c, d nu_c/dt): the current in body axes and its rate [m/s, m/s^2]; ``rmat`` is
        R, body to NED."""
        nu_c = np.zeros(6)
        nu_c_dot = np.zeros(6)
        if self.inputs.current_fn is not None:
            vc_ned, dvc_ned = self.inputs.current_fn(time)
            rt = rmat.T
            vc = rt @ vc_ned
            nu_c[:3] = vc
            nu_c_dot[:3] = -skew(nu[3:]) @ vc + rt @ dvc_ned
        return nu_c, nu_c_dot

    def __call__(self, time, y):
        # floats, not 3-vectors: numpy's call overhead (~1 us) dwarfs a 3 x 3 product; the
        # velocity forces' tables are the model's, read once (docs/performance.md)
        model, inputs = self.model, self.inputs
        quat, nu = y[3:7], y[7:]
        e1, e2, e3, q0, u, v, w, p, q, r = y[3:].tolist()
        # R(q), eq. 2.72, of the normalised q (the integrator's drift of |q|)
        norm = math.sqrt(e1 * e1 + e2 * e2 + e3 * e3 + q0 * q0)
        x_, y_, z_, w_ = e1 / norm, e2 / norm, e3 / norm, q0 / norm
        r00, r01, r02 = 1 - 2 * (y_ * y_ + z_ * z_), 2 * (x_ * y_ - z_ * w_), 2 * (x_ * z_ + y_ * w_)
        r10, r11, r12 = 2 * (x_ * y_ + z_ * w_), 1 - 2 * (x_ * x_ + z_ * z_), 2 * (y_ * z_ - x_ * w_)
        r20, r21, r22 = 2 * (x_ * z_ - y_ * w_), 2 * (y_ * z_ + x_ * w_), 1 - 2 * (x_ * x_ + y_ * y_)
        rmat = None
        c, thrust, tau, delta = inputs(time)
        if inputs.current_fn is None:
            nu_c, nu_r = _ZERO6, nu
            # C_RB(nu) nu + C_A(nu) nu + D(nu) nu, lift included (HydroModel.velocity_forces)
            rhs_force = tau - velocity_product(*self.terms_still, nu)
        else:
            rmat = np.array([[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]])
            nu_c, nu_c_dot = self.current(time, rmat, nu)
            nu_r = nu - nu_c
            rhs_force = tau + self.m_added @ nu_c_dot
            # C_RB(nu) nu + C_A(nu_r) nu_r + D(nu_r) nu_r (HydroModel.velocity_forces)
            vel = velocity_product(*self.terms_water, nu_r)
            if self.terms_body is not None:
                vel = vel + velocity_product(*self.terms_body, nu)
            rhs_force = rhs_force - vel
        rhs_force = rhs_force - restoring_from_down((r20, r21, r22), **self.gravity)
        if self.b_delta is not None:
            rhs_force = rhs_force + nu_r[0] * abs(nu_r[0]) * (self.b_delta @ delta)
        if self.effect_terms or self.extra_force is not None:
            if rmat is None:
                rmat = np.array([[r00, r01, r02], [r10, r11, r12], [r20, r21, r22]])
            eta = np.concatenate([y[:3], _matrix_euler(rmat, quat)])
            names = inputs.names
            hook = {"commands": dict(zip(names, c)), "thrust": dict(zip(names, thrust)),
                    "tau": tau, "nu_c": nu_c, "nu_r": nu_r, "model": model,
                    "allocation": inputs.alloc, "input_history": (inputs.t, inputs.tau_history),
                    "columns": inputs.channels(time)}
            for term in self.effect_terms:
                rhs_force = rhs_force + term(time, eta, nu, hook)
            if self.extra_force is not None:
                rhs_force = rhs_force + np.asarray(self.extra_force(time, eta, nu, hook),
                                                   dtype=float).reshape(6)
        # p_dot = R v; eps_dot = (q0 w + eps x w) / 2; q0_dot = -eps . w / 2 (eq. 2.86)
        return np.array([r00 * u + r01 * v + r02 * w, r10 * u + r11 * v + r12 * w,
                         r20 * u + r21 * v + r22 * w,
                         0.5 * (q0 * p + e2 * r - e3 * q), 0.5 * (q0 * q + e3 * p - e1 * r),
                         0.5 * (q0 * r + e1 * q - e2 * p), -0.5 * (e1 * p + e2 * q + e3 * r),
                         *(self.m_inv @ rhs_force).tolist()])


_ZERO6 = np.zeros(6)
_ZERO6.flags.writeable = False


def integrate(f, t, y0, bounds, *, start_segment=None, rtol=1e-8, atol=1e-10, method="RK45",
              max_step=None, max_evaluations=MAX_EVALUATIONS, time_limit=TIME_LIMIT,
              desc="simulate") -> np.ndarray:
    r"""States ``(n, len(y0))`` of :math:`\dot y = f(t, y)` at the times ``t``, integrated by
    :func:`scipy.integrate.solve_ivp` segment by segment between the sample indices ``bounds``
    (the inputs jump only there), ``start_segment(k, y)`` called at the start of each; within
    ``max_evaluations`` evaluations of f and ``time_limit`` seconds of this process's CPU time
    (:func:`time.process_time`, not the wall clock: a machine loaded by other work must not stop
    a run that the same machine finishes idle), else an
    :class:`~stripcoef.errors.UnreachableError` saying where it got to.
    """
    n = t.size
    y = np.asarray(y0, dtype=float)
    states = np.empty((n, y.size))
    states[0] = y
    spent = {"evaluations": 0}
    deadline = _time.process_time() + time_limit if np.isfinite(time_limit) else None
    clock = TimeBar(t[0], t[-1], desc=desc)

    def budgeted(time, y):
        """f within the evaluation and CPU-time budgets, and finite."""
        spent["evaluations"] += 1
        if spent["evaluations"] > max_evaluations:
            raise _OverBudget(time, f"over the budget of {max_evaluations} right-hand-side "
                                    "evaluations")
        if deadline is not None and spent["evaluations"] % 64 == 0 \
                and _time.process_time() > deadline:
            raise _OverBudget(time, f"over the time budget of {time_limit:g} s")
        clock.advance(time)
        out = f(time, y)
        if not math.isfinite(out.sum()):       # inf or NaN in any entry (np.all: 3 us more)
            raise _OverBudget(time, "the state or its rate is no longer finite (the motion "
                                    "diverged)")
        return out

    opts = {"rtol": rtol, "atol": atol, "method": method}
    if max_step is not None:
        opts["max_step"] = max_step
    for a, b in zip(bounds[:-1], bounds[1:]):
        if b <= a:
            continue
        if start_segment is not None:
            start_segment(a, y)
        try:
            sol = solve_ivp(budgeted, (t[a], t[b]), y, t_eval=t[a:b + 1], **opts)
        except _OverBudget as stop:
            raise UnreachableError(
                f"t = {stop.time:.6g} s: simulation stopped, {stop.why}; got "
                f"{len(bounds) - 1} input segments, {n} samples over {t[0]:g}..{t[-1]:g} s; "
                "expected a run that is not stiff or divergent (check the mass, inertia, "
                "damping and current)") from None
        if sol.status != 0 or sol.y.shape[1] != b - a + 1 or not np.all(np.isfinite(sol.y)):
            raise UnreachableError(f"t = {t[a]:g}..{t[b]:g} s: simulation failed "
                                   f"({sol.message}); expected a motion that stays finite "
                                   "(did it diverge?)")
        states[a:b + 1] = sol.y.T
        y = sol.y[:, -1]
        # at t_b the new inputs take over (zero-order hold), so the state carries on.
    clock.close()
    return states


def simulate(model, t, *, forces=None, commands=None, current=None, eta0=None, nu0=None,
             interpolation: str = "previous", rtol: float = 1e-8, atol: float = 1e-10,
             method: str = "RK45", max_step: float | None = None,
             extra_force: Callable | None = None, effects: bool = True,
             munk: bool = True, coriolis: bool = True, channels: dict | None = None,
             controller: Callable | None = None, deflections: dict | None = None,
             max_evaluations: int = MAX_EVALUATIONS, time_limit: float | None = None) -> Log:
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
        Integrator tolerances (``solve_ivp``): 1e-13 <= rtol < 1, atol > 0.
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
    coriolis : bool
        Keep :math:`C_{RB}(\nu)\nu + C_A(\nu_r)\nu_r` (``False`` drops both, as the limits'
        ``coriolis=False`` does).
    channels : dict, optional
        Other logged signals over ``t`` (e.g. ``tether_length`` [m]) that effects read;
        held like the inputs and copied into the output log.
    deflections : dict, optional
        Control surface name -> deflection over ``t`` (array of n) or a constant [rad]; its
        force is :math:`u_r|u_r| b\,\delta` (:meth:`HydroModel.control_force`). A deflection
        beyond the surface's ``max_deflection`` is an error. Surfaces not named stay at 0.
    controller : callable, optional
        Feedback: ``controller(time, eta, nu, commands) -> {thruster: command}`` is called at
        every sample with the state and the open-loop commands of that sample; the commands
        it returns replace them until the next sample (zero-order hold) and are logged (an
        autopilot, e.g. the heading autopilot of Indiveri 1998's heave trials).
    max_evaluations : int
        Budget of right-hand-side evaluations (:data:`MAX_EVALUATIONS`).
    time_limit : float, optional
        Wall-clock budget [s] (default :data:`TIME_LIMIT`; ``inf``: none). A stiff or divergent run
        (a tiny mass, a huge current, a non-finite force) stops with an
        :class:`~stripcoef.errors.UnreachableError` saying where it got to and why.

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
    for key, value, ok, expected in (
            ("rtol", rtol, lambda v: 1e-13 <= v < 1.0, "a relative tolerance from 1e-13 to < 1"),
            ("atol", atol, lambda v: 0.0 < v < np.inf, "an absolute tolerance > 0"),
            ("max_evaluations", max_evaluations, lambda v: v >= 1, "a budget >= 1"),
            ("time_limit", TIME_LIMIT if time_limit is None else time_limit, lambda v: v > 0,
             "a time budget > 0 [s]")):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.number)) \
                or np.isnan(value) or (key != "time_limit" and np.isinf(value)) or not ok(value):
            raise InputError("invalid integrator setting", key=key, value=value,
                             expected=expected)
    t = _as_time(t)
    history = bool((effects and model.effects) or extra_force is not None)
    inputs = InputSampler(model, t, forces=forces, commands=commands, deflections=deflections,
                          channels=channels, current=current, interpolation=interpolation,
                          history=history)
    eta0 = np.zeros(6) if eta0 is None else _as_series(eta0, 1, 6, "eta0").reshape(6)
    nu0 = np.zeros(6) if nu0 is None else _as_series(nu0, 1, 6, "nu0").reshape(6)
    f = RightHandSide(model, inputs, effects=effects, munk=munk, coriolis=coriolis,
                      extra_force=extra_force)
    if controller is not None and not inputs.held_between_samples:
        raise InputError("a controller needs sampled inputs held between samples",
                         key="controller", expected="interpolation='previous' and "
                         "forces given as samples (not a function)")

    def start_segment(k, state):
        """At sample k: the controller's commands, then the inputs held over the segment."""
        if controller is not None:
            inputs.command(k, controller(t[k], pose(state)[0], state[7:].copy(),
                                         inputs.commands_at(k)))
        inputs.hold(k)

    bounds = list(range(t.size)) if controller is not None else inputs.segments()
    states = integrate(f, t, state_vector(eta0, nu0), bounds, start_segment=start_segment,
                       rtol=rtol, atol=atol, method=method, max_step=max_step,
                       max_evaluations=max_evaluations,
                       time_limit=TIME_LIMIT if time_limit is None else float(time_limit),
                       desc=f"simulate {model.name}")
    if controller is not None:   # the command issued at the last sample (logged)
        last = states[-1]
        inputs.command(t.size - 1, controller(t[-1], pose(last)[0], last[7:].copy(),
                                              inputs.commands_at(t.size - 1)))
    if inputs.surfaces:
        _check_stall(inputs.surfaces, states[:, 7:], inputs.defl, t, inputs.current_fn is not None)
    inputs.release()
    states = np.column_stack([pose(states, eta0), states[:, 7:]])
    return _motion_log(model, inputs, states, current=current, interpolation=interpolation)


def _motion_log(model, inputs, states, *, current, interpolation) -> Log:
    """The log of a run: pose, velocities, applied forces (at the sample times), commands,
    deflections and channels."""
    t = inputs.t
    taus = np.array([inputs.applied(ti)[2] for ti in t])
    cols = {"t": t}
    for i, name in enumerate(POSE):
        cols[name] = states[:, i]
    for i, name in enumerate(VELOCITIES):
        cols[name] = states[:, 6 + i]
    for i, name in enumerate(FORCES):
        cols[name] = taus[:, i]
    for name in inputs.commanded:
        cols[COMMAND_PREFIX + name] = inputs.cmd[:, inputs.names.index(name)]
    for name in inputs.deflected:
        cols[DEFLECTION_PREFIX + name] = inputs.defl[:, inputs.snames.index(name)]
    for k, name in enumerate(inputs.chan_names):
        cols[name] = inputs.chan_series[:, k]
    meta = {"model": model.name, "interpolation": interpolation}
    if current is not None and not callable(current):
        meta["current"] = np.asarray(current, dtype=float).tolist()
    return Log(cols, source=f"simulate({model.name})", meta=meta)


def effective_angle(surface, nu_r, delta) -> np.ndarray:
    r"""Effective angle of attack of a control surface [rad].

    .. math:: \alpha_e = \sigma\delta - \frac{b^T\nu_r}{b_e\,u_r},\qquad
              \sigma = \operatorname{sign}(b_e)

    with b the surface's derivative column and b_e its lift-direction entry (Y for a rudder,
    Z for an elevator): :math:`b^T\nu_r / b_e` is the area-weighted cross velocity of its
    panels at their quarter chords (Prestero 2001, sec. 3.7; docs/theory.md sec. 8).
    ``nu_r`` (n, 6) [m/s, rad/s], ``delta`` (n,) [rad]; NaN where u_r = 0.
    """
    b = np.asarray(surface.derivative, dtype=float)
    row = 1 if surface.kind == "rudder" else 2
    be = b[row]
    nu_r = np.atleast_2d(nu_r)
    u = nu_r[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        cross = (nu_r @ b) / be
        return np.where(u != 0.0, np.sign(be) * np.asarray(delta) - cross / u, np.nan)


#: The stall check reads a surface's angle of attack only where |u| is at least this fraction of
#: the run's largest |u| [-] and at least :data:`STALL_MIN_SPEED`: the fin force scales with u^2
#: (Prestero 2001, sec. 3.7), so below them it is under 1 % of its force at the run's top speed
#: (0.5 % of it at 1.5 m/s, REMUS's cruise), and as u -> 0 the angle of attack -v_f/u is
#: undefined (issue 37: 101.5 deg reported for an undeflected elevator at u ~ 0).
STALL_SPEED_FRACTION = 0.1
STALL_MIN_SPEED = 0.1   # [m/s]


def _check_stall(surfaces, nu, defl, t, with_current: bool) -> None:
    r"""Warn (ModelWarning) when a surface's effective angle of attack passes its stall angle:
    the linear lift law is then extrapolated (docs/theory.md sec. 8). With a current, the
    angle is computed on the velocity over ground (an approximation, said in the message).
    Only where the vehicle moves (:data:`STALL_SPEED_FRACTION`), and as the flow angle at the
    surface, :math:`\sigma\delta - \arctan(v_f/u)` [rad], of which :func:`effective_angle`'s
    :math:`\sigma\delta - v_f/u` is the small-angle form (the angle stays within 90 deg + |delta|
    however slow the vehicle; the stall angle is a flow angle)."""
    import warnings

    from stripcoef.errors import ModelWarning

    speed = np.abs(nu[:, 0])
    moving = speed >= max(STALL_MIN_SPEED, STALL_SPEED_FRACTION * float(np.max(speed, initial=0.0)))
    for k, sf in enumerate(surfaces):
        lead = np.sign(sf.derivative[1 if sf.kind == "rudder" else 2]) * defl[:, k]
        a = lead - np.arctan(lead - effective_angle(sf, nu, defl[:, k]))
        a = np.where(moving, np.abs(a), 0.0)
        if np.nanmax(a, initial=0.0) > sf.stall_angle:
            i = int(np.nanargmax(a))
            warnings.warn(f"control surface {sf.name!r}: effective angle of attack "
                          f"{np.degrees(a[i]):.1f} deg at t = {t[i]:g} s (u = {nu[i, 0]:.3g} m/s) "
                          "exceeds its stall "
                          f"angle {np.degrees(sf.stall_angle):.1f} deg; the linear lift is "
                          "extrapolated there" + (" (angle from the velocity over ground)"
                                                   if with_current else ""),
                          ModelWarning, stacklevel=3)


#: Bounds beyond which a simulated motion is reported as diverging (no underwater vehicle moves
#: this fast; a pitch or roll past them means it looped or capsized).
DIVERGENCE_SPEED = 20.0          # [m/s], each linear velocity
DIVERGENCE_RATE = 20.0           # [rad/s], each angular velocity
DIVERGENCE_ATTITUDE = np.pi / 2  # [rad], |roll| or |pitch|


@dataclass(frozen=True)
class MotionSummary:
    """What a simulated (or logged) motion did, for a one-look summary.

    Attributes
    ----------
    duration : float [s]
    final_velocity : (6,) [m/s, rad/s], body axes over ground (u v w p q r at the last sample)
    final_speed : float [m/s], |(u, v, w)| at the last sample
    distance : float [m], path length over ground (sum of |delta (x, y, z)|)
    displacement : (3,) [m], (x, y, z) at the end minus at the start (NED)
    heading_change : float [rad], unwrapped psi(end) - psi(start)
    max_roll, max_pitch : float [rad], largest |phi| and |theta|
    warnings : tuple of str
        The state diverged (a speed, rate or attitude beyond :data:`DIVERGENCE_SPEED`,
        :data:`DIVERGENCE_RATE`, :data:`DIVERGENCE_ATTITUDE`) or the heading ran away (more
        than one full turn while the applied yaw moment averaged out: see
        :func:`summarize_motion`).
    """

    duration: float
    final_velocity: np.ndarray
    final_speed: float
    distance: float
    displacement: np.ndarray
    heading_change: float
    max_roll: float
    max_pitch: float
    warnings: tuple = field(default=())


def summarize_motion(log: Log, *, model=None, munk: bool = True) -> MotionSummary:
    r"""Summary of a motion log (columns ``t``, ``x y z phi theta psi``, ``u .. r``; ``N`` if
    logged) and the warnings it deserves.

    Heading runaway: the unwrapped heading turned more than :math:`2\pi` while the yaw moment
    put on the vehicle averaged out, :math:`|\int N_a\,dt| \le 0.1 \int |N_a|\,dt`, with
    :math:`N_a = N + u|u|\,(B_\delta\delta)_6` the applied yaw moment and, given ``model``,
    that of its deflected control surfaces (log columns ``delta_<surface>``; Prestero 2001,
    sec. 3.7; u over ground): a straight run that spins, for a finless body the Munk moment
    :math:`(Y_{\dot v} - X_{\dot u})\,u v` makes yaw unstable (Fossen 2011 sec. 6.5). A
    commanded turn (a steady moment, a held rudder) is no runaway, and a run without the Munk
    moment (``munk=False``) gets no such warning. Capsized or looped: the body z axis tilted
    more than 90 deg from the vertical, :math:`\cos\phi\cos\theta < 0` (whatever Euler angles
    represent the attitude). Divergence: see :class:`MotionSummary`. Units: [s, m, rad, m/s,
    rad/s, N m].
    """
    t = log.require("t")
    pose = np.column_stack([log.get(k, np.zeros(len(log))) for k in POSE])
    nu = log.velocities()
    psi = np.unwrap(pose[:, 5])
    heading = float(psi[-1] - psi[0])
    steps = np.linalg.norm(np.diff(pose[:, :3], axis=0), axis=1)
    wrap = (pose[:, 3:5] + np.pi) % (2 * np.pi) - np.pi
    summary = dict(duration=float(t[-1] - t[0]), final_velocity=nu[-1].copy(),
                   final_speed=float(np.linalg.norm(nu[-1, :3])), distance=float(steps.sum()),
                   displacement=pose[-1, :3] - pose[0, :3], heading_change=heading,
                   max_roll=float(np.max(np.abs(wrap[:, 0]))),
                   max_pitch=float(np.max(np.abs(wrap[:, 1]))))
    warn = []
    speed = np.max(np.abs(nu[:, :3]))
    rate = np.max(np.abs(nu[:, 3:]))
    if speed > DIVERGENCE_SPEED or rate > DIVERGENCE_RATE:
        warn.append(f"the state diverges: speeds reach {speed:.3g} m/s and rates "
                    f"{rate:.3g} rad/s (limits {DIVERGENCE_SPEED:g} m/s, {DIVERGENCE_RATE:g} "
                    "rad/s): check the model's damping and the inputs")
    tilt = float(np.max(np.arccos(np.clip(np.cos(pose[:, 3]) * np.cos(pose[:, 4]), -1, 1))))
    if tilt > DIVERGENCE_ATTITUDE:
        warn.append(f"the vehicle capsized or looped: its z axis tilted {np.degrees(tilt):.3g} "
                    f"deg from the vertical (max |roll| {summary['max_roll']:.3g} rad, "
                    f"max |pitch| {summary['max_pitch']:.3g} rad; beyond "
                    f"{DIVERGENCE_ATTITUDE:.3g} rad): check the CG/CB (metacentric height)")
    yaw = log.get("N")
    control = control_moments(log, model)
    if control is not None:
        yaw = control[:, 5] if yaw is None else yaw + control[:, 5]
    dt = np.diff(t)
    net = abs(np.sum(0.5 * (yaw[1:] + yaw[:-1]) * dt)) if yaw is not None else 0.0
    total = np.sum(0.5 * (np.abs(yaw[1:]) + np.abs(yaw[:-1])) * dt) if yaw is not None else 0.0
    forces = log.forces()
    scale = 1e-9 * (float(t[-1] - t[0])) * max(1.0, np.max(np.abs(forces)) if forces is not None
                                               else 1.0)      # round-off of a zero moment
    if munk and abs(heading) > 2 * np.pi and net <= 0.1 * total + scale:
        warn.append(f"the heading runs away: it turned {heading:.4g} rad "
                    f"({abs(heading) / (2 * np.pi):.1f} turns) while the applied yaw moment "
                    + ("(control surfaces included) " if control is not None else "")
                    + "averaged out; a finless body is directionally unstable (Munk moment): "
                    "compare without it (munk=False)")
    return MotionSummary(**summary, warnings=tuple(warn))


def control_moments(log: Log, model) -> np.ndarray | None:
    r"""Forces of the deflected control surfaces along a log [N, N m], (n, 6):

    .. math:: \tau_\delta = u|u|\,B_\delta\,\delta

    with u the logged surge velocity (over ground: with a current an approximation) and
    ``delta_<surface>`` the logged deflections [rad]; None without a model, surfaces or
    deflections (:meth:`HydroModel.control_force`; Prestero 2001, sec. 3.7).
    """
    surfaces = [sf.name for sf in getattr(model, "control_surfaces", ())] if model else []
    defl = log.deflections()
    if not surfaces or not any(k in surfaces for k in defl):
        return None
    delta = np.column_stack([defl.get(k, np.zeros(len(log))) for k in surfaces])
    u = log.velocities()[:, 0]
    return (u * np.abs(u))[:, None] * (delta @ np.asarray(model.control_matrix, float).T)


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


def initial_state(log, index: int = 0) -> tuple:
    """The logged state at row ``index``: pose eta0 [m, rad], body velocity nu0 [m/s, rad/s]
    and the names of the pose and velocity columns the log lacks (taken as 0: the caller says
    so). The start of a free simulation from a log (Fossen 2011, eq. 7.190: the state
    (eta, nu) fixes the motion for given inputs)."""
    eta0 = np.array([float(log.columns[c][index]) if c in log else 0.0 for c in POSE])
    nu0 = np.array([float(log.columns[c][index]) if c in log else 0.0 for c in VELOCITIES])
    missing = [c for c in POSE + VELOCITIES if c not in log]
    return eta0, nu0, missing


def free_run_errors(log, prediction) -> dict:
    r"""RMS error of a free simulation against the log it started from, per logged velocity.

    .. math:: e_i = \sqrt{\tfrac1n \textstyle\sum_k (\nu_{i,k}^{log} - \nu_{i,k}^{sim})^2},
              \quad e_i^{hold} = \sqrt{\tfrac1n \textstyle\sum_k (\nu_{i,k}^{log}
              - \nu_{i,0}^{log})^2}

    with the trivial predictor "hold the initial velocity" as the reference a model must
    beat [m/s, rad/s]. ``prediction`` is the simulated log on the same times.

    Returns
    -------
    dict
        velocity name -> {"rms": e, "hold_initial_rms": e_hold}
    """
    out = {}
    for c in VELOCITIES:
        if c in log:
            v = log.columns[c]
            out[c] = {"rms": float(np.sqrt(np.mean((v - prediction.columns[c]) ** 2))),
                      "hold_initial_rms": float(np.sqrt(np.mean((v - v[0]) ** 2)))}
    return out


# --- log replay: the one rule ------------------------------------------------------------------

def replay(model, log, *, inputs: LogInputs | None = None, **options) -> Log:
    r"""Free simulation of ``model`` from the state logged at the first row of ``log``
    (:func:`initial_state`) with the log's inputs (:func:`log_inputs`, or ``inputs``, e.g.
    another file's resampled with :meth:`LogInputs.at`), at the inputs' times.

    .. math:: \hat x(t) = x(t_0) + \int_{t_0}^{t} f(\hat x, u_{log}(s))\,ds

    ``options`` go to :func:`simulate` (``rtol``, ``interpolation``, ``current``, ``munk``...).
    A log written by :func:`simulate` and replayed with its model and settings gives its states
    back to the integrator's tolerance (tests/test_replay.py).

    References
    ----------
    Fossen (2011), eq. 7.190 (the state fixes the motion for given inputs); Ljung, System
    Identification (1999), sec. 16.4 (simulation from measured inputs).
    """
    inputs = log_inputs(log, model) if inputs is None else inputs
    eta0, nu0, _ = initial_state(log)
    return simulate(model, inputs.t, eta0=eta0, nu0=nu0, **inputs.simulate_inputs(), **options)
