r"""The MAP least-squares fit of one DOF's window residual: calibration columns, effects'
regressors and their band priors.

- :func:`_solve`: maximum a posteriori least squares with Gaussian band priors (Tarantola
  2005, eq. 3.37), the inertia change profiled on the noise-corrected cost (Golub & Pereyra
  1973; Fuller 1987, sec. 2.2);
- :class:`Calibration` (:func:`_calibration`): the prior's own coefficients of a DOF as
  columns, with their bands; :func:`_identifiability` (Ljung 1999, eq. 9.29);
- :class:`_Config`: the calibration plus a list of effects, its design matrix and bounds;
  :func:`_evaluate`: its fit on all windows and its blocked cross-validation;
- :func:`fit_effects`: a fixed list of effects fitted with the calibration.

Depends on: effects, identify (residual statistics), diagnose.settings, diagnose.priors.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from scipy.optimize import least_squares, lsq_linear

from stripcoef.conventions import DOF, parse_dof
from stripcoef.diagnose.couplings import coupling_bounds, coupling_dof, coupling_keys
from stripcoef.diagnose.priors import TERM_MATRIX, added_mass_bounds
from stripcoef.diagnose.settings import (DEFAULT_WINDOW, MIN_INFORMATION_RATIO, N_BLOCKS,
                                         UNLIMITED, Budget, DiagnoseSettings)
from stripcoef.effects.laws import WindowData, coefficient_column, get_effect
from stripcoef.effects.windows import window_data

#: The settings of a fit outside a diagnosis (:func:`fit_effects`, tests): the fixed bands.
DEFAULTS = DiagnoseSettings()
#: Most command levels the dead band's fine search evaluates between its coarse neighbours
#: (:func:`_profile_hyper`) [-].
FINE_LEVELS = 100


# ---------------------------------------------------------------------------
# least squares with band priors
# ---------------------------------------------------------------------------

def _solve(y, H, prior_sd, sigma, lower=None, m=None, upper=None, *, with_cov=True):
    r"""MAP least squares: min |y - H theta|^2 / sigma^2 + sum_j (theta_j / s_j)^2,
    subject to theta >= lower (physical bounds: no negative added mass or damping).

    ``m = (columns, M, v)``: the columns that multiply the acceleration (inertia changes
    :math:`\mu`, collinear), the prior inertia M of the DOF and the variance v of the
    measured window acceleration's noise. The force balance is homogeneous: scaling
    inertia, damping and thrust together leaves it unchanged, while the velocity noise
    enters the residual as :math:`(M + \mu) n`; a plain fit follows that noise and shrinks
    everything (errors in variables). :math:`\mu` is therefore profiled (variable
    projection, Golub & Pereyra 1973) on the cost corrected for the expected noise term,
    :math:`J(\mu) - N (M + \mu)^2 v / \sigma^2` (corrected least squares, Fuller 1987,
    Measurement Error Models, sec. 2.2).

    ``upper``: upper bounds (an added mass within its plausible factor of the prior,
    :data:`ADDED_MASS_FACTOR`).

    Returns theta, covariance (the unconstrained one at the solution; None with
    ``with_cov=False``, for the fits that need only theta or the residual), weighted residual.
    """
    if m is not None and len(m[0]):
        return _solve_profiled(y, H, prior_sd, sigma, lower, m, upper, with_cov=with_cov)
    return _solve_linear(y, H, prior_sd, sigma, lower, upper=upper, with_cov=with_cov)


def _linear_system(H, prior_sd, sigma, weight=1.0, *, factor=False) -> tuple:
    r"""(a, a / scale, column scale, prior rows, pseudo-inverse) of :func:`_solve_linear`'s
    stacked system: the same for every right-hand side y (the profiled inertia tries several).

    ``factor``: with the pseudo-inverse :math:`A_s^+ = V \Sigma^{-1} U^T` of the scaled
    matrix (its singular value decomposition, the singular values at or below
    :math:`\epsilon \max(m, n)\,\sigma_1` dropped: the cut-off of ``numpy.linalg.lstsq``
    with ``rcond=None``, whose minimum-norm solution :math:`A_s^+ b` it then gives; Golub &
    Van Loan 2013, Matrix Computations, sec. 5.5), built once so that each right-hand side costs one product
    instead of a decomposition; else None (a system solved once)."""
    p = H.shape[1]
    rows = [H * weight / sigma]
    finite = np.isfinite(prior_sd)
    if finite.any():
        reg = np.zeros((int(finite.sum()), p))
        reg[np.arange(reg.shape[0]), np.nonzero(finite)[0]] = 1.0 / prior_sd[finite]
        rows.append(reg)
    a = np.vstack(rows)
    scale = np.sqrt((a ** 2).sum(axis=0))
    scale[scale == 0] = 1.0
    a_s = a / scale
    pinv = None
    if factor:
        u, sv, vt = np.linalg.svd(a_s, full_matrices=False)
        keep = sv > np.finfo(float).eps * max(a_s.shape) * sv[0] if sv.size else sv > 0
        pinv = (vt[keep].T / sv[keep]) @ u[:, keep].T
    return a, a_s, scale, a.shape[0] - H.shape[0], pinv


def _solve_linear(y, H, prior_sd, sigma, lower=None, weight=1.0, upper=None, *,
                  with_cov=True, system=None):
    """:func:`_solve` without inertia columns; ``with_cov=False`` skips the covariance
    (None in its place: a cost evaluation needs only the residual); ``system``: the
    :func:`_linear_system` of H, prior_sd, sigma and weight, built once by the caller."""
    p = H.shape[1]
    if p == 0:
        return np.zeros(0), np.zeros((0, 0)), y * weight / sigma
    a, a_s, scale, n_prior, pinv = _linear_system(H, prior_sd, sigma, weight) \
        if system is None else system
    b = np.concatenate([y * weight / sigma, np.zeros(n_prior)])
    theta_s = np.linalg.lstsq(a_s, b, rcond=None)[0] if pinv is None else pinv @ b
    low_bad = lower is not None and np.any(theta_s / scale < lower)
    up_bad = upper is not None and np.any(theta_s / scale > upper)
    if low_bad or up_bad:
        lb = (np.full(p, -np.inf) if lower is None
              else np.where(np.isfinite(lower), lower * scale, -np.inf))
        ub = (np.full(p, np.inf) if upper is None
              else np.where(np.isfinite(upper), upper * scale, np.inf))
        theta_s = lsq_linear(a_s, b, bounds=(lb, ub), method="bvls").x
    theta = theta_s / scale
    if not with_cov:
        return theta, None, b - a @ theta
    cov = np.linalg.pinv(a_s.T @ a_s) / np.outer(scale, scale)
    return theta, cov, b - a @ theta


def _solve_profiled(y, H, prior_sd, sigma, lower, m, upper=None, *, with_cov=True):
    from scipy.optimize import minimize_scalar

    mcols, m_total, noise_var = list(m[0]), float(m[1]), float(m[2])
    keep = [j for j in range(H.shape[1]) if j not in mcols]
    rate = H[:, mcols[0]]
    msd = prior_sd[mcols]
    mu_sd = np.inf if not np.all(np.isfinite(msd)) else float(np.sqrt(np.sum(msd ** 2)))
    lo = -0.95 * m_total
    if lower is not None:
        lo = max(lo, float(np.max(lower[mcols])))
    X, sdx = H[:, keep], prior_sd[keep]
    lowx = None if lower is None else lower[keep]
    upx = None if upper is None else upper[keep]

    # built and factored once: the profile below solves it for five or more values of mu
    system = _linear_system(X, sdx, sigma, factor=True) if X.shape[1] else None

    def inner(mu, with_cov=True):
        th, cov, res = _solve_linear(y - mu * rate, X, sdx, sigma, lowx, upper=upx,
                                     with_cov=with_cov, system=system)
        extra = np.array([mu / mu_sd]) if np.isfinite(mu_sd) else np.zeros(0)
        return th, cov, np.concatenate([res, extra])

    def cost(mu):
        return float(np.sum(inner(mu, False)[2] ** 2)) \
            - y.size * (m_total + mu) ** 2 * noise_var / sigma ** 2

    hi = 5.0 * m_total
    if upper is not None:
        hi = min(hi, float(np.min(upper[mcols])))
    # without active bounds the profiled cost is exactly quadratic in mu (a linear
    # least-squares residual of y - mu * rate, plus quadratic prior and noise terms):
    # three evaluations give its vertex; otherwise fall back to a bounded search. The
    # vertex is taken only where the cost there is the quadratic's own value: a bound
    # active at the three points and not at the vertex (or the reverse) makes the cost
    # piecewise quadratic, and the parabola through the three points then has its vertex
    # away from the minimum, though below the three (issue 33: a BlueROV2-like surge log
    # with a 2.5x added mass, seed 29113033, where a cross added mass sat at its lower
    # bound near mu = 0: the vertex mu = 6.5 with a cost of 52 beside the minimum 9.2 with
    # 0.04, and a thrust scale named in the added mass's place)
    h = 0.1 * m_total
    c0, cp, cm = cost(0.0), cost(h), cost(-h)
    curv = (cp - 2 * c0 + cm) / h ** 2
    mu = None
    if curv > 0:
        slope = (cp - cm) / (2 * h)
        cand = float(np.clip(-slope / curv, lo, hi))
        quadratic = c0 + slope * cand + 0.5 * curv * cand ** 2
        tol = 1e-6 * max(abs(c0), abs(cp), abs(cm), 1.0)
        if abs(cost(cand) - quadratic) <= tol:
            mu = cand
    if mu is None:
        sol = minimize_scalar(cost, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-6 * m_total})
        mu = float(sol.x)
    th, covx, res = inner(mu, with_cov)
    theta = np.zeros(H.shape[1])
    theta[keep] = th
    if not with_cov:
        theta[_inertia_column(mcols, prior_sd, mu_sd)] = mu
        return theta, None, res
    if not (curv > 0 and lo + h <= mu <= hi - h):
        c0, cp, cm = cost(mu), cost(min(mu + h, hi)), cost(max(mu - h, lo))
        curv = (cp - 2 * c0 + cm) / h ** 2
    var_mu = 2.0 / curv if curv > 0 else np.inf
    cov = np.zeros((H.shape[1], H.shape[1]))
    cov[np.ix_(keep, keep)] = covx
    j = _inertia_column(mcols, prior_sd, mu_sd)
    theta[j] = mu
    cov[j, j] = var_mu
    return theta, cov, res


def _inertia_column(mcols, prior_sd, mu_sd) -> int:
    """The column the profiled inertia change goes to: the first inertia column, or with a
    released (free) one, that one."""
    if not np.isfinite(mu_sd):
        return next((c for c in mcols if not np.isfinite(prior_sd[c])), mcols[-1])
    return mcols[0]


@dataclass(frozen=True)
class Calibration:
    """The calibration of one DOF (:func:`_calibration`): the window columns of its
    coefficients (n_windows, k), the sd of each correction's Gaussian prior [units of the
    coefficient], their names (``M``, ``D_L``, ``D_Q``, ``M_<dof>``), their prior values and
    the relative bands by name [-]."""

    cols: np.ndarray
    sd: np.ndarray
    names: tuple
    prior: np.ndarray
    band: Mapping

    def subset(self, keep) -> Calibration:
        """The calibration of the columns ``keep`` (indices) only."""
        keep = list(keep)
        return Calibration(self.cols[:, keep], np.asarray(self.sd, float)[keep],
                           tuple(self.names[j] for j in keep),
                           np.asarray(self.prior, float)[keep], self.band)


class _Config:
    """Calibration columns + accepted effects (+ a candidate) for one DOF.

    ``settings`` (:class:`DiagnoseSettings`: the added-mass bands) and ``budget``
    (:class:`Budget`, checked at every design) are those of the running diagnosis."""

    def __init__(self, data: WindowData, dof: int, cal: Calibration, terms, *,
                 settings: DiagnoseSettings = DEFAULTS, budget: Budget = UNLIMITED):
        self.data, self.dof, self.cal = data, dof, cal
        self.settings, self.budget = settings, budget
        self.cal_cols, self.cal_sd = cal.cols, np.asarray(cal.sd, float)
        # names of the calibration columns (for recomputing them); None without any
        self.cal_names = list(cal.names) or None
        prior = np.asarray(cal.prior, float)
        # the calibrated coefficient stays >= 0: no negative added mass or drag
        self.cal_lower = -np.abs(prior)
        self.cal_upper = np.full(self.cal_lower.size, np.inf)
        for j, key in enumerate(self.cal_names or ()):
            if key == "M" or key.startswith("M_"):
                owner = dof if key == "M" else parse_dof(key[2:])
                lo, hi = added_mass_bounds(owner, prior[j], settings.band_sd(owner))
                self.cal_lower[j] = max(self.cal_lower[j], lo - prior[j])
                self.cal_upper[j] = hi - prior[j]
            elif coupling_dof(key) is not None:    # a drag coupling keeps its sign
                self.cal_lower[j], self.cal_upper[j] = coupling_bounds(
                    prior[j], cal.band[key])
        self.cal_has_m = (len(self.cal_sd) > 0
                          and float(data.model.added_mass[dof, dof]) != 0.0
                          and (self.cal_names is None or self.cal_names[:1] == ["M"]))
        self.terms = terms  # list of (effect, hyper)

    def with_terms(self, terms, *, budget: Budget | None = None) -> _Config:
        """The same calibration with the terms ``terms`` (a new configuration), under
        ``budget`` (None: this configuration's)."""
        return _Config(self.data, self.dof, self.cal, list(terms), settings=self.settings,
                       budget=self.budget if budget is None else budget)

    def hyper_terms(self, hyper_override=None):
        """(effect, hyper) of each term, the last one's hyper replaced by ``hyper_override``
        when given (the candidate whose nonlinear parameters are being profiled)."""
        last = len(self.terms) - 1
        return [(eff, hyper_override if (hyper_override is not None and k == last) else hyper)
                for k, (eff, hyper) in enumerate(self.terms)]

    def term(self, eff, hyper):
        """:class:`_Term` of ``eff`` at ``hyper`` on this configuration's data and DOF."""
        return _term(self.data, self.dof, eff, hyper)

    def lower(self, hyper_override=None):
        """Lower bounds of all parameters (calibration: coefficient >= 0)."""
        return np.concatenate([self.cal_lower] + [self.term(eff, h).lower for eff, h in
                                                  self.hyper_terms(hyper_override)])

    def upper(self, hyper_override=None):
        """Upper bounds of all parameters (calibration: added mass within its factor)."""
        return np.concatenate([self.cal_upper] + [self.term(eff, h).upper for eff, h in
                                                  self.hyper_terms(hyper_override)])

    def m_info(self, hyper_override=None):
        """(indices of the inertia columns, prior inertia of the DOF) for :func:`_solve`."""
        cols = []
        if self.cal_has_m:
            cols.append(0)
        k = self.cal_cols.shape[1]
        for eff, h in self.hyper_terms(hyper_override):
            n = self.term(eff, h).cols.shape[1]
            if getattr(eff, "inertia", False):
                cols.append(k + n - 1)
            k += n
        # the columns are divided by the residual scale (design): so is their noise
        return (cols, float(self.data.model.mass_matrix[self.dof, self.dof]),
                self.data.rate_noise_variance(self.dof)
                / self.residual_scale(hyper_override) ** 2)

    def residual_scale(self, hyper_override=None) -> float:
        r"""The factor [-] the residual of this configuration is divided by to be in the
        units of the commanded force: the product of its terms' ``residual_scale`` (a
        thrust scale s, :class:`~stripcoef.effects.thrust.ThrustEffectiveness`: the
        balance :math:`s\tau = M\dot\nu + \dots` divided by s), 1 without one. The log
        determines every force only as its ratio to the thrust map, so fits with and
        without a scale are compared in those units."""
        s = 1.0
        for eff, h in self.hyper_terms(hyper_override):
            rule = getattr(eff, "residual_scale", None)
            if rule is not None and h is not None:
                s *= float(rule(h))
        return s

    def calibration_columns(self, hyper_override=None):
        """The calibration columns, at the velocity relative to the water when a term (the
        current) defines it -- drag and added mass act on nu_r (Fossen 2011, eq. 10.1)."""
        for eff, h in self.hyper_terms(hyper_override):
            if h is not None and hasattr(eff, "relative_velocity") and self.cal_names:
                # computed once per effect, parameters and columns (as :func:`_term`)
                key = ("calibration", id(eff), self.dof, tuple(self.cal_names),
                       tuple(np.atleast_1d(np.asarray(h, float)).tolist()))
                cache = self.data.cached("terms", dict)
                hit = cache.get(key)
                if hit is not None and hit[0] is eff:
                    return hit[1]
                nur = eff.relative_velocity(self.data, h)
                cols = np.column_stack([coefficient_column(self.data, self.dof, name, nur)
                                        for name in self.cal_names])
                cache[key] = (eff, cols)
                return cols
        return self.cal_cols

    def design(self, hyper_override=None):
        self.budget.check()
        y = self.data.e0[:, self.dof].copy()
        cols = [self.calibration_columns(hyper_override)]
        sd = [self.cal_sd]
        for eff, h in self.hyper_terms(hyper_override):
            term = self.term(eff, h)
            if term.offset is not None:
                y = y - term.offset
            cols.append(term.cols)
            sd.append(term.sd)
        scale = self.residual_scale(hyper_override)
        if scale != 1.0:      # the residual in the commanded force's units
            return y / scale, np.hstack(cols) / scale, np.concatenate(sd)
        return y, np.hstack(cols), np.concatenate(sd)


@dataclass(frozen=True)
class _Term:
    """One term of a configuration at given nonlinear parameters: its window offset (or
    None) and columns (:meth:`Effect.design`), the prior sd, lower and upper bound of each
    column."""

    offset: np.ndarray | None
    cols: np.ndarray
    sd: np.ndarray
    lower: np.ndarray
    upper: np.ndarray


def _term(data: WindowData, dof: int, eff, hyper) -> _Term:
    """The :class:`_Term` of effect ``eff`` in DOF ``dof`` at ``hyper``, computed once per
    window data: a selection evaluates the same effect at the same parameters in every
    configuration that holds it, each profiling step and each cross-validation fold, and
    each evaluation is a pass over the whole log. Kept in the data's own cache (the data
    are fixed once cut; the effect object is kept with its entry, so that its id is not
    reused)."""
    key = (id(eff), dof, None if hyper is None else
           tuple(np.atleast_1d(np.asarray(hyper, float)).tolist()))
    cache = data.cached("terms", dict)
    hit = cache.get(key)
    if hit is not None and hit[0] is eff:
        return hit[1]
    off, c = eff.design(data, dof, hyper)
    n = c.shape[1]
    # the base rules of an effect's prior sd and bounds ask for the design's width: given
    # here, so that the design (a pass over the log) is not computed twice more
    sized = {"ncols": n}
    sd = eff.prior_sd(data, dof, hyper, **_sized(eff, "prior_sd", sized)) \
        if hasattr(eff, "prior_sd") else np.full(n, np.inf)
    lo = eff.lower_bounds(data, dof, hyper, **_sized(eff, "lower_bounds", sized)) \
        if hasattr(eff, "lower_bounds") else np.full(n, -np.inf)
    up = eff.upper_bounds(data, dof, hyper) if hasattr(eff, "upper_bounds") \
        else np.full(n, np.inf)
    term = _Term(off, c, np.asarray(sd, float), np.asarray(lo, float), np.asarray(up, float))
    cache[key] = (eff, term)
    return term


def _sized(eff, method: str, sized: dict) -> dict:
    """``sized`` when ``eff``'s ``method`` is the base rule of :class:`Effect` (which takes
    the design's width), else no keyword (an effect's own rule)."""
    from stripcoef.effects.base import Effect

    return sized if getattr(type(eff), method, None) is getattr(Effect, method) else {}


class _Nuisance:
    """The nuisance columns of an effect as a term of its own (the reference fit)."""

    hyper = ()

    def __init__(self, effect):
        self.effect = effect
        self.name = effect.name + "(reference)"

    def design(self, data, dof, hyper=None):
        return None, self.effect.nuisance(data, dof)

    def prior_sd(self, data, dof, hyper=None):
        return self.effect.nuisance_sd(data, dof)

    def lower_bounds(self, data, dof, hyper=None):
        return self.effect.nuisance_lower(data, dof)


def _sigma(y, H, sd=None, lower=None, m=None, upper=None):
    """Noise level of the window residual: iterate the MAP fit from sigma = RMS(y) (a free
    fit could follow the scale degeneracy of the force balance to sigma = 0)."""
    if H.shape[1] == 0:
        return max(float(np.sqrt(np.mean(y ** 2))), 1e-12)
    sd = np.full(H.shape[1], np.inf) if sd is None else sd
    sigma = max(float(np.sqrt(np.mean(y ** 2))), 1e-12)
    for _ in range(4):
        theta, _, _ = _solve(y, H, sd, sigma, lower, m, upper, with_cov=False)
        r = y - H @ theta

        p_eff = min(H.shape[1], y.size - 1)
        sigma = max(float(np.sqrt(r @ r / max(y.size - p_eff, 1))), 1e-12)
    return sigma


def sigma_beside_bias(y, H, sd=None) -> float:
    r"""Noise level [units of y] of the window residual :math:`y` with a free constant column
    beside the columns :math:`H` (band sds ``sd``): :func:`_sigma` of :math:`[H, 1]`.

    The Cramer-Rao bound of a coefficient holds the variance of the innovations (Ljung
    1999, sec. 9.2, eq. 9.29); a constant force the prior misses (a buoyancy change, a bias:
    the library's ``buoyancy_offset`` in every DOF) is a term of the model, not noise, and
    left in the residual it inflates every bound by the ratio of its size to the noise's.
    Used by :func:`_identifiability` with ``DiagnoseSettings.noise_with_bias`` only."""
    sd = np.full(H.shape[1], np.inf) if sd is None else np.asarray(sd, float)
    return _sigma(y, np.column_stack([H, np.ones(len(y))]), np.append(sd, np.inf))


def _fit(cfg: _Config, mask=None, hyper=None):
    y, H, sd = cfg.design(hyper)
    lower = cfg.lower(hyper)
    upper = cfg.upper(hyper)
    m = cfg.m_info(hyper)
    yy, HH = (y, H) if mask is None else (y[mask], H[mask])
    sigma = _sigma(yy, HH, sd, lower, m, upper)
    theta, cov, _ = _solve(yy, HH, sd, sigma, lower, m, upper)
    resid = y - H @ theta
    return {"theta": theta, "cov": cov, "resid": resid, "sigma": sigma, "y": y, "H": H,
            "sd": sd}


def grid_minimum(cost, grid) -> tuple[float, float]:
    """``(value, cost(value))``: the minimum of a scalar ``cost`` of one parameter on a
    bounded range, by the ``grid`` (increasing), then a bounded scalar search (Brent's
    method, scipy's ``minimize_scalar``) between the neighbours of the best grid point,
    kept when it is no worse than that point."""
    from scipy.optimize import minimize_scalar

    costs = np.array([cost(c) for c in grid])
    k = int(np.argmin(costs))
    value, best = float(grid[k]), float(costs[k])
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
    if hi > lo:
        sol = minimize_scalar(cost, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-3 * (hi - lo)})
        if sol.fun <= best:
            value, best = float(sol.x), float(sol.fun)
    return value, best


