r"""Consider covariance: the uncertainty a fit inherits from the prior coefficients it holds.

A DOF's fit (:func:`stripcoef.diagnose.fit._fit`) keeps at the prior the coefficients the log
does not determine (:func:`~stripcoef.diagnose.fit._identifiability`; or, in a written fit,
the whole calibration when the validation removed it). Their prior values are not the truth:
each is known only to its band, the 1-sigma width of its Gaussian prior. Whatever the true
coefficient differs by, :math:`\delta c_k`, is in the window residual the fit explains,
:math:`y = H\theta + H_c\,\delta c + e`, and the fitted parameters take part of it: a thrust
scale, whose regressor the inertia and drag reproduce, picks up their errors (issue 33: a
scale of 0.79 +- 0.011 on the dead-band log of seed 604217, whose truth is 0.93).

The *consider covariance* of orbit determination (Tapley, Schutz & Born 2004, Statistical
Orbit Determination, sec. 6.3; Schmidt 1966's "consider parameters") carries them into the
fitted parameters' covariance without estimating them. With the estimator's sensitivity
:math:`S = \partial\hat\theta/\partial y` and the held coefficients' prior covariance
:math:`\bar P_{cc} = \mathrm{diag}(b_k^2)` (independent bands, :math:`b_k` [units of
coefficient k]):

.. math:: P_c = P + S H_c \bar P_{cc} H_c^T S^T = P + \sum_k d_k d_k^T,\qquad
          d_k = \hat\theta(y + b_k h_k) - \hat\theta(y)

(Tapley et al. 2004, eqs. 6.3.7-6.3.10 with the a-priori consider covariance), with
:math:`h_k` the column of coefficient k [N or N m per unit]. The MAP estimator of
:func:`~stripcoef.diagnose.fit._solve` is linear in y (the profiled inertia change is the
vertex of a quadratic whose curvature does not depend on y), so :math:`d_k` is computed by
refitting with the residual moved by :math:`\pm b_k h_k` (central difference: exact without
an active bound, the one-sided response at a bound); the point estimate is unchanged.

The nonlinear parameters of a term (a lag, a delay, a current, a dead band) move with the
residual by the Gauss-Newton step of their profiled residual r(p) (variable projection,
Golub & Pereyra 1973): :math:`d_k = -(J^T J)^{-1} J^T \Delta r_k`, :math:`\Delta r_k` the
change of the profiled residual when y moves by :math:`b_k h_k`
(:func:`hyper_consider_variance`).

Tests of a change (the likelihood ratios of :mod:`stripcoef.diagnose.compare`) marginalise
the held coefficients over their priors: :math:`y \sim N(H\theta, \sigma^2 I + H_c\bar
P_{cc}H_c^T)`, whose :math:`-2\log` likelihood is, by the Woodbury identity, the MAP cost
with the held columns appended with their Gaussian priors and minimised over
(:func:`marginal_design`; Tarantola 2005, eq. 3.37; Gelman et al. 2013, sec. 3.2 on
nuisance parameters integrated out).

What a reported standard deviation means, then: the spread of the estimate over the noise
of the log *and* over the truths its held coefficients may have within their bands; a
parameter's band [estimate - 1.96 sd, estimate + 1.96 sd] is meant to cover the truth 95 %
of the time when the truth's held coefficients lie within their bands (the bands are the
prior's 1-sigma widths). It does not cover errors outside the model's terms (an effect the
library lacks) nor the thrust maps' own uncertainty, which no calibration column holds.

Depends on: effects.windows (the held columns); the fit's solver is passed in
(:mod:`.fit` imports this module).
"""

from __future__ import annotations

import numpy as np

from stripcoef.effects.windows import coefficient_column


def held_design(cfg, hyper_override=None) -> tuple:
    """``(columns (n_windows, k), bands (k,), names)`` of the coefficients ``cfg``'s
    calibration holds at the prior (:attr:`Calibration.held_names`), at the velocity relative
    to the water when a term (the current) defines it, as the calibration's own columns
    (:meth:`_Config.calibration_columns`) [N or N m per unit, units of each coefficient]."""
    cal = cfg.cal
    names = tuple(cal.held_names)
    if not names:
        return np.zeros((cfg.data.n_windows, 0)), np.zeros(0), names
    cols = cal.held_cols
    for eff, h in cfg.hyper_terms(hyper_override):
        if h is not None and hasattr(eff, "relative_velocity"):
            nur = eff.relative_velocity(cfg.data, h)
            cols = np.column_stack([coefficient_column(cfg.data, cfg.dof, n, nur)
                                    for n in names])
            break
    sd = np.asarray(cal.held_sd, float)
    keep = np.isfinite(sd) & (sd > 0)
    return cols[:, keep], sd[keep], tuple(n for n, k in zip(names, keep) if k)


