r"""Log windows: the generalized force a model misses, averaged over windows of a log.

The one-step (window) form of the equations of motion (Wang & Clark 2006, eqs.
14-17, integrated over a window of W samples instead of one):

.. math::
    e_i = \frac{1}{T}\Big[\big(M(\nu(t_1) - \nu(t_0))\big)_i
    + \int_{t_0}^{t_1}\big(C(\nu)\nu + D(\nu)\nu + g(\eta)\big)_i dt
    - \int_{t_0}^{t_1}\tau_i\,dt\Big]

is the generalized force [N, N m] the prior model misses (what must be added to its
right-hand side to reproduce the motion), averaged over each window of length T. Inputs are held (zero-order hold) between samples, so their integral is exact;
the state terms are integrated with the trapezoidal rule.  Windows do not overlap, so a
correct model leaves residuals that are nearly independent.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
from scipy.signal import savgol_coeffs

from stripcoef.conventions import parse_dof
from stripcoef.errors import InputError
from stripcoef.ingest.attitude import euler_matrices
from stripcoef.logfile import log_inputs
from stripcoef.model import coriolis_table, velocity_product


#: Half-span of the end-value quadratics of :meth:`WindowData.rate` [s] (0.2 s: 5 samples
#: at 10 Hz, noise variance x 0.486). Measured on a noise-free log of the Wang & Clark 2006 ROV
#: (time constants M/D about 0.5-1 s), RMS window residual of the true model, 4 s windows:
#: raw end values 0.0011 / 0.0018 / 0.0027 N (surge / sway / heave: trapezoidal
#: quadrature), 0.2 s 0.0004 / 0.0006 / 0.0020 N, 0.4 s 0.0071 / 0.0099 / 0.0056 N (the
#: quadratic misses the fast transients after steps); the noise floor it lowers is about
#: 0.02-0.03 N (tests/test_diagnose_effects.py).
ENDPOINT_SPAN = 0.2


#: A step of the applied generalized force larger than this fraction of its range is an
#: input jump (a kink of the velocity) that the end-value quadratics do not straddle.
JUMP_FRACTION = 0.05


def coriolis_times_velocity(mass_matrix, nu) -> np.ndarray:
    r"""C(nu) nu [N, N m] of a 6x6 inertia matrix [kg, kg m, kg m^2] for (n, 6) velocities
    [m/s, rad/s]: the rule of :meth:`stripcoef.model.HydroModel.velocity_forces`
    (:func:`stripcoef.model.coriolis_table`; Fossen 2011, Theorem 3.2, eq. 3.46), for a bare
    mass matrix (a coefficient's regressor, :func:`coefficient_column`)."""
    nu = np.atleast_2d(np.asarray(nu, dtype=float))
    return velocity_product(coriolis_table(mass_matrix), None, nu)


def white_noise_sd(x) -> float:
    r"""Standard deviation of the white noise on a sampled signal [its unit], from second
    differences: :math:`\mathrm{var}(\Delta^2 x) = 6\sigma^2` for white noise, the spread of
    :math:`\Delta^2 x` by the median absolute deviation (scale 1.4826 for a normal
    distribution; Rousseeuw & Croux 1993, J. Am. Stat. Assoc. 88: 1273-1283), robust to the
    signal itself (a smooth signal's second differences are small). 0 for fewer than three
    samples. The one estimator of the log's noise: :meth:`WindowData.rate_noise_variance`,
    diagnose's excitation rule and the held-out noise growth read it."""
    return float(_second_difference_mad(x) / np.sqrt(6.0))


def _second_difference_mad(x) -> float:
    """1.4826 MAD of the second differences of ``x`` (:func:`white_noise_sd`, times sqrt 6)."""
    x = np.asarray(x, dtype=float)
    d2 = x[2:] - 2 * x[1:-1] + x[:-2]
    return float(1.4826 * np.median(np.abs(d2 - np.median(d2)))) if d2.size else 0.0


def damping_times_velocity(model, nu) -> np.ndarray:
    r""":math:`D(\nu)\nu = D_L\nu + u L\nu + D_Q(|\nu|\odot\nu)` for (n, 6) velocities [N, N m]:
    :meth:`stripcoef.model.HydroModel.velocity_forces` without C (Fossen 2011, eq. 6.59 with
    the diagonal-in-|nu| quadratic form of HydroModel.damping and its lift L, Prestero 2001
    sec. 3.6)."""
    return model.velocity_forces(np.atleast_2d(np.asarray(nu, dtype=float)), coriolis=False)


def rotation_matrices(eta) -> np.ndarray:
    """(n, 3, 3) body-to-NED rotations R(phi, theta, psi) (Fossen 2011, eq. 2.18).

    R = R_z(psi) R_y(theta) R_x(phi) [-] for each row of ``eta`` (n, 6) [m, rad]: the
    vectorised :func:`stripcoef.conventions.rotation_matrix`
    (:func:`stripcoef.ingest.attitude.euler_matrices`).
    """
    eta = np.atleast_2d(eta)
    return euler_matrices(eta[:, 3], eta[:, 4], eta[:, 5])


def savgol_centre_weights(h: int) -> np.ndarray:
    r"""Weights of the centre value of a least-squares quadratic through 2h+1 equally
    spaced samples (Savitzky & Golay 1964, *Anal. Chem.* 36, 1627, table I):

    .. math:: w_k = \frac{3(3h^2 + 3h - 1) - 15k^2}{(2h+1)(4h^2 + 4h - 3)},\quad k = -h..h

    (dimensionless; they sum to 1, and :math:`\sum w_k^2 = w_0`, the factor by which white
    noise variance is reduced). h = 0 or 1 gives the sample itself. Computed by
    ``scipy.signal.savgol_coeffs`` (polynomial order 2, or 2h when that is lower)."""
    return _savgol_centre_weights(int(h))


@lru_cache(maxsize=64)
def _savgol_centre_weights(h: int) -> np.ndarray:
    """:func:`savgol_centre_weights`, computed once per half-width (a fit asks for the same
    few thousands of times); read-only, as it is shared."""
    w = savgol_coeffs(2 * h + 1, min(2, 2 * h), use="dot")
    w.flags.writeable = False
    return w


@dataclass
class WindowData:
    """A time-series log and a prior model, prepared for window regressions.

    Attributes
    ----------
    t : (n,) [s]; nu : (n, 6) [m/s, rad/s]; eta : (n, 6) [m, rad]
    tau : (n, 6) applied generalized force [N, N m]: from the commands through the prior's
        thrust maps when the log has ``n_<thruster>`` columns, else the logged ``X..N``
    thrust : (n, k) thrust per thruster [N] (prior map) or None; commands : (n, k) or None
    alloc : (6, k) allocation matrix of the prior
    i0, i1 : (m,) first and last sample of each window; T : (m,) window length [s]
    e0 : (m, 6) the prior's window force residual [N, N m]
    columns : dict of the log's other columns (``tether_length``...)
    """

    log: object
    model: object
    t: np.ndarray
    nu: np.ndarray
    eta: np.ndarray
    tau: np.ndarray
    thrust: np.ndarray | None
    commands: np.ndarray | None
    alloc: np.ndarray
    i0: np.ndarray
    i1: np.ndarray
    T: np.ndarray
    e0: np.ndarray = field(default=None)
    columns: dict = field(default_factory=dict)
    source: str = ""
    endpoint_halfwidth: int = 0
    #: other DOFs' added-mass changes {``M_<dof>``: change [kg or kg m^2]} already taken out
    #: of ``e0`` as known forces (:func:`stripcoef.diagnose.cross.with_known`)
    known_added_mass: dict = field(default_factory=dict)
    #: what :meth:`cached` computed from these data, by key (not an input: a copy made by
    #: ``dataclasses.replace`` starts without it)
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    @property
    def n_windows(self) -> int:
        return self.i0.size

    def cached(self, key, make):
        """``make()``, computed once per window data and ``key`` (the data are fixed once
        cut): the end-value half-widths, the rate noise, the effects' design terms and the
        current effect's log-side terms are asked for many times in one diagnosis."""
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    # window operators -----------------------------------------------------
    def _dt(self) -> np.ndarray:
        """The sampling intervals, np.diff(t) (n - 1,) [s], computed once (read-only)."""
        def make():
            dt = np.diff(self.t)
            dt.flags.writeable = False
            return dt
        return self.cached("dt", make)

    def mean(self, f) -> np.ndarray:
        """Trapezoidal window mean of a sampled state function (n,) or (n, c)."""
        f = np.asarray(f, dtype=float)
        dt = self._dt()
        seg = 0.5 * (f[1:] + f[:-1]) * (dt if f.ndim == 1 else dt[:, None])
        cum = np.concatenate([np.zeros((1,) + f.shape[1:]), np.cumsum(seg, axis=0)])
        return (cum[self.i1] - cum[self.i0]) / (self.T if f.ndim == 1 else self.T[:, None])

    def mean_held(self, f) -> np.ndarray:
        """Window mean of a zero-order-hold input (n,) or (n, c): exact for held inputs."""
        f = np.asarray(f, dtype=float)
        dt = self._dt()
        seg = f[:-1] * (dt if f.ndim == 1 else dt[:, None])
        cum = np.concatenate([np.zeros((1,) + f.shape[1:]), np.cumsum(seg, axis=0)])
        return (cum[self.i1] - cum[self.i0]) / (self.T if f.ndim == 1 else self.T[:, None])

    def _endpoint_halfwidths(self) -> tuple[np.ndarray, np.ndarray]:
        """Half-widths (samples) of the end-value estimates of each window start and end:
        ``endpoint_halfwidth`` where the velocity is smooth, fewer near an input jump (a
        kink of the velocity: the acceleration jumps with a held input; see
        :data:`JUMP_FRACTION`), none at it."""
        return self.cached("endpoint_halfwidths", self._halfwidths_of_the_log)

    def _halfwidths_of_the_log(self):
        n, hmax = self.t.size, int(self.endpoint_halfwidth)
        tau = np.asarray(self.tau, float)
        # a jump: a step of the applied force of more than JUMP_FRACTION of its range (the
        # small per-sample steps of a sampled sinusoid leave the velocity smooth enough)
        big = np.abs(np.diff(tau, axis=0)) > JUMP_FRACTION * np.ptp(tau, axis=0)[None, :]
        jumps = np.nonzero(np.any(big, axis=1))[0] + 1

        def widths(idx):
            h = np.minimum(np.full(idx.size, hmax), np.minimum(idx, n - 1 - idx))
            if jumps.size:
                k = np.searchsorted(jumps, idx)
                left = np.where(k > 0, idx - jumps[np.maximum(k - 1, 0)], n)
                right = np.where(k < jumps.size, jumps[np.minimum(k, jumps.size - 1)] - idx, n)
                h = np.minimum(h, np.minimum(left, right) - 1)
            h = np.maximum(h, 0)
            return np.where(h < 2, 0, h)  # a 3-point quadratic fit is the sample itself

        return widths(self.i0), widths(self.i1)

    def _end_values(self, f, idx, hs):
        out = np.empty((idx.size,) + f.shape[1:])
        for h in np.unique(hs):
            sel = hs == h
            w = savgol_centre_weights(int(h))
            rows = idx[sel][:, None] + np.arange(-h, h + 1)[None, :]
            out[sel] = np.tensordot(f[rows], w, axes=([1], [0])) if f.ndim == 1 \
                else np.einsum("mkc,k->mc", f[rows], w)
        return out

    def rate(self, f) -> np.ndarray:
        r"""(f(t1) - f(t0)) / T: the window-mean derivative.

        The end values are the centre values of least-squares quadratics through
        :math:`2h+1` samples centred on each end (Savitzky & Golay 1964; exact for cubics
        at the centre), :math:`h` = ``endpoint_halfwidth`` where the signal is smooth and
        less near an input jump, where the velocity has a kink (no smoothing across it):
        white measurement noise enters each end value with the variance factor
        :func:`savgol_centre_weights` ``[h]`` (0.486 for h = 2) instead of 1. Noise in this
        term would otherwise bias the fitted inertia low (errors in variables) and sets the
        noise floor of the window residual."""
        f = np.asarray(f, dtype=float)
        h0, h1 = self._endpoint_halfwidths()
        a = self._end_values(f, self.i0, h0)
        b = self._end_values(f, self.i1, h1)
        return (b - a) / (self.T if f.ndim == 1 else self.T[:, None])

    def rate_noise_variance(self, dof: int) -> float:
        r"""Variance of the noise of :meth:`rate` for velocity ``dof`` [(m/s^2)^2].

        White velocity noise of variance :math:`\sigma_v^2`, estimated robustly from
        second differences (:math:`\operatorname{var}(\Delta^2 v) = 6\sigma_v^2` for white
        noise; median absolute deviation), gives the window mean of
        :math:`\sigma_v^2 (c_{h_0} + c_{h_1}) / T^2`, with :math:`c_h` the centre weight of
        the end-value quadratic (its variance factor; 1 for a raw sample).
        """
        def make():
            var_v = _second_difference_mad(self.nu[:, dof]) ** 2 / 6.0   # white_noise_sd^2
            h0, h1 = self._endpoint_halfwidths()
            c = np.array([savgol_centre_weights(int(h))[int(h)] for h in range(
                int(max(h0.max(initial=0), h1.max(initial=0))) + 1)])
            return float(var_v * np.mean((c[h0] + c[h1]) / self.T ** 2))
        return self.cached(("rate_noise_variance", dof), make)

    def thruster_force(self, dof: int):
        """Per-sample generalized force in ``dof`` from each thruster (n, k), or None
        (computed once per DOF, read-only)."""
        if self.thrust is None:
            return None

        def make():
            fk = self.thrust * self.alloc[dof][None, :]
            fk.flags.writeable = False
            return fk
        return self.cached(("thruster_force", dof), make)

    def acting(self, dof: int, tol: float = 1e-9) -> list:
        """Indices of thrusters that act in ``dof``."""
        return [k for k in range(self.alloc.shape[1]) if abs(self.alloc[dof, k]) > tol]


#: Fewest sampling intervals in a window: its mean and the velocity change across it need
#: several samples (a window of one sample, e.g. ``--window 1e-6``, was silently widened).
MIN_WINDOW_SAMPLES = 4


def window_data(log, model, *, window: float = 1.0) -> WindowData:
    """Cut a log into non-overlapping windows of about ``window`` seconds.

    Raises
    ------
    InputError
        No time column, no velocities, no inputs, or too few windows (< 12).
    """
    from stripcoef.conventions import POSE, VELOCITIES

    t = log.require("t")
    if not (np.isfinite(window) and window > 0):
        raise InputError("not a positive window", key="window", value=window,
                         expected="a finite number of seconds > 0")
    present = [v for v in VELOCITIES if v in log]
    if not present:
        raise InputError("no velocity columns", file=log.source,
                         expected="some of " + " ".join(VELOCITIES) + " [m/s, rad/s]")
    nu = log.velocities()
    eta = np.column_stack([log.get(p, np.zeros(len(log))) for p in POSE])
    names = [th.name for th in model.thrusters]
    inputs = log_inputs(log, model)      # the one replay rule (simulate --from-log's)
    alloc = model.allocation()
    thrust = commands = None
    if inputs.commands:
        commands = np.column_stack([inputs.commands.get(n, np.zeros(len(log))) for n in names])
        thrust = np.column_stack([np.asarray(th.thrust(commands[:, k]), float).reshape(-1)
                                  for k, th in enumerate(model.thrusters)])
        tau = thrust @ alloc.T  # logged X..N, if any, are their record: thrust is the prior's map
    elif inputs.forces is not None:
        tau = inputs.forces
    else:
        tau = np.zeros((len(log), 6))
    if inputs.deflections:
        # control surfaces: u|u| B_delta delta at the logged speed (Prestero 2001, sec. 3.7)
        snames = [sf.name for sf in model.control_surfaces]
        delta = np.column_stack([inputs.deflections.get(n, np.zeros(len(log))) for n in snames])
        u = nu[:, 0]
        tau = tau + (u * np.abs(u))[:, None] * (delta @ model.control_matrix.T)
    dt = float(np.median(np.diff(t)))
    if window < MIN_WINDOW_SAMPLES * dt:
        raise InputError("window shorter than the log's sampling resolves", key="window",
                         value=window, expected=f"at least {MIN_WINDOW_SAMPLES} sampling "
                         f"intervals of the log ({MIN_WINDOW_SAMPLES * dt:.3g} s; median "
                         f"step {dt:.3g} s in {log.source})")
    w = max(1, int(round(window / dt)))
    i0 = np.arange(0, len(t) - w, w)
    i1 = i0 + w
    if i0.size < 12:
        raise InputError("log too short for the diagnosis", file=log.source, key="t",
                         value=f"{t[-1] - t[0]:g} s",
                         expected=f"at least 12 windows of {w * dt:g} s")
    data = WindowData(log=log, model=model, t=t, nu=nu, eta=eta, tau=tau, thrust=thrust,
                      commands=commands, alloc=alloc, i0=i0, i1=i1, T=t[i1] - t[i0],
                      columns={k: v for k, v in log.columns.items()},
                      source=log.source,
                      endpoint_halfwidth=min(int(round(ENDPOINT_SPAN / dt)), w // 4))
    data.e0 = prior_residual(data, model)
    if not np.all(np.isfinite(data.e0)):
        # values so large that the prior's forces overflow (1e300 in a column): refused
        # here, where the log's column can still be named, not as a failed SVD later
        k = int(np.nonzero(~np.all(np.isfinite(data.e0), axis=1))[0][0])
        big = max(log.names, key=lambda c: float(np.max(np.abs(log.columns[c]))))
        raise InputError(f"the model's forces overflow in window {k}", file=log.source,
                         key=big, value=float(np.max(np.abs(log.columns[big]))),
                         expected="values in SI units of a plausible magnitude")
    return data


#: The prefix of a drag coupling's calibration name: ``D_Q_sway`` is :math:`D_Q[i, \text{sway}]`
#: in the calibration of moment DOF i (:mod:`stripcoef.diagnose.couplings`).
COUPLING_PREFIX = "D_Q_"


def coefficient_column(data: WindowData, dof: int, key: str, nu=None) -> np.ndarray:
    r"""Window regressor of a change of one prior coefficient in DOF i [N or N m per unit]:
    minus the derivative of the window residual :func:`prior_residual` with respect to it,

    - ``M`` (the DOF's added mass): :math:`-(\nu_i(t_1) - \nu_i(t_0))/T`;
    - ``D_L``, ``D_Q``: :math:`-\overline{\nu_i}`, :math:`-\overline{\nu_i|\nu_i|}`;
    - ``M_<dof>`` (another DOF's added mass :math:`M_{jj}`, seen through the added-mass
      Coriolis force, linear in :math:`M_A`; Fossen 2011, eq. 6.43):
      :math:`-\overline{(C_A[E_{jj}](\nu)\nu)_i}`;
    - ``D_Q_<dof>`` (a quadratic drag coupling :math:`D_Q[i, j]`, the moment of DOF j's
      drag; :mod:`stripcoef.diagnose.couplings`): :math:`-\overline{\nu_j|\nu_j|}`,

    with ``nu`` (n, 6) the velocity the coefficient acts on: over ground by default, relative
    to the water when a current is in the model (Fossen 2011, eq. 10.1)."""
    nu = data.nu if nu is None else nu
    v = nu[:, dof]
    if key == "M":
        return -data.rate(v)
    if key == "D_L":
        return -data.mean(v)
    if key == "D_Q":
        return -data.mean(v * np.abs(v))
    if key.startswith(COUPLING_PREFIX):
        w = nu[:, parse_dof(key[len(COUPLING_PREFIX):])]
        return -data.mean(w * np.abs(w))
    unit = np.zeros((6, 6))
    j = parse_dof(key[2:])
    unit[j, j] = 1.0
    return -data.mean(coriolis_times_velocity(unit, nu)[:, dof])


def prior_residual(data: WindowData, model) -> np.ndarray:
    r"""Window force residual of a model (module docstring) [N, N m], shape (m, 6).

    .. math:: e = M\frac{\nu(t_1) - \nu(t_0)}{T} + \overline{C(\nu)\nu + D(\nu)\nu + g(\eta)}
              - \overline{\tau}

    (window means, trapezoidal for states, exact for held inputs; T [s]). Window form of
    Wang & Clark 2006, eqs. 14-17 and Fossen (2011), eq. 7.190.
    """
    nu, eta = data.nu, data.eta
    rest = model.velocity_forces(nu) + model.restoring(eta.T).T     # rows at once
    return (data.rate(nu) @ model.mass_matrix.T + data.mean(rest) - data.mean_held(data.tau))