def _profile_hyper(cfg: _Config, mask):
    """Optimise the nonlinear parameters of the last term on the fitting windows."""
    eff, _ = cfg.terms[-1]
    if not eff.hyper:
        return None
    h0 = eff.hyper_start(cfg.data, cfg.dof)
    y0, H0, sd0 = cfg.design(h0)
    sigma0 = _sigma(y0[mask], H0[mask], sd0, cfg.lower(h0), cfg.m_info(h0), cfg.upper(h0))

    def cost_vec(h):
        y, H, sd = cfg.design(h)
        yy, HH = y[mask], H[mask]
        theta, _, wres = _solve(yy, HH, sd, sigma0, cfg.lower(h), cfg.m_info(h), cfg.upper(h),
                                with_cov=False)
        return wres

    if hasattr(eff, "grid"):
        # one nonlinear parameter on a bounded range (a time constant, a delay)
        def cost1(c):
            return float(np.sum(cost_vec(np.array([c])) ** 2))
        return np.array([grid_minimum(cost1, eff.grid(cfg.data, cfg.dof))[0]])

    if eff.name == "deadband":
        cands = eff.candidates(cfg.data, cfg.dof)
        if cands.size == 0:
            return np.array([0.0])
        def cost(c):
            return float(np.sum(cost_vec(np.array([c])) ** 2))

        costs = np.array([cost(c) for c in cands])
        k = int(np.argmin(costs))
        lo = cands[max(k - 1, 0)]
        hi = cands[min(k + 1, cands.size - 1)]
        # fine search: the cost only changes when the threshold crosses a command level of
        # the fitting windows, so evaluate between consecutive levels near the coarse optimum
        act = cfg.data.acting(cfg.dof)
        rows = np.zeros(cfg.data.t.size, bool)
        for a, b in zip(cfg.data.i0[mask], cfg.data.i1[mask]):
            rows[a:b] = True
        levels = np.unique(np.abs(cfg.data.commands[rows][:, act]))
        levels = levels[(levels >= lo) & (levels <= hi)]
        if levels.size > FINE_LEVELS:
            # a long log of continuous commands has thousands of levels here, each a pass
            # over the log: every k-th level (the threshold is then known to the spacing of
            # FINE_LEVELS levels, far below its uncertainty, the coarse grid's, _hyper_std)
            levels = levels[np.round(np.linspace(0, levels.size - 1, FINE_LEVELS)).astype(int)]
        if levels.size >= 2:
            mids = 0.5 * (levels[1:] + levels[:-1])
            fine = np.array([cost(c) for c in mids])
            j = int(np.argmin(fine))
            # the threshold is only known to lie between two levels: take their middle
            return np.array([mids[j]])
        return np.array([cands[k]])
    best = None
    for start in ([0.0, 0.0], [0.2, 0.0], [0.0, 0.2], [-0.2, 0.0], [0.0, -0.2]):
        sol = least_squares(cost_vec, np.asarray(start, float), method="lm", x_scale=0.1)
        if best is None or sol.cost < best.cost:
            best = sol
    return best.x