def sensitivities(solve, y, cols, sd) -> np.ndarray:
    r"""(p, k): the response :math:`d_k` of the estimate ``solve(y)`` (a function of the
    window residual y returning :math:`\hat\theta`) to each held coefficient moved by its
    band, :math:`(\hat\theta(y + b_k h_k) - \hat\theta(y - b_k h_k))/2` (module docstring)."""
    out = []
    for k in range(cols.shape[1]):
        step = sd[k] * cols[:, k]
        out.append(0.5 * (np.asarray(solve(y + step), float)
                          - np.asarray(solve(y - step), float)))
    return np.column_stack(out) if out else np.zeros((0, 0))


def consider_term(cfg, estimate, y, hyper=None) -> tuple:
    r"""``(d, names)``: the responses :math:`d_k` (p, k) of a fit's estimate, ``estimate(y)``
    (:math:`\hat\theta` of the window residual y: the MAP fit of
    :func:`~stripcoef.diagnose.fit._solve` at fixed noise level, bounds and inertia columns),
    to each coefficient ``cfg`` holds at the prior (:func:`held_design`), and those
    coefficients' names; the consider term of the covariance is :math:`d d^T`."""
    cols, bands, names = held_design(cfg, hyper)
    p = np.asarray(estimate(y)).size
    if not names or p == 0:
        return np.zeros((p, 0)), ()
    return sensitivities(estimate, y, cols, bands), names


def covariance(full, exclude=()) -> np.ndarray:
    """The covariance of a fit (:func:`~stripcoef.diagnose.fit._fit`'s record) with the
    consider term of every held coefficient but those named in ``exclude``."""
    if "consider" not in full:
        return np.asarray(full["cov"], float)
    d, names = full["consider"]
    use = [j for j, n in enumerate(names) if n not in exclude]
    return np.asarray(full["cov_data"], float) + d[:, use] @ d[:, use].T


def scale_ratio_variance(full, i_mu, i_s, m_ii: float) -> float:
    r"""Variance of the inertia a thrust scale and the calibration's inertia change imply in
    the prior's thrust units, :math:`r = (M_{ii} + \mu)/s` [kg^2, or (kg m^2)^2], from the
    fit's covariance (the delta method: :math:`g^T P g`, :math:`g = (1/s,
    -(M_{ii} + \mu)/s^2)` in :math:`(\mu, 	heta_s)`, :math:`s = 1 + 	heta_s`) with the
    consider term of every held coefficient except the DOF's own added mass ``M``, whose
    band the test adds itself (:func:`stripcoef.diagnose.select._scale_inertia_change`).
    ``i_mu``: the index of the inertia change (None when the calibration holds it),
    ``i_s``: the scale's column. 0 for a record without a covariance (the band alone)."""
    if "cov" not in full:
        return 0.0
    cov = covariance(full, exclude=("M",))
    theta = np.asarray(full["theta"], float)
    s = 1.0 + float(theta[i_s])
    mu = float(theta[i_mu]) if i_mu is not None else 0.0
    g = np.zeros(theta.size)
    g[i_s] = -(m_ii + mu) / s ** 2
    if i_mu is not None:
        g[i_mu] = 1.0 / s
    return float(max(g @ cov @ g, 0.0))


def consider_sd(cov, term) -> np.ndarray:
    """Standard deviations of ``cov + term`` (the data's covariance and the consider term)."""
    return np.sqrt(np.clip(np.diag(np.asarray(cov) + np.asarray(term)), 0, None))


def hyper_consider_variance(cfg, hyper, residual, jac) -> np.ndarray:
    r"""(q,): the variance the last term's nonlinear parameters ``hyper`` inherit from the
    held coefficients (module docstring: :math:`d_k = -(J^T J)^{-1} J^T \Delta r_k`), with
    ``residual(h, shift)`` the profiled residual at parameters h of the window residual
    moved by ``shift`` (that of :func:`~stripcoef.diagnose.fit._hyper_std`) and ``jac`` its
    Jacobian in h (q columns) [residual units per unit of each parameter]."""
    hyper = np.atleast_1d(np.asarray(hyper, float))
    cols, bands, _ = held_design(cfg, hyper)
    if cols.shape[1] == 0 or hyper.size == 0:
        return np.zeros(hyper.size)
    pinv = np.linalg.pinv(np.asarray(jac, float))
    var = np.zeros(hyper.size)
    for k in range(cols.shape[1]):
        shift = bands[k] * cols[:, k]
        dr = 0.5 * (residual(hyper, shift) - residual(hyper, -shift))
        var += (pinv @ dr) ** 2
    return var


def marginal_design(cfg, y, H, sd, lower, upper, hyper=None) -> tuple:
    """``(H, sd, lower, upper)`` with the held coefficients' columns appended, each with its
    Gaussian prior (its band) and no bound: minimising the MAP cost over them marginalises
    them (module docstring). The inertia columns of ``cfg.m_info`` keep their indices."""
    cols, bands, _ = held_design(cfg, hyper)
    if cols.shape[1] == 0:
        return H, sd, lower, upper
    k = cols.shape[1]
    lo = None if lower is None else np.concatenate([lower, np.full(k, -np.inf)])
    up = None if upper is None else np.concatenate([upper, np.full(k, np.inf)])
    return np.hstack([H, cols]), np.concatenate([sd, bands]), lo, up
