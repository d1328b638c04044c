r"""From measured method errors to band widths, and how often bands cover held-out references.

**The error of one term.** For a diagonal added-mass term with strip-theory value :math:`a`
and reference :math:`a_{ref}` (same sign), the error is the log ratio

.. math:: e = \ln(a / a_{ref}) \quad [-],

the quantity the sampling perturbs (a lognormal factor :math:`f = e^{\sigma z}`,
:mod:`stripcoef.study.sources`); :math:`a = 0 \ne a_{ref}` gives :math:`|e| = \infty` (no
factor can reach the reference).

**The band width.** From the errors :math:`e_1 \dots e_n` of one shape class and term family,

.. math:: q = |e|_{(k)}, \quad k = \min(n, \lceil 0.95\,(n + 1) \rceil), \qquad \sigma = q / 1.96,

the k-th smallest absolute error and the sd of ln whose 95 % band :math:`a\,e^{\pm 1.96 \sigma}`
is :math:`a\,e^{\pm q}`. This is the split-conformal quantile (Vovk, Gammerman & Shafer 2005,
*Algorithmic Learning in a Random World*; Lei et al. 2018, JASA 113, 1094-1111): if a new
term's error is exchangeable with the n measured ones, it falls within :math:`q` with
probability exactly :math:`k / (n + 1)`, whatever the errors' distribution -- at least 0.95 for
:math:`n \ge 19`; for fewer errors the band is the largest error and claims only
:math:`n / (n + 1)` (e.g. 0.90 from 9 errors). A quantile, not the sample sd: the errors are not
normal (30 of the 42 bluff rotations are within a factor 2, ten off by 4x to 130x, one
predicted as nearly zero). (The plain empirical quantile, :math:`k = \lceil 0.95 n \rceil`,
under-covers new terms: :math:`k/(n+1) = 0.905` at n = 20.)

**Coverage.** :func:`binomial_interval` is the exact (Clopper-Pearson) interval of a rate
from k of n items inside (Clopper & Pearson 1934, Biometrika 26, 404-413): a claimed 95 %
inside that interval is not contradicted by the n items.
"""

from __future__ import annotations

import math

import numpy as np

#: the two-sided 95 % quantile of N(0, 1): Phi^-1(0.975) [-]
Z95 = 1.959963984540054
LEVEL = 0.95


def log_error(strip, reference) -> np.ndarray:
    r""":math:`e = \ln(a / a_{ref})` [-] (module docstring); ``inf`` where ``a`` is 0 or of the
    other sign."""
    a = np.asarray(strip, float)
    r = np.asarray(reference, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = a / r
    return np.where(ratio > 0, np.log(np.where(ratio > 0, ratio, 1.0)), np.inf)


def conformal_rank(n: int) -> int:
    r""":math:`k = \min(n, \lceil 0.95 (n + 1) \rceil)` (module docstring)."""
    return min(int(n), math.ceil(LEVEL * (n + 1) - 1e-9))


def claimed_coverage(n: int) -> float:
    r"""The probability :math:`k / (n + 1)` that a new exchangeable error falls in the band
    made from ``n`` errors [-] (0.95 for n >= 19)."""
    return conformal_rank(n) / (n + 1) if n > 0 else 0.0


def quantile95(abs_errors) -> float:
    r""":math:`|e|_{(k)}`, :math:`k = \min(n, \lceil 0.95 (n + 1) \rceil)` [-] (module
    docstring: the split-conformal quantile)."""
    e = np.sort(np.abs(np.asarray(abs_errors, float)))
    if e.size == 0:
        return math.nan
    return float(e[conformal_rank(e.size) - 1])


def sd_from_errors(errors) -> float:
    r""":math:`\sigma = |e|_{(k)} / 1.96` [-], the lognormal sd of ln whose 95 % band covers
    95 % of ``errors`` (module docstring)."""
    return quantile95(errors) / Z95


def inside(errors, sd) -> np.ndarray:
    r"""Whether a reference with log error ``e`` lies in the band :math:`a e^{\pm 1.96\sigma}`,
    i.e. :math:`|e| \le 1.96 \sigma` (booleans)."""
    return np.abs(np.asarray(errors, float)) <= Z95 * float(sd) * (1 + 1e-12)


def leave_one_group_out(errors, groups) -> np.ndarray:
    """For each item: is it inside the band set by the errors of every OTHER group (shape)?
    ``errors``: (n,) log errors of one class and family; ``groups``: (n,) shape labels. Items of
    a class with one shape only have no band from the others: False. A NaN error (a model term
    of the wrong sign, which no factor reaches) is outside and sets no band."""
    e = np.asarray(errors, float)
    g = np.asarray(groups)
    out = np.zeros(e.size, bool)
    for label in np.unique(g):
        own = g == label
        others = e[~own & np.isfinite(e)]
        if others.size == 0:
            continue
        out[own] = inside(e[own], sd_from_errors(others))
    return out


def binomial_interval(k: int, n: int, level: float = 0.95) -> tuple[float, float]:
    r"""Clopper-Pearson interval of a rate from ``k`` successes in ``n`` trials [-]:
    :math:`[B^{-1}(\alpha/2; k, n-k+1),\ B^{-1}(1-\alpha/2; k+1, n-k)]`, :math:`\alpha = 1 -`
    ``level`` (Clopper & Pearson 1934)."""
    from scipy.stats import beta

    if n <= 0:
        return (0.0, 1.0)
    a = 1.0 - level
    lo = 0.0 if k == 0 else float(beta.ppf(a / 2, k, n - k + 1))
    hi = 1.0 if k == n else float(beta.ppf(1 - a / 2, k + 1, n - k))
    return lo, hi