def _hyper_std(cfg: _Config, hyper, sigma):
    """Std of nonlinear parameters: sigma^2 (J^T J)^-1 of the profiled residual."""
    if hyper is None or len(np.atleast_1d(hyper)) == 0:
        return np.zeros(0)
    eff = cfg.terms[-1][0]
    if eff.name == "deadband":
        # one-sided steps between command levels: take the spacing of the candidate grid
        cands = eff.candidates(cfg.data, cfg.dof)
        h = float(hyper[0])
        if cands.size < 2:
            return np.array([np.nan])
        k = int(np.argmin(np.abs(cands - h)))
        lo = cands[max(k - 1, 0)]
        hi = cands[min(k + 1, cands.size - 1)]
        return np.array([0.5 * (hi - lo) / math.sqrt(3.0)])
    hyper = np.asarray(hyper, float)

    def vec(h):
        y, H, sd = cfg.design(h)
        return _solve(y, H, sd, sigma, cfg.lower(h), cfg.m_info(h), cfg.upper(h),
                      with_cov=False)[2] * sigma

    j = np.empty((vec(hyper).size, hyper.size))
    for k in range(hyper.size):
        step = 1e-4 * max(1.0, abs(hyper[k]))
        hp, hm = hyper.copy(), hyper.copy()
        hp[k] += step
        hm[k] -= step
        j[:, k] = (vec(hp) - vec(hm)) / (2 * step)
    cov = sigma ** 2 * np.linalg.pinv(j.T @ j)
    return np.sqrt(np.clip(np.diag(cov), 0, None))


