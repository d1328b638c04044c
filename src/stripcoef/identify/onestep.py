r"""One-step-ahead prediction least squares on a one-DOF state equation (Wang & Clark 2006, eqs. 8-19).

Wang & Clark (Wang & Clark 2006, eq. 8) model the decoupled yaw motion of the VideoRay Pro III as

.. math:: \dot r = \alpha r + \beta r|r| + \gamma n + \delta

and identify :math:`\theta = [\alpha\ \beta\ \gamma\ \delta]^T` from samples
:math:`y_k = r(t_k) + e_k` (eq. 10) by minimising the one-step-ahead prediction error
(eqs. 11-17)

.. math::
    \varepsilon_k = y_k - y_{k-1} - \Phi_k\theta, \qquad
    \Phi_k = \int_{t_{k-1}}^{t_k} \phi(\hat r(\tau), n(\tau))\, d\tau, \qquad
    \phi = [r\ \ r|r|\ \ n\ \ 1]

solved by least squares (eqs. 18-19).  Here :math:`\Phi_k` is the trapezoidal rule on the
measured samples.  The trapezoid makes the noise of the linear column uncorrelated with the
noise of :math:`Y_k = y_k - y_{k-1}` (both contain :math:`e_k` and :math:`e_{k-1}` with
opposite signs), so the regression is unbiased to first order in the noise.  The residuals
of differenced measurement noise are MA(1) with lag-1 correlation -1/2; the default
covariance is the OLS sandwich under an MA(1) noise whose correlation is estimated from the
residuals (0 for pure process noise, -1/2 for pure measurement noise).

The same form serves any DOF: the state is the DOF's velocity and ``n`` the applied
generalized force along it [N or N m] (or a raw command; then gamma is per command unit).

Derivation of the SNAME coefficients (sign convention of docs/conventions.md: SNAME
derivatives keep their sign, damping derivatives are negative).  The decoupled equation of
motion about the DOF (Fossen 2011, eq. 7.19 restricted to one DOF) is

.. math:: (I - N_{\dot r})\,\dot r = N_r r + N_{r|r|} r|r| + \tau_N + b

Dividing by the total inertia and matching terms with eq. 8:

.. math::
    \gamma = \frac{1}{I - N_{\dot r}}, \quad \alpha = \gamma N_r, \quad \beta = \gamma N_{r|r|},
    \quad \delta = \gamma b
    \;\Longrightarrow\;
    N_{\dot r} = I - \frac{1}{\gamma}, \quad N_r = \frac{\alpha}{\gamma}, \quad
    N_{r|r|} = \frac{\beta}{\gamma}, \quad b = \frac{\delta}{\gamma}

with ``I`` the rigid-body inertia about the axis (I_zz for yaw) [kg m^2].  A damped motion
gives :math:`\alpha < 0`.  Wang & Clark (2006) prints :math:`\alpha = 0.6199 > 0` and lists the
coefficients as positive magnitudes (Fossen's positive D matrix), so its eq. 8 must be read
with the damping signs folded into the printed values: :math:`|N_r| = \alpha/\gamma`.
"""

from __future__ import annotations

import numpy as np
from scipy.signal import savgol_filter

from stripcoef.conventions import DOF, FORCES, POSE, VELOCITIES, parse_dof
from stripcoef.errors import InputError, unknown_name
from stripcoef.identify.estimators import FitResult, linear_lstsq, runs_test_z

#: Model name -> terms (linear, quadratic, input, bias); LQB is Wang & Clark 2006's eq. 8.
MODELS = {
    "LQB": (True, True, True, True),
    "LQNB": (True, True, True, False),
    "LB": (True, False, True, True),
    "LNB": (True, False, True, False),
}
PARAMS = ("alpha", "beta", "gamma", "delta")


def _terms(model):
    if model not in MODELS:
        raise unknown_name("one-step model", model, MODELS)
    return [p for p, on in zip(PARAMS, MODELS[model]) if on]


def phi(x, n, model="LQB") -> np.ndarray:
    r"""Regressor row(s) :math:`\phi(r, n) = [r\ \ r|r|\ \ n\ \ 1]` (Wang & Clark 2006, eq. 9)."""
    x = np.asarray(x, dtype=float)
    n = np.asarray(n, dtype=float)
    cols = {"alpha": x, "beta": x * np.abs(x), "gamma": n, "delta": np.ones_like(x)}
    return np.column_stack([cols[p] for p in _terms(model)])


