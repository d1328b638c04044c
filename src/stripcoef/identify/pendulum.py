r"""Free-decay pendulum and torsion pendulum identification (Eng et al., Eng et al. 2009).

Pendulum (Eng et al. 2009, eqs. 1-4): a model of mass M [kg] and buoyancy B [N] on a rod of
length r [m] swings in water; the hydrodynamic force :math:`F_H = m_a\ddot x + K_L\dot x +
K_Q|\dot x|\dot x` acts along the path, :math:`\dot x = r\dot\theta`.  Then

.. math::
    \ddot\theta = \alpha\sin\theta - \beta\dot\theta - \gamma|\dot\theta|\dot\theta, \quad
    \alpha = \frac{B - Mg}{(M + m_a) r}, \quad \beta = \frac{K_L}{M + m_a}, \quad
    \gamma = \frac{K_Q r}{M + m_a}

identified by least squares on :math:`y = \ddot\theta`, :math:`H = [\sin\theta\ \
-\dot\theta\ \ -|\dot\theta|\dot\theta]` (eqs. 5-7; the minus signs make beta and gamma the
positive quantities of eq. 4 - the paper's eq. 5 prints them with + signs, which is why its
in-air beta and gamma come out with mixed signs).  Inverting:

.. math::
    m_a = \frac{B - Mg}{\alpha r} - M, \qquad K_L = \beta (M + m_a), \qquad
    K_Q = \frac{\gamma (M + m_a)}{r}

In air (B = 0, m_a = 0) the first relation gives the rod length, :math:`r = -g/\alpha`
(Eng et al. 2009, sec. IV.A: alpha = -25.128 gives r = 0.3904 m with g = 9.81 m/s^2).

Torsion pendulum (Eng et al. 2009, eq. 12) for yaw: the rod is replaced by a torsion spring of
stiffness K [N m/rad] and

.. math:: \ddot\theta = a\,\theta - b\,\dot\theta - c\,|\dot\theta|\dot\theta, \quad
          a = -\frac{K}{I + I_a}, \quad b = \frac{K_L}{I + I_a}, \quad c = \frac{K_Q}{I + I_a}

(the paper prints :math:`+K/(I+I_a)`; a restoring spring makes the fitted ``a`` negative).
So :math:`I_a = -K/a - I`, :math:`K_L = b(I + I_a)`, :math:`K_Q = c(I + I_a)`.

The derivatives come from a Savitzky-Golay smoothing of the sampled angle (Savitzky & Golay
1964; Indiveri 1998 sec. 4.2.4 uses the same filter).  Its residuals are correlated over the
window, so the covariance is Newey-West with ``window`` lags.  The quality measure is the
paper's: the RMS of the re-simulated angle minus the measured angle [rad] (Table II).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.signal import savgol_filter

from stripcoef.errors import InputError
from stripcoef.fluid import G
from stripcoef.identify.estimators import FitResult, linear_lstsq

COLUMN = "theta_pendulum"
_EIV_NOTE = ("equation error on noisy derivatives underestimates the added mass when the angle "
             "noise is large (docs/identify.md); --refine fits the re-simulated angle instead")


def smooth_derivatives(t, theta, *, window: int = 15, order: int = 4):
    r"""Savitzky-Golay smoothed angle and its first two derivatives [rad, rad/s, rad/s^2].

    Requires uniform sampling within 1 %.
    :math:`\theta^{(d)}_k = h^{-d}\sum_{j=-m}^{m} c^{(d)}_j \theta_{k+j}`, d = 0, 1, 2, with
    :math:`c^{(d)}` the weights of the local least-squares polynomial of degree ``order``
    over ``window`` = 2m + 1 samples, h the step [s] (Savitzky & Golay, Anal. Chem. 36
    (1964) 1627). ``t`` [s], ``theta`` [rad].
    """
    t = np.asarray(t, dtype=float)
    theta = np.asarray(theta, dtype=float)
    dt = np.diff(t)
    h = float(np.median(dt))
    if np.max(np.abs(dt - h)) > 0.01 * h:
        raise InputError("non-uniform sampling", key="t",
                         value=f"steps {dt.min():.4g}..{dt.max():.4g} s",
                         expected="a uniform time step (within 1 %) for the Savitzky-Golay filter")
    if window % 2 == 0 or window <= order or window > t.size:
        raise InputError("bad Savitzky-Golay window", key="window", value=window,
                         expected=f"an odd number > order {order} and <= {t.size} samples")
    th = savgol_filter(theta, window, order, deriv=0)
    om = savgol_filter(theta, window, order, deriv=1, delta=h)
    ac = savgol_filter(theta, window, order, deriv=2, delta=h)
    return th, om, ac


def simulate_decay(t, theta0, omega0, a, b, c, *, restoring="sin", substeps: int = 4):
    r"""Angle [rad] of :math:`\ddot\theta = a f(\theta) - b\dot\theta - c|\dot\theta|\dot\theta`
    with f = sin (pendulum, eq. 4) or identity (torsion, eq. 12).

    Classical fixed-step Runge-Kutta 4 with ``substeps`` steps per sample interval (error
    O((omega h)^4), below 1e-5 rad for 30 samples/s and periods above 1 s).  Non-finite after
    a blow-up.
    """
    t = np.asarray(t, dtype=float)
    lin = restoring != "sin"
    sin = math.sin
    fabs = math.fabs
    th, om = float(theta0), float(omega0)
    a, b, c = float(a), float(b), float(c)         # Python floats: inf, not numpy warnings
    times = t.tolist()
    out = np.empty(t.size)
    out[0] = th
    def acc(x, v):
        return a * (x if lin else sin(x)) - b * v - c * fabs(v) * v
    for k in range(1, t.size):
        h = (times[k] - times[k - 1]) / substeps
        try:
            for _ in range(substeps):
                k1x, k1v = om, acc(th, om)
                k2x, k2v = om + 0.5 * h * k1v, acc(th + 0.5 * h * k1x, om + 0.5 * h * k1v)
                k3x, k3v = om + 0.5 * h * k2v, acc(th + 0.5 * h * k2x, om + 0.5 * h * k2v)
                k4x, k4v = om + h * k3v, acc(th + h * k3x, om + h * k3v)
                th += h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x)
                om += h / 6.0 * (k1v + 2 * k2v + 2 * k3v + k4v)
        except (ValueError, OverflowError):     # sin(inf) within a step: a blow-up
            th = math.inf
        if not (fabs(th) < 1e6 and fabs(om) < 1e9):
            out[k:] = np.nan
            return out
        out[k] = th
    return out


def auto_window(t, theta, *, order: int = 4) -> int:
    """Savitzky-Golay window: the odd number of samples nearest 0.4 of the oscillation period
    (period from the peak of the amplitude spectrum of the de-meaned angle), at least order+3."""
    th = np.asarray(theta, dtype=float) - np.mean(theta)
    n = th.size
    h = float(np.median(np.diff(t)))
    spec = np.abs(np.fft.rfft(th, 8 * n))
    freq = np.fft.rfftfreq(8 * n, h)
    k = int(np.argmax(spec[1:])) + 1
    w = int(round(0.4 / (freq[k] * h)))
    w = max(w, order + 3)
    w = min(w, n if n % 2 == 1 else n - 1)
    return w if w % 2 == 1 else w + 1


def _fit_decay(t, theta, restoring, names, *, window, order, source, method):
    t = np.asarray(t, dtype=float)
    theta = np.asarray(theta, dtype=float)
    if window is None:
        window = auto_window(t, theta, order=order)
    th, om, ac = smooth_derivatives(t, theta, window=window, order=order)
    k = window // 2
    sl = slice(k, t.size - k)                  # drop the filter's edge estimates
    f = np.sin(th[sl]) if restoring == "sin" else th[sl]
    H = np.column_stack([f, -om[sl], -np.abs(om[sl]) * om[sl]])
    fit = linear_lstsq(H, ac[sl], names, method=method, model=method, dof="",
                       covariance="hac", lags=window,
                       what=f"{source}: {method} regression")
    a, b, c = fit.theta
    sim = simulate_decay(t[sl], th[sl][0], om[sl][0], a, b, c, restoring=restoring)
    err = sim - theta[sl]
    fit.rms_error = float(np.sqrt(np.mean(err ** 2))) if np.all(np.isfinite(sim)) else float("inf")
    fit.metrics["rms_angle_error"] = fit.rms_error
    fit.data.update({"t": t[sl], "y": theta[sl], "simulated": sim, "velocity": om[sl],
                     "acceleration": ac[sl]})
    fit.notes.append(f"derivatives: Savitzky-Golay window {window}, order {order}; "
                     f"covariance Newey-West with {window} lags; rms_error = RMS of re-simulated "
                     "minus measured angle [rad] (Eng et al. 2009, Table II)")
    return fit


def refine_output_error(fit: FitResult, t, theta, *, restoring: str = "sin") -> FitResult:
    r"""Output-error refinement: minimise :math:`\sum_k (\theta_k - \theta_{sim}(t_k))^2` over
    a, b, c and the initial state, starting from the equation-error estimate.

    The re-simulated angle is the paper's own quality measure (Eng et al. 2009, Table II); making it
    the cost removes the errors-in-variables bias of noisy derivatives.  Covariance
    :math:`\hat\sigma^2 (J^T J)^{-1}` at the optimum (Gauss-Newton, white angle noise;
    Ljung 1999, sec. 9.3).  Returns a new FitResult (method ``<method> output-error``).
    ``t`` [s], ``theta`` [rad]; a [1/s^2], b [1/s], c [1/rad] as in the module docstring
    (Eng et al. 2009, eqs. 4 and 12).
    """
    from scipy.optimize import least_squares
    t = np.asarray(t, dtype=float)
    theta = np.asarray(theta, dtype=float)
    t0 = fit.data["t"][0]
    keep = t >= t0
    tt, yy = t[keep], theta[keep]
    x0 = np.concatenate([fit.theta, [fit.data["simulated"][0], fit.data["velocity"][0]]])

    def resid(x):
        sim = simulate_decay(tt, x[3], x[4], x[0], x[1], x[2], restoring=restoring)
        r = sim - yy
        return np.where(np.isfinite(r), r, 1e3)
    sol = least_squares(resid, x0, x_scale="jac", method="lm")
    names = list(fit.names) + ["theta0", "omega0"]
    J = sol.jac
    r = sol.fun
    cost = float(r @ r)
    n, p = J.shape
    try:
        cov = cost / (n - p) * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        raise InputError("output-error refinement failed: singular Jacobian", key="refine",
                         expected="a decay record that excites all terms") from None
    out = FitResult(method=f"{fit.method} output-error", model=fit.model, dof=fit.dof,
                    names=names, theta=sol.x, cov=cov, residuals=-r, cost=cost, n_obs=n,
                    covariance="iid (Gauss-Newton)", units=dict(fit.units))
    out.units.update({"theta0": "rad", "omega0": "rad/s"})
    out.rms_error = float(np.sqrt(np.mean(r ** 2)))
    out.metrics["rms_angle_error"] = out.rms_error
    out.metrics["equation_error_rms_angle"] = fit.rms_error
    sim = yy + r
    out.data.update({"t": tt, "y": yy, "simulated": sim, "fitted": sim,
                     "velocity": np.gradient(sim, tt)})
    out.notes.append("output-error refinement of the equation-error estimate: " +
                     ", ".join(f"{n_}={v:.5g}" for n_, v in zip(fit.names, fit.theta)))
    return out


def pendulum(t, theta, *, mass=None, buoyancy=0.0, length=None, g: float = G,
             medium: str = "water", window: int | None = None, order: int = 4,
             source: str = "<memory>", dof: str = "", refine: bool = False) -> FitResult:
    r"""Free-decay pendulum identification (Eng et al. 2009, eqs. 1-7).

    Parameters
    ----------
    t, theta : arrays
        Time [s] (uniform) and pendulum angle from the vertical [rad].
    mass : float
        Mass M of the model [kg] (needed for m_a, K_L, K_Q; in air for K_L and K_Q).
    buoyancy : float
        Buoyancy force B [N] (0 in air).
    length : float
        Rod length r [m] (from the in-air calibration, or measured).
    medium : {"water", "air"}
        ``air``: B = 0, m_a = 0, derives the rod length :math:`r = -g/\alpha`.
    window, order : int
        Savitzky-Golay window (default: 0.4 of the period) and polynomial order.
    refine : bool
        Follow the paper's equation-error fit by an output-error fit
        (:func:`refine_output_error`).
    """
    if medium not in ("water", "air"):
        raise InputError("unknown medium", key="medium", value=medium, expected="water or air")
    fit = _fit_decay(t, theta, "sin", ["alpha", "beta", "gamma"], window=window, order=order,
                     source=source, method="pendulum")
    if refine:
        fit = refine_output_error(fit, t, theta, restoring="sin")
    else:
        fit.notes.append(_EIV_NOTE)
    fit.dof = dof
    fit.units.update({"alpha": "1/s^2", "beta": "1/s", "gamma": "1/rad"})
    if medium == "air":
        fit.model = "pendulum in air"
        fit.derive("r", lambda p: -g / p["alpha"], unit="m")
        if mass is not None:
            fit.derive("K_L", lambda p: p["beta"] * mass, unit="N s/m")
            fit.derive("K_Q", lambda p: p["gamma"] * mass / (-g / p["alpha"]), unit="N s^2/m^2")
        return fit
    if mass is None or length is None:
        fit.notes.append("mass and length not given: only alpha, beta, gamma reported")
        return fit

    def total(p):
        return (buoyancy - mass * g) / (p["alpha"] * length)
    fit.derive("m_a", lambda p: total(p) - mass, unit="kg")
    fit.derive("K_L", lambda p: p["beta"] * total(p), unit="N s/m")
    fit.derive("K_Q", lambda p: p["gamma"] * total(p) / length, unit="N s^2/m^2")
    fit.notes.append(f"M = {mass:g} kg, B = {buoyancy:g} N, r = {length:g} m, g = {g:g} m/s^2 "
                     "taken as exact")
    return fit


def torsion(t, theta, *, stiffness=None, inertia=None, medium: str = "water",
            window: int | None = None, order: int = 4, source: str = "<memory>",
            dof: str = "yaw", refine: bool = False) -> FitResult:
    r"""Torsion-pendulum identification (Eng et al. 2009, eq. 12).

    Parameters
    ----------
    stiffness : float
        Torsion spring constant K [N m/rad].
    inertia : float
        Rigid-body moment of inertia I about the spring axis [kg m^2].
    medium : {"water", "air"}
        ``air``: I_a = 0; derives K from I, or I from K (whichever is missing).
    """
    fit = _fit_decay(t, theta, "linear", ["a", "b", "c"], window=window, order=order,
                     source=source, method="torsion")
    if refine:
        fit = refine_output_error(fit, t, theta, restoring="linear")
    else:
        fit.notes.append(_EIV_NOTE)
    fit.dof = dof
    fit.units.update({"a": "1/s^2", "b": "1/s", "c": "1/rad"})
    if medium == "air":
        fit.model = "torsion in air"
        if inertia is not None:
            fit.derive("K", lambda p: -p["a"] * inertia, unit="N m/rad")
        elif stiffness is not None:
            fit.derive("I", lambda p: -stiffness / p["a"], unit="kg m^2")
        return fit
    if stiffness is None or inertia is None:
        fit.notes.append("stiffness and inertia not given: only a, b, c reported")
        return fit

    def total(p):
        return -stiffness / p["a"]
    fit.derive("I_a", lambda p: total(p) - inertia, unit="kg m^2")
    fit.derive("K_L", lambda p: p["b"] * total(p), unit="N m s/rad")
    fit.derive("K_Q", lambda p: p["c"] * total(p), unit="N m s^2/rad^2")
    fit.notes.append(f"K = {stiffness:g} N m/rad, I = {inertia:g} kg m^2 taken as exact")
    return fit


def pendulum_log(log, **kw) -> FitResult:
    """:func:`pendulum` on a log with columns ``t`` and ``theta_pendulum``."""
    return pendulum(log.require("t"), log.require(COLUMN), source=log.source, **kw)


def torsion_log(log, **kw) -> FitResult:
    """:func:`torsion` on a log with ``t`` and ``theta_pendulum`` (or ``psi``)."""
    col = COLUMN if COLUMN in log or "psi" not in log else "psi"
    return torsion(log.require("t"), log.require(col), source=log.source, **kw)


def in_air_length(alpha: float, *, g: float = G) -> float:
    r"""Rod length from the in-air alpha: :math:`r = -g/\alpha` [m] (Eng et al. 2009, sec. IV.A)."""
    return -g / alpha