def _rms(x):
    return float(np.sqrt(np.mean(np.asarray(x) ** 2))) if np.size(x) else float("nan")


def _bic(resid, n_params):
    n = resid.size
    return n * math.log(max(float(resid @ resid), 1e-300) / n) + n_params * math.log(n)



def refit(fits: dict, dof: str, cfg: _Config) -> tuple[dict, dict]:
    """Write a configuration with a shared value in it (one lag, one current) into
    ``fits[dof]``, evaluated again (:func:`_evaluate`); returns the evaluation before and
    after."""
    from dataclasses import replace

    before, ev = fits[dof].evaluation, _evaluate(cfg)
    fits[dof] = replace(fits[dof], config=cfg, evaluation=ev)
    return before, ev


def _evaluate(cfg: _Config):
    """Fit on all windows (parameters, error, BIC) and by blocked cross-validation (the
    held-out error: each of ``N_BLOCKS`` contiguous blocks predicted by a fit on the others).

    The nonlinear parameters of a new term are profiled once on all windows (not per fold):
    a slight optimism for the two effects that have them (current, dead band)."""
    hyper = None
    everything = np.ones(cfg.data.n_windows, bool)
    if cfg.terms and cfg.terms[-1][0].hyper and cfg.terms[-1][1] is None:
        hyper = _profile_hyper(cfg, everything)
        cfg.terms[-1] = (cfg.terms[-1][0], hyper)
    full = _fit(cfg)
    pred = np.empty(cfg.data.n_windows)
    for fold in np.array_split(np.arange(cfg.data.n_windows), N_BLOCKS):
        mask = everything.copy()
        mask[fold] = False
        tr = _fit(cfg, mask)
        pred[fold] = tr["resid"][fold]
    n_free = int(np.sum(~np.isfinite(full["sd"]))) + (
        len(np.atleast_1d(hyper)) if hyper is not None else 0)
    return {"full": full, "held_out_error": _rms(pred), "held_out_resid": pred,
            "error": _rms(full["resid"]), "bic": _bic(full["resid"], n_free),
            "hyper": hyper, "n_free": n_free}