def velocity_from_pose(t, pose, *, window: int = 15, order: int = 3) -> np.ndarray:
    r"""Velocity [unit/s] as the Savitzky-Golay derivative of a sampled pose.

    Local least-squares polynomial of degree ``order`` over ``window`` samples
    (Savitzky & Golay, Anal. Chem. 36 (1964) 1627; used by Indiveri 1998, sec. 4.2.4).
    Requires near-uniform sampling (checked: spacing within 1 %).

    :math:`\dot x_k = \frac{1}{h}\sum_{j=-m}^{m} c_j x_{k+j}`, with c_j the first-derivative
    weights of that polynomial, h the time step [s], ``window`` = 2m + 1; ``t`` [s],
    ``pose`` [m or rad], result [m/s or rad/s].
    """
    t = np.asarray(t, dtype=float)
    dt = np.diff(t)
    h = float(np.median(dt))
    if np.max(np.abs(dt - h)) > 0.01 * h:
        raise InputError("non-uniform sampling", key="t", value=f"steps {dt.min():.4g}..{dt.max():.4g} s",
                         expected="a uniform time step (within 1 %) for the Savitzky-Golay derivative")
    if window % 2 == 0 or window <= order or window > t.size:
        raise InputError("bad Savitzky-Golay window", key="window", value=window,
                         expected=f"an odd number > order {order} and <= {t.size} samples")
    return savgol_filter(np.asarray(pose, dtype=float), window, order, deriv=1, delta=h)


def one_step(t, y, n, *, model: str = "LQB", dof: str = "yaw", inertia: float | None = None,
             covariance: str = "ma1", lags: int = 2, source: str = "<memory>") -> FitResult:
    r"""Identify the state equation of one DOF by one-step-ahead prediction LS (Wang & Clark 2006).

    Parameters
    ----------
    t : (N,) array
        Sample times [s], strictly increasing.
    y : (N,) array
        Measured velocity of the DOF [m/s or rad/s].
    n : (N,) array
        Input along the DOF [N, N m] (or a command).
    model : str
        ``LQB`` (eq. 8), ``LQNB``, ``LB``, ``LNB``.
    inertia : float, optional
        Rigid-body mass or inertia about the DOF [kg, kg m^2]; when given, the added mass
        (``N_rdot``) is derived.
    covariance : {"ma1", "hac", "iid"}
        ``ma1`` (default): OLS sandwich under MA(1) residuals - the structure of differenced
        white measurement noise, which the textbook ``iid`` formula overstates 5-20 times
        (tests/test_identify_onestep.py measures this); ``hac``: Newey-West with ``lags``.

    Returns
    -------
    FitResult with ``alpha``.. ``delta`` and the derived SNAME coefficients.
    """
    i = parse_dof(dof)
    t = np.asarray(t, dtype=float)
    y = np.asarray(y, dtype=float)
    n = np.asarray(n, dtype=float)
    if t.size < 3:
        raise InputError("too few samples", file=source, key="t", value=t.size,
                         expected="a time series of many samples")
    names = _terms(model)
    dt = np.diff(t)
    rows = phi(y, n, model)
    Phi = 0.5 * dt[:, None] * (rows[1:] + rows[:-1])       # eq. 16, trapezoidal rule
    Y = np.diff(y)                                           # eq. 19
    fit = linear_lstsq(Phi, Y, names, method="one-step", model=model, dof=DOF[i],
                       covariance=covariance, lags=lags, what=f"{source}: one-step regression")
    fv, fx = VELOCITIES[i], FORCES[i]
    lin_u = "m/s" if i < 3 else "rad/s"
    fit.units.update({"alpha": "1/s", "beta": "1/m" if i < 3 else "1/rad",
                      "gamma": "1/kg" if i < 3 else "1/(kg m^2)",
                      "delta": "m/s^2" if i < 3 else "rad/s^2"})
    u_lin = "N s/m" if i < 3 else "N m s/rad"
    u_quad = "N s^2/m^2" if i < 3 else "N m s^2/rad^2"
    if "gamma" in names:
        if abs(fit.value("gamma")) > 0:
            fit.derive("inertia_total", lambda p: 1.0 / p["gamma"],
                       unit="kg" if i < 3 else "kg m^2")
            if "alpha" in names:
                fit.derive(f"{fx}_{fv}", lambda p: p["alpha"] / p["gamma"], unit=u_lin)
            if "beta" in names:
                fit.derive(f"{fx}_{fv}{fv}", lambda p: p["beta"] / p["gamma"], unit=u_quad)
            if "delta" in names:
                fit.derive("bias", lambda p: p["delta"] / p["gamma"], unit="N" if i < 3 else "N m")
            if inertia is not None:
                fit.derive(f"{fx}_{fv}dot", lambda p: inertia - 1.0 / p["gamma"],
                           unit="kg" if i < 3 else "kg m^2")
                fit.notes.append(f"rigid-body inertia {inertia:g} assumed exact")
    # free-run re-simulation of the identified equation with the measured input
    sim = simulate_state(t, n, y[0], fit.parameters, model)
    fit.data.update({"t": t, "y": y, "velocity": y, "input": n, "simulated": sim,
                     "one_step": y[:-1] + fit.data["fitted"]})
    fit.rms_error = float(np.sqrt(np.mean(fit.residuals ** 2)))
    free = float(np.sqrt(np.mean((sim - y) ** 2))) if np.all(np.isfinite(sim)) else float("inf")
    fit.metrics["free_run_rms"] = free
    if np.isfinite(free):
        fit.metrics["free_run_runs_z"] = runs_test_z(sim - y)
    fit.notes.append(f"rms_error = one-step-ahead prediction RMS [{lin_u}]; free_run_rms = RMS "
                     f"of the re-simulated {fv} with the measured input; free_run_runs_z = runs "
                     "test of its sign (below -3: systematic error, a missing term)")
    return fit


