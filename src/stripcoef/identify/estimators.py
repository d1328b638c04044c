r"""Linear least squares with honest error bars: the core every identification method uses.

The papers all reduce identification to a linear regression

.. math:: y = H\theta + \varepsilon

solved by ordinary least squares (Caccia, Indiveri 1998, eqs. 4.5, 4.6, 4.12; Wang & Clark,
Wang & Clark 2006, eq. 18; Eng et al., Eng et al. 2009, eqs. 6-7):

.. math::
    \hat\theta = (H^T H)^{-1} H^T y, \qquad
    \hat\sigma^2 = \frac{(y - H\hat\theta)^T (y - H\hat\theta)}{N - p}, \qquad
    \operatorname{cov}\hat\theta = \hat\sigma^2 (H^T H)^{-1}

with the relative error :math:`100\,\hat\sigma_\theta / |\hat\theta|` [%] (Indiveri 1998, Table I)
and the cost :math:`J_{LS} = \sum \varepsilon^2` (Indiveri 1998, yaw tables).

The i.i.d. covariance above is honest only when the residuals are uncorrelated. Residuals
built from smoothed derivatives (Savitzky-Golay) or from differenced samples (one-step-ahead
prediction) are correlated over a few samples, and the i.i.d. formula then understates the
uncertainty. ``covariance="hac"`` uses the Newey-West heteroskedasticity-and-autocorrelation
consistent estimator instead (Newey & West, Econometrica 55 (1987) 703-708, eq. 2 with
Bartlett weights :math:`1 - l/(L+1)`):

.. math::
    \operatorname{cov}\hat\theta = (H^T H)^{-1}\, \hat S\, (H^T H)^{-1}, \qquad
    \hat S = \sum_k e_k^2 h_k h_k^T + \sum_{l=1}^{L} w_l \sum_k e_k e_{k-l}
             (h_k h_{k-l}^T + h_{k-l} h_k^T)

scaled by :math:`N/(N-p)` (the same small-sample correction as :math:`\hat\sigma^2`).

Information criteria (Akaike 1974; Schwarz 1978; Hurvich & Tsai 1989 small-sample AICc),
for Gaussian residuals with unknown variance:

.. math::
    AIC = N \ln(J/N) + 2p, \quad BIC = N \ln(J/N) + p \ln N, \quad
    AICc = AIC + \frac{2p(p+1)}{N - p - 1}
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from stripcoef.errors import InputError

COVARIANCES = ("iid", "hac", "ma1")


@dataclass
class FitResult:
    r"""Result of one identification: estimates, uncertainties, residuals and fit quality.

    Attributes
    ----------
    method : str
        Identification method (``steady``, ``one-step``, ``pendulum``, ``torsion``, ``lstsq``).
    model : str
        Model name within the method (``eta``, ``LQB``, ``yaw``...).
    dof : str
        Degree of freedom (``heave``, ``yaw``...), or ``""``.
    names : list of str
        Names of the estimated parameters, in the order of the regressor columns.
    theta : (p,) array
        Estimates.
    cov : (p, p) array
        Covariance of the estimates.
    residuals : (N,) array
        :math:`y - H\hat\theta` in the units of ``y``.
    cost : float
        :math:`J_{LS}` = residual sum of squares [units of y squared].
    n_obs : int
        Number of observations N.
    covariance : str
        How ``cov`` was computed: ``"iid"`` or ``"hac(L)"``.
    derived : dict
        Derived quantities by name -> (value, std), e.g. SNAME coefficients.
    rms_error : float or None
        RMS of the method's natural error (e.g. re-simulated angle [rad]); defaults to the
        RMS of the residuals.
    units : dict
        Units of parameters by name (for tables).
    notes : list of str
        Assumptions and warnings to show with the result.
    metrics : dict
        Other scalar measures of fit by name (e.g. ``free_run_rms``), serialised as "metrics".
    data : dict
        Arrays for plots (``y``, ``fitted``, ``x`` velocity, ``t``...); not serialised.
    """

    method: str
    model: str
    dof: str
    names: list
    theta: np.ndarray
    cov: np.ndarray
    residuals: np.ndarray
    cost: float
    n_obs: int
    covariance: str = "iid"
    derived: dict = field(default_factory=dict)
    rms_error: float | None = None
    units: dict = field(default_factory=dict)
    notes: list = field(default_factory=list)
    metrics: dict = field(default_factory=dict)
    data: dict = field(default_factory=dict, repr=False)

    # -- sizes and quality --------------------------------------------------
    @property
    def n_params(self) -> int:
        return len(self.names)

    @property
    def degrees_of_freedom(self) -> int:
        """N - p [-] (Indiveri 1998's nu, eq. 4.12)."""
        return self.n_obs - self.n_params

    @property
    def sigma2(self) -> float:
        r""":math:`\hat\sigma^2 = J_{LS} / (N - p)` [units of y squared] (Indiveri 1998, eq. 4.12)."""
        return self.cost / self.degrees_of_freedom

    @property
    def residual_rms(self) -> float:
        return math.sqrt(self.cost / self.n_obs)

    @property
    def aic(self) -> float:
        """Akaike information criterion, Gaussian residuals, variance estimated.

        AIC = N ln(J_LS / N) + 2 p [-] (Akaike 1974; Ljung 1999, ch. 16), p = :attr:`n_params`
        (the noise variance is not counted: a constant offset for all candidates).
        """
        return _loglik_term(self.cost, self.n_obs) + 2.0 * self.n_params

    @property
    def aicc(self) -> float:
        """Small-sample AIC (Hurvich & Tsai 1989); inf when N - p - 1 <= 0.

        AICc = AIC + 2 p (p + 1) / (N - p - 1) [-].
        """
        k = self.n_params
        d = self.n_obs - k - 1
        return self.aic + (2.0 * k * (k + 1) / d if d > 0 else math.inf)

    @property
    def bic(self) -> float:
        """Schwarz (Bayesian) information criterion.

        BIC = N ln(J_LS / N) + p ln N [-] (Schwarz 1978).
        """
        return _loglik_term(self.cost, self.n_obs) + self.n_params * math.log(self.n_obs)

    # -- parameters -----------------------------------------------------------
    @property
    def estimated_std(self) -> np.ndarray:
        return np.sqrt(np.clip(np.diag(self.cov), 0.0, None))

    @property
    def parameters(self) -> dict:
        """Estimated then derived parameters, name -> value."""
        out = {n: float(v) for n, v in zip(self.names, self.theta)}
        out.update({n: float(v) for n, (v, _) in self.derived.items()})
        return out

    @property
    def std(self) -> dict:
        """Standard deviations, name -> value (same keys as :attr:`parameters`)."""
        out = {n: float(s) for n, s in zip(self.names, self.estimated_std)}
        out.update({n: float(s) for n, (_, s) in self.derived.items()})
        return out

    @property
    def relative_error_percent(self) -> dict:
        r""":math:`100\,\sigma/|\theta|` [%] (Indiveri 1998, Table I); inf for a zero estimate."""
        p, s = self.parameters, self.std
        return {n: (100.0 * s[n] / abs(p[n]) if p[n] != 0.0 else math.inf) for n in p}

    def value(self, name: str) -> float:
        try:
            return self.parameters[name]
        except KeyError:
            raise InputError("unknown parameter", key="parameter", value=name,
                             expected="one of " + ", ".join(self.parameters)) from None

    def correlation(self) -> np.ndarray:
        s = self.estimated_std
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.cov / np.outer(s, s)

    def derive(self, name: str, func: Callable[[dict], float], *, unit: str = "") -> float:
        r"""Add a derived quantity ``func(parameters)`` with its delta-method std.

        .. math:: \sigma_f^2 = \nabla f^T \operatorname{cov}\hat\theta\, \nabla f

        (first-order error propagation; the gradient by central differences).
        ``func`` receives a dict of the estimated and already derived values.
        """
        base = self.parameters
        value = float(func(base))
        grad = np.zeros(self.n_params)
        for i, (n, v) in enumerate(zip(self.names, self.theta)):
            h = 1e-6 * max(abs(v), 1e-8) if abs(v) > 0 else 1e-8
            plus = dict(base)
            minus = dict(base)
            plus[n] = v + h
            minus[n] = v - h
            grad[i] = (func(plus) - func(minus)) / (2.0 * h)
        var = float(grad @ self.cov @ grad)
        self.derived[name] = (value, math.sqrt(max(var, 0.0)))
        if unit:
            self.units[name] = unit
        return value

    def to_dict(self) -> dict:
        """The JSON contract (issue 6): keys other tools depend on."""
        def num(x):
            x = float(x)
            return x if math.isfinite(x) else None
        return {
            "method": self.method,
            "model": self.model,
            "dof": self.dof,
            "parameters": {k: num(v) for k, v in self.parameters.items()},
            "std": {k: num(v) for k, v in self.std.items()},
            "relative_error_percent": {k: num(v) for k, v in
                                       self.relative_error_percent.items()},
            "cost": num(self.cost),
            "degrees_of_freedom": int(self.degrees_of_freedom),
            "rms_error": num(self.rms_error if self.rms_error is not None
                             else self.residual_rms),
            "n_obs": int(self.n_obs),
            "covariance": self.covariance,
            "aic": num(self.aic),
            "aicc": num(self.aicc),
            "bic": num(self.bic),
            "units": dict(self.units),
            "notes": list(self.notes),
            "metrics": {k: num(v) for k, v in self.metrics.items()},
        }


def _loglik_term(cost: float, n: int) -> float:
    return n * math.log(max(cost, 1e-300) / n)


#: Largest magnitude whose square is finite in double precision [-] (IEEE 754 binary64).
_SQUARE_LIMIT = math.sqrt(np.finfo(float).max)


def linear_lstsq(H, y, names, *, method: str = "lstsq", model: str = "", dof: str = "",
                 covariance: str = "iid", lags: int = 0, units: dict | None = None,
                 what: str = "regression") -> FitResult:
    r"""Ordinary least squares :math:`\hat\theta = (H^T H)^{-1} H^T y` with its covariance.

    Parameters
    ----------
    H : (N, p) array
        Regressor matrix [units of y per unit of theta].
    y : (N,) array
        Measurement vector.
    names : sequence of str
        Parameter names, one per column of H.
    covariance : {"iid", "hac", "ma1"}
        ``iid``: :math:`\hat\sigma^2 (H^TH)^{-1}` (Indiveri 1998, eqs. 4.6, 4.12);
        ``hac``: Newey-West with ``lags`` lags (for correlated residuals);
        ``ma1``: sandwich :math:`(H^TH)^{-1} H^T \Sigma H (H^TH)^{-1}` with
        :math:`\Sigma = \hat\sigma^2 (I + \hat\rho (S + S^T))`, S the one-sample shift and
        :math:`\hat\rho` the lag-1 residual autocorrelation clipped to [-1/2, 1/2] - the
        structure of differenced white measurement noise (one-step-ahead residuals).
    lags : int
        Number of lags L for ``hac`` (about the correlation length of the residuals).
    what : str
        Description used in error messages.

    Returns
    -------
    FitResult

    Raises
    ------
    InputError
        Shapes disagree, non-finite data, N <= p, or a column that the data cannot
        determine (rank deficiency; the message names the parameter).

    References
    ----------
    Ljung, System Identification (1999), sec. 7.3 and 9.2; Caccia (Indiveri 1998) eqs. 4.5-4.12.
    """
    H = np.asarray(H, dtype=float)
    y = np.asarray(y, dtype=float).reshape(-1)
    names = list(names)
    if H.ndim != 2 or H.shape[0] != y.size or H.shape[1] != len(names):
        raise InputError("regressor shape mismatch", key=what, value=H.shape,
                         expected=f"({y.size}, {len(names)}) for parameters {names}")
    if covariance not in COVARIANCES:
        raise InputError("unknown covariance estimator", key="covariance", value=covariance,
                         expected="one of " + ", ".join(COVARIANCES))
    n, p = H.shape
    if n <= p:
        raise InputError("too few observations", key=what, value=n,
                         expected=f"more than {p} (one per parameter {', '.join(names)}, "
                         "plus at least one for the noise variance)")
    bad = ~np.isfinite(H).all(axis=1) | ~np.isfinite(y)
    if bad.any():
        raise InputError("non-finite value in the regression", key=what,
                         value=f"observation {int(np.nonzero(bad)[0][0])}", expected="finite data")
    # A value whose square overflows (|x| > sqrt(max double), about 1.34e154) makes the sums of
    # squares of the cost and the covariance overflow, or not, depending on the BLAS kernel's
    # order of operations (an exact fit passed on one CPU and overflowed on another): refused
    # here, by the same rule on every machine.
    if max(np.abs(H).max(), np.abs(y).max()) > _SQUARE_LIMIT:
        _refuse_magnitudes(H, y, names, what)
    # Scale columns for conditioning, then QR (the norm of each column divided by its
    # largest entry first: a 1e300 entry squared would overflow to inf)
    peak = np.abs(H).max(axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        scale = peak * np.sqrt(((H / np.where(peak > 0, peak, 1.0)) ** 2).sum(axis=0))
    for j, s in enumerate(scale):
        if s == 0.0:
            raise InputError("parameter not identifiable: its regressor column is all zero",
                             key=what, value=names[j],
                             expected="data that excite this term (e.g. both directions)")
    Hs = H / scale
    q, r = np.linalg.qr(Hs)
    dr = np.abs(np.diag(r))
    if not dr.min() >= 1e-10 * dr.max():          # also NaN: nothing to solve
        if not np.all(np.isfinite(dr)):
            _refuse_magnitudes(H, y, names, what)
        # the column that is (nearly) a combination of the previous ones
        j = int(np.argmin(dr))
        raise InputError("parameter not identifiable: regressor column is a combination of the "
                         "others", key=what, value=names[j],
                         expected="data that separate it (vary the inputs, or drop the term)")
    with np.errstate(over="ignore", invalid="ignore"):
        theta_s = np.linalg.solve(r, q.T @ y)
        theta = theta_s / scale
        resid = y - H @ theta
        cost = float(resid @ resid)
    if not (np.all(np.isfinite(theta)) and math.isfinite(cost)):
        _refuse_magnitudes(H, y, names, what)
    rinv = np.linalg.inv(r)
    xtx_inv_s = rinv @ rinv.T                     # (Hs^T Hs)^-1
    xtx_inv = xtx_inv_s / np.outer(scale, scale)  # (H^T H)^-1
    dof_ = n - p
    if covariance == "iid":
        cov = cost / dof_ * xtx_inv
        label = "iid"
    elif covariance == "ma1":
        # OLS sandwich under MA(1) residuals: Sigma = s2 (I + rho (S + S^T)), |rho| <= 1/2
        rho = float(resid[1:] @ resid[:-1]) / cost if cost > 0 else 0.0
        rho = min(max(rho, -0.5), 0.5)
        s2 = cost / dof_
        sh = Hs.T @ Hs + rho * (Hs[1:].T @ Hs[:-1] + Hs[:-1].T @ Hs[1:])
        cov_s = s2 * xtx_inv_s @ sh @ xtx_inv_s
        cov = cov_s / np.outer(scale, scale)
        label = f"ma1(rho={rho:.3f})"
    else:
        lags = int(max(lags, 0))
        hs = Hs * resid[:, None]
        s = hs.T @ hs
        for lag in range(1, min(lags, n - 1) + 1):
            w = 1.0 - lag / (lags + 1.0)
            g = hs[lag:].T @ hs[:-lag]
            s += w * (g + g.T)
        cov_s = xtx_inv_s @ s @ xtx_inv_s * (n / dof_)
        cov = cov_s / np.outer(scale, scale)
        label = f"hac({lags})"
    if not np.all(np.isfinite(cov)):
        _refuse_magnitudes(H, y, names, what)
    return FitResult(method=method, model=model, dof=dof, names=names, theta=theta, cov=cov,
                     residuals=resid, cost=cost, n_obs=n, covariance=label,
                     units=dict(units or {}),
                     data={"y": y, "fitted": H @ theta, "H": H})


def _refuse_magnitudes(H, y, names, what):
    """The regression overflows (a value near 1e300 among ordinary ones): an error naming the
    observation of largest magnitude, instead of a non-finite estimate or error bar."""
    peak_h = np.abs(H).max(axis=1)
    k = int(np.argmax(np.maximum(peak_h, np.abs(y))))
    value = float(y[k]) if abs(y[k]) >= peak_h[k] else float(H[k, np.argmax(np.abs(H[k]))])
    raise InputError("the regression overflows (estimates or error bars not finite)", key=what,
                     value=f"{value:.4g} at observation {k}",
                     expected=f"data of ordinary magnitudes for the parameters "
                              f"{', '.join(names)} (check the units and that value)")


def residual_autocorrelation(residuals, max_lag: int = 20) -> np.ndarray:
    r"""Sample autocorrelation :math:`\rho_l` of the residuals for l = 0..max_lag [-].

    A well-specified model fitted to white-noise data has :math:`|\rho_l| \lesssim 2/\sqrt N`
    for l >= 1 (Ljung 1999, sec. 16.6); structure there means a missing term.
    """
    e = np.asarray(residuals, dtype=float) - np.mean(residuals)
    d = float(e @ e)
    n = e.size
    return np.array([float(e[lag:] @ e[:n - lag]) / d if d > 0 else 0.0
                     for lag in range(min(max_lag, n - 1) + 1)])


def runs_test_z(residuals) -> float:
    r"""Wald-Wolfowitz runs test on the signs of the residuals: z-score [-].

    .. math:: z = \frac{R - \mu_R}{\sigma_R}, \quad \mu_R = \frac{2 n_+ n_-}{n} + 1, \quad
              \sigma_R^2 = \frac{(\mu_R - 1)(\mu_R - 2)}{n - 1}

    Strongly negative z (too few runs) means residuals are systematic: a model error
    (Draper & Smith, Applied Regression Analysis, 3rd ed., sec. 7.3).
    """
    s = np.sign(np.asarray(residuals, dtype=float))
    s = s[s != 0]
    n = s.size
    npos = int((s > 0).sum())
    nneg = n - npos
    if npos == 0 or nneg == 0:
        return -math.inf
    runs = 1 + int((s[1:] != s[:-1]).sum())
    mu = 2.0 * npos * nneg / n + 1.0
    var = (mu - 1.0) * (mu - 2.0) / (n - 1.0)
    return (runs - mu) / math.sqrt(var) if var > 0 else 0.0