def _calibration(data: WindowData, dof: int, settings: DiagnoseSettings = DEFAULTS,
                 cross=None) -> Calibration:
    r"""Calibration columns and band standard deviations for one DOF.

    The relative bands: :meth:`DiagnoseSettings.band_table` (the bands given, else the
    :class:`~stripcoef.diagnose.priors.PriorWidths` the diagnosis runs with, a vehicle file's
    method-table rows, else :data:`~stripcoef.diagnose.settings.BANDS`); the standard deviation of
    a correction is the band times the prior value's magnitude [units of the coefficient].

    The DOF's own inertia, linear and quadratic damping, and the added mass
    :math:`M_{jj}` of every *other* DOF j that reaches this one through the added-mass
    Coriolis and centripetal force :math:`C_A(\nu)\nu` (Fossen 2011, eq. 6.43: e.g.
    :math:`M_{33}\,w q` and :math:`-M_{22}\,v r` in surge). Those are the prior's own
    coefficients as well, with the band of their DOF: on a log with turns, strip theory's
    error in the sway added mass shows in the surge residual as :math:`\Delta M_{22}\,v r`,
    which no effect of the library should be asked to explain. Their column is the window
    mean of :math:`\partial (C_A(\nu)\nu)_i / \partial M_{jj} = (C_A[E_{jj}](\nu)\nu)_i`
    (C_A is linear in M_A); they are named ``M_<dof>`` (e.g. ``M_sway``) and are omitted
    when that product never moves in the log, or when DOF j is not in ``cross`` (the DOFs
    whose added mass this DOF may calibrate: those that move, a thruster-less one
    included; one value is written, :mod:`stripcoef.diagnose.cross`; None = all).
    """
    bands = settings.band_table()
    kind = "translational" if dof < 3 else "rotational"
    b = dict(bands[kind])
    m = data.model
    cols, sd, names, prior = [], [], [], []
    for key in ("M", "D_L", "D_Q"):
        value = float({"M": m.added_mass, "D_L": m.linear_damping,
                       "D_Q": m.quadratic_damping}[key][dof, dof])
        if value == 0.0:
            continue
        cols.append(coefficient_column(data, dof, key))
        sd.append(b[key] * abs(value))
        names.append(key)
        prior.append(value)
    for j in range(6):
        value = float(m.added_mass[j, j])
        if j == dof or value == 0.0 or (cross is not None and j not in cross):
            continue
        key = "M_" + DOF[j]
        col = coefficient_column(data, dof, key)
        if not np.any(np.abs(col) > 0.0):
            continue
        b[key] = bands["translational" if j < 3 else "rotational"]["M"]
        cols.append(col)
        sd.append(b[key] * abs(value))
        names.append(key)
        prior.append(value)
    # option: a moment DOF's drag couplings D_Q[dof, j], each with the band of the
    # translation j's own D_Q (diagnose.couplings)
    for key in (coupling_keys(m, dof, cross) if settings.drag_couplings else ()):
        j = coupling_dof(key)
        col = coefficient_column(data, dof, key)
        if not np.any(np.abs(col) > 0.0):
            continue
        value = float(m.quadratic_damping[dof, j])
        b[key] = bands["translational"]["D_Q"]
        cols.append(col)
        sd.append(b[key] * abs(value))
        names.append(key)
        prior.append(value)
    cols = np.column_stack(cols) if cols else np.zeros((data.n_windows, 0))
    return Calibration(cols, np.asarray(sd, float), tuple(names), np.asarray(prior, float), b)