def simulate_state(t, n, x0, params: dict, model: str = "LQB", *, substeps: int = 2) -> np.ndarray:
    r"""Integrate :math:`\dot x = \phi(x, n)\theta` through the sample times, ``n`` linearly
    interpolated (classical Runge-Kutta 4, ``substeps`` steps per sample).  Returns inf after
    a blow-up (|x| > 1e6).

    .. math:: \dot x = \alpha x + \beta x|x| + \gamma n + \delta

    (Wang & Clark 2006, eq. 8; terms absent from ``model`` are zero). ``t`` [s]; ``x0`` and the result
    [m/s or rad/s]; ``n`` [N, N m or command]; alpha [1/s], beta [1/m or 1/rad], gamma
    [1/kg or 1/(kg m^2), or per command], delta [m/s^2 or rad/s^2].
    """
    t = np.asarray(t, dtype=float)
    n = np.asarray(n, dtype=float)
    p = {k: float(params.get(k, 0.0)) if k in _terms(model) else 0.0 for k in PARAMS}
    a, b, c, d = p["alpha"], p["beta"], p["gamma"], p["delta"]
    fabs = abs
    out = np.full(t.size, np.inf)
    x = float(x0)
    out[0] = x
    for k in range(1, t.size):
        h = (t[k] - t[k - 1]) / substeps
        n0, n1 = n[k - 1], n[k]
        for j in range(substeps):
            s0 = j / substeps
            na = n0 + (n1 - n0) * s0
            nm = n0 + (n1 - n0) * (s0 + 0.5 / substeps)
            nb = n0 + (n1 - n0) * (s0 + 1.0 / substeps)
            k1 = a * x + b * x * fabs(x) + c * na + d
            y = x + 0.5 * h * k1
            k2 = a * y + b * y * fabs(y) + c * nm + d
            y = x + 0.5 * h * k2
            k3 = a * y + b * y * fabs(y) + c * nm + d
            y = x + h * k3
            k4 = a * y + b * y * fabs(y) + c * nb + d
            x += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not fabs(x) < 1e6:
            return out
        out[k] = x
    return out


def one_step_log(log, dof: str, *, model: str = "LQB", input=None, inertia=None,
                 window: int = 15, order: int = 3, covariance: str | None = None) -> FitResult:
    """:func:`one_step` on a log: velocity column, or Savitzky-Golay derivative of the pose.

    ``input`` overrides the force column (e.g. thrust mapped from commands by a vehicle).
    """
    i = parse_dof(dof)
    t = log.require("t")
    vname, pname, fname = VELOCITIES[i], POSE[i], FORCES[i]
    lags = 2
    if vname in log:
        y = log[vname]
        cov = covariance or "ma1"
    elif pname in log:
        pose = np.unwrap(log[pname]) if i >= 3 else log[pname]     # angles may wrap at pi
        y = velocity_from_pose(t, pose, window=window, order=order)
        lags = window + 1
        cov = covariance or "hac"
    else:
        log.require(vname)
    n = np.asarray(input, dtype=float) if input is not None else log.require(fname)
    fit = one_step(t, y, n, model=model, dof=DOF[i], inertia=inertia, covariance=cov,
                   lags=lags, source=log.source)
    if vname not in log:
        fit.notes.append(f"{vname} from the Savitzky-Golay derivative of {pname} "
                         f"(window {window}, order {order}); covariance lags = window + 1")
    return fit


def videoray_table_i(alpha=0.6199, beta=1.1219, gamma=26.95, izz=0.02532) -> dict:
    r"""Wang & Clark's (2006) yaw coefficients from their printed alpha, beta, gamma and I_zz (Table I).

    Magnitudes, as Table I prints them:
    :math:`|N_r| = \alpha/\gamma`, :math:`|N_{r|r|}| = \beta/\gamma`,
    :math:`|N_{\dot r}| = 1/\gamma - I_{zz}`.

    alpha [1/s], beta [1/rad], gamma [1/(kg m^2)], izz [kg m^2]; returns N_r [N m s/rad],
    N_rr [N m s^2/rad^2], N_rdot and inertia_total [kg m^2]. Derivation: module docstring.
    """
    return {"N_r": alpha / gamma, "N_rr": beta / gamma, "N_rdot": 1.0 / gamma - izz,
            "inertia_total": 1.0 / gamma}