def _column_owner(dof: int, name: str) -> int:
    """The DOF [index] whose velocity the calibration coefficient ``name`` of DOF ``dof``
    belongs to: ``dof`` itself for ``M``, ``D_L``, ``D_Q``; j for another DOF's added mass
    ``M_<j>`` and for a drag coupling ``D_Q_<j>`` (:mod:`.couplings`)."""
    if name in TERM_MATRIX:
        return dof
    coupled = coupling_dof(name)
    return coupled if coupled is not None else parse_dof(name[2:])


def _band_sources(dof: int, names, settings: DiagnoseSettings) -> dict:
    """Where each calibrated coefficient's band came from: the method-table row (its text)
    with a vehicle file's :class:`PriorWidths`, else the bands given or the fixed
    :data:`BANDS`."""
    widths = settings.widths
    out = {}
    for n in names:
        owner = _column_owner(dof, n)
        kind = "translational" if owner < 3 else "rotational"
        term = n if n in TERM_MATRIX else "D_Q" if coupling_dof(n) is not None else "M"
        if widths is not None:
            out[n] = widths.rows[kind][term]
        elif settings.bands is not None:
            out[n] = f"the bands given to diagnose ({kind} {term})"
        else:
            out[n] = f"BANDS {kind} {term}: Wang & Clark 2006 Table I"
    return out


def _identifiability(data: WindowData, dof: int, cols, sd, names, excited,
                     settings: DiagnoseSettings = DEFAULTS) -> dict:
    r"""Which calibration coefficients the log can determine, and why not the others.

    A coefficient is kept at the prior when (1) the DOF it belongs to is not excited
    (:func:`excited_dofs`), or (2) its conditional Fisher information is too small: with
    the window residual's noise :math:`\sigma` (MAP fit of all columns) the Cramer-Rao
    standard deviation of coefficient j given the others is
    :math:`s_j = \sigma\sqrt{[(H^T H)^{-1}]_{jj}}`; it is calibrated only if
    :math:`b_j / s_j \ge` :data:`MIN_INFORMATION_RATIO`, b_j its band (Ljung 1999,
    sec. 9.2, eq. 9.29; a near-collinear pair has a large conditional variance, which is
    the condition check).

    With ``settings.noise_with_bias`` the noise level :math:`\sigma` is that of the window
    residual with a free constant beside the calibration's columns
    (:func:`sigma_beside_bias`): a constant force the prior
    misses is not noise (on by default since adopt33h, settings.ADOPTED_TOGETHER;
    benchmarks/data/spur33f_trace.md).

    Returns ``{"kept_at_prior": {name: reason}, "information_ratio": {name: b_j/s_j}}``.
    """
    reasons, ratios = {}, {}
    for n in names:
        owner = _column_owner(dof, n)
        if owner not in excited:
            reasons[n] = f"{DOF[owner]} is not excited in this log"
    keep = [j for j, n in enumerate(names) if n not in reasons]
    if keep:
        H = cols[:, keep]
        noise = sigma_beside_bias if settings.noise_with_bias else _sigma
        sigma = noise(data.e0[:, dof], H, np.asarray(sd, float)[keep])
        cov = np.linalg.pinv(H.T @ H) * sigma ** 2
        for k, j in enumerate(keep):
            s_data = math.sqrt(max(float(cov[k, k]), 0.0))
            ratio = sd[j] / s_data if s_data > 0 else math.inf
            ratios[names[j]] = float(ratio)
            if ratio < MIN_INFORMATION_RATIO:
                reasons[names[j]] = (f"the log determines it only to +-{s_data:.3g}, less than "
                                     f"{MIN_INFORMATION_RATIO:g}x better than its band "
                                     f"+-{sd[j]:.3g} (Fisher information)")
    return {"kept_at_prior": reasons, "information_ratio": ratios}



class _Generic:
    """The generic basis as a term (free columns)."""

    hyper = ()
    name = "generic"

    def __init__(self, basis):
        self.basis = basis

    def design(self, data, dof, hyper=None):
        return None, self.basis



@dataclass(frozen=True)
class EffectFit:
    """The result of :func:`fit_effects`: a fixed list of effects fitted with the calibration.

    Attributes
    ----------
    parameters : dict
        Effect name -> its fitted parameters (:meth:`Effect.to_parameters`)
    std : dict
        Effect name -> the standard deviations of those parameters
    calibration : dict
        Calibrated coefficient name -> value (the columns of :func:`_calibration`)
    error : float
        RMS window force residual of the fit [N or N m]
    held_out_error : float
        RMS residual of the blocked cross-validation: each block of windows predicted by a fit
        on the others [N or N m]
    """

    parameters: dict
    std: dict
    calibration: dict
    error: float
    held_out_error: float


def fit_effects(log, model, dof, effects, *, window: float = DEFAULT_WINDOW,
                bands=None) -> EffectFit:
    """Fit the calibration and a given list of effects (no selection): the "what if" of a
    fixed model structure, e.g. Indiveri 1998's standard model (calibration + buoyancy) or its
    eta model (+ thrust_asymmetry).

    Returns
    -------
    EffectFit
    """
    data = window_data(log, model, window=window)
    i = parse_dof(dof)
    cal = _calibration(data, i, DiagnoseSettings(bands=bands))
    cal_names = cal.names
    cfg = _Config(data, i, cal, [])
    ev = _evaluate(cfg)
    for name in effects:
        cfg = cfg.with_terms(list(cfg.terms) + [(get_effect(name), None)])
        ev = _evaluate(cfg)
    full = ev["full"]
    theta, cov = full["theta"], full["cov"]
    k = len(cal_names)
    params, std = {}, {}
    for eff, hyper in cfg.terms:
        ncol = eff.design(data, i, hyper)[1].shape[1]
        nuis = eff.nuisance(data, i)
        kn = 0 if nuis is None else nuis.shape[1]
        own = slice(k + kn, k + ncol)
        hsd = np.zeros(0)
        if hyper is not None:
            probe = cfg.with_terms([t for t in cfg.terms if t[0] is not eff] + [(eff, hyper)])
            hsd = _hyper_std(probe, hyper, full["sigma"])
        params[eff.name] = eff.to_parameters(theta[own], hyper, theta[k:k + kn])
        std[eff.name] = eff.std_of(theta[own], cov[own, own], hsd, cov[k:k + ncol, k:k + ncol])
        k += ncol
    return EffectFit(parameters=params, std=std,
                     calibration={n: float(v) for n, v in zip(cal_names, theta[:len(cal_names)])},
                     error=float(ev["error"]), held_out_error=float(ev["held_out_error"]))
