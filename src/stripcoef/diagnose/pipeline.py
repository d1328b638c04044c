r"""Closing the loop: find the residual, trace it to the effect the model lacks, add it.

Steps, for each degree of freedom (issue 7):

1. **Baseline**: the prior (strip-theory) model predicts the log; the error is the RMS of the
   window force residual :math:`e_i` of :mod:`stripcoef.effects.laws` [N or N m] (the
   one-step form of Wang & Clark 2006, eqs. 14-17, over windows of ``window`` seconds), and, when
   ``resimulate`` is on, the RMS of the re-simulated velocity [m/s or rad/s].
2. **Calibration** of the prior's own coefficients of that DOF (inertia M_ii, linear and
   quadratic damping D_L,ii and D_Q,ii) *within their bands*: a Gaussian prior on each
   correction with standard deviation ``band * prior value`` (maximum a posteriori least
   squares, Tarantola 2005 eq. 3.37; ridge regression). Bands, from the analytical vs
   experimental columns of Wang & Clark 2006 Table I: translational added mass 30 %, linear drag
   60 %, quadratic drag 30 %; rotational added mass 100 %, linear and quadratic drag 300 %
   (N_r is off by 4.8x and N_r|r| by 50x there: strip theory barely constrains rotation).
   With a vehicle file (its shape class known) the bands are instead the method table's
   sd of ln c per matrix and DOF group (:class:`PriorWidths`, issue 19: the added mass
   measured, the translational quadratic drag measured for the classes with published 3D
   body drag and assumed otherwise, the rotational drag assumed, the linear drag not
   predicted: a very wide prior).
   A coefficient the prior has as zero is not calibrated (strip theory says it is absent).
3. **Structure** of the residual: bias, lag-1 autocorrelation, runs test, dependence on the
   sign of the velocity and of the thrust, correlation with each candidate's regressors.
4. **Effects**: every applicable effect of the library is fitted together with the
   calibration (nonlinear parameters profiled); it is *significant* when all of
   - the held-out error (blocked cross-validation: the log's windows in ``N_BLOCKS``
     contiguous blocks, each predicted by a fit on the others) drops by at least
     ``MIN_HELD_OUT_GAIN``,
   - the Bayesian information criterion on all windows drops by at least
     ``MIN_DELTA_BIC`` (Schwarz 1978; windows do not overlap, so residuals are close to
     independent and N is the number of windows),
   - a parameter of the effect is at least ``MIN_Z`` standard deviations from zero,
   - its parameters are physically plausible (a drag is positive, an efficiency in (0.1, 3)),
   - an effect without a signature in this log (it only mimics a prior coefficient, e.g. a
     tether drag without a ``tether_length`` column looks like a larger D_Q) must also push
     that coefficient more than ``MIMIC_BANDS`` bands away from the prior.
   The significant effect with the lowest held-out error is added; effects within ``TIE``
   of it are reported as alternatives, and an effect with a signature is preferred over one
   without. Repeat until nothing is significant.
5. **What remains**: a generic basis (velocities of every DOF, their squares and cubes,
   signs, applied force, heading, other logged channels) is fitted to the final residual; if
   it cuts the held-out error by ``UNEXPLAINED_GAIN`` the residual is still structured and,
   no library effect explaining it, ``unexplained`` is true.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares, lsq_linear

from stripcoef.conventions import DOF, FORCES, VELOCITIES, parse_dof
from stripcoef.errors import InputError, ModelWarning, UnreachableError
from stripcoef.model import frozen_mapping, plain
from stripcoef.effects.laws import (EFFECTS, WindowData, coefficient_column,
                                    effect_window_forces, get_effect)
from stripcoef.effects.windows import window_data
from stripcoef.identify.estimators import residual_autocorrelation, runs_test_z
from stripcoef.progress import track

#: 1-sigma relative bands on the prior's coefficients (see module docstring).
BANDS = {"translational": {"M": 0.3, "D_L": 0.6, "D_Q": 0.3},
         "rotational": {"M": 1.0, "D_L": 3.0, "D_Q": 3.0}}
MIN_HELD_OUT_GAIN = 0.10
MIN_DELTA_BIC = 10.0
MIN_Z = 3.0
TIE = 0.02
MIMIC_BANDS = 2.5
UNEXPLAINED_GAIN = 0.10
#: The residual is unexplained also when, after the best candidates, its held-out error
#: stays above this multiple of the noise floor F = M_ii sqrt(var(rate noise)) (the part of
#: the window residual the velocity noise alone makes; effects/windows.py): a model that
#: explained the log would leave about F (chi-square with one degree of freedom per window
#: exceeds 5^2 with probability < 1e-6, so noise alone never crosses it) -- provided the
#: generic basis predicts some of it (held-out gain > 0): the window residual also carries
#: the quadrature error of the window integrals on a jittered log, which no basis predicts
#: (measured: 7.4 floors on a 10 Hz log with 20 % jitter and 1-s windows diagnosed with its
#: own true model, tests/test_ingest_cli.py; a missing effect such as Coulomb friction is
#: partly predicted by the basis's sign column).
NOISE_FLOOR_FACTOR = 5.0
N_BLOCKS = 5
MAX_STEPS = 4
#: Wall-clock budget of one diagnosis [s]: the fits cost grows with the log's length (a
#: 200,000-row log would take most of an hour); past the budget the diagnosis stops with an
#: error saying so, instead of grinding.
TIME_LIMIT = 300.0
_deadline = {"at": None, "limit": None, "rows": 0, "source": ""}


def _check_budget() -> None:
    """Raise once the running diagnosis is past its wall-clock budget (checked per design)."""
    at = _deadline["at"]
    if at is not None and time.monotonic() > at:
        raise UnreachableError(
            f"{_deadline['source']}: diagnosis stopped, over its time budget of {_deadline['limit']:g} s; got "
            f"{_deadline['rows']} log rows; expected a log this machine can fit in time "
            "(resample it, e.g. to 10 Hz, or cut it into parts)")
#: Plausible added mass as a factor of the prior's [-] (lower, upper): Wang & Clark 2006
#: Table I has analytical/experimental ratios up to 2.7 (N_rdot); strip theory's translational
#: added mass is closer (a factor 4 either way is an assumption that covers the synthetic
#: benchmark's 2-3x truths), rotation is barely constrained (a factor 5).
ADDED_MASS_FACTOR = {"translational": (0.25, 4.0), "rotational": (0.2, 5.0)}
#: Identifiability: a coefficient is calibrated only when sd_band / sd_data >=
#: MIN_INFORMATION_RATIO, with sd_data^2 = sigma^2 [(H^T H)^-1]_jj the conditional (Fisher)
#: variance given the other columns (Cramer-Rao bound of the linear model; Ljung 1999,
#: sec. 9.2, eq. 9.29). Below 0.3 the log adds less than 9 % (0.3^2) to the information of
#: the band: the MAP estimate would move by less than about a tenth of a band, noise rather
#: than a measurement, so the coefficient is kept exactly at the prior. (2.0 was tried
#: first: it froze every heave coefficient of the short ROMEO trials, Indiveri 1998, whose
#: data carry 0.4-0.9 of the band's information, and the thrust efficiency then absorbed
#: the inertia and drag errors.)
MIN_INFORMATION_RATIO = 0.3
#: A DOF is excited when its velocity's standard deviation is this many times its noise
#: (the noise from second differences, :meth:`WindowData.rate_noise_variance`'s estimator)
#: and its applied force moves.
EXCITATION_SNR = 3.0
#: Fraction of the fitting log (its last part) kept to validate each change by free
#: simulation: a calibration or an effect stays only if it lowers the validation error.
VALIDATION_FRACTION = 0.25
#: Default window of the one-step residual [s]. Velocity noise of standard deviation
#: sigma_v enters the window residual as M_ii sqrt(2) sigma_v / T: 4 s windows halve the
#: noise floor of 2 s ones, while 60 windows in a 4-minute log still resolve 6-20 s steps
#: (measured: benchmarks/diagnose_detection.py --window 2 vs 4, docs/performance.md).
DEFAULT_WINDOW = 4.0
#: Velocity standard deviation above which ``dof="all"`` counts a DOF as excited [m/s, rad/s].
EXCITATION_STD = 1e-3
METRIC = "rms_window_force_residual"
METRIC_TEXT = ("RMS of the one-step force residual: the generalized force the model misses, "
               "averaged over non-overlapping windows [N or N m]")


#: Half-width of the method uncertainty band of the added mass, in standard deviations [-]:
#: :math:`\pm 3\sigma` holds 99.73 % of a normal distribution (two-sided), the band a
#: calibrated added mass is clipped to when the prior's method uncertainty is known
#: (:func:`method_added_mass_sd`; issue 19: the study's bands as the diagnosis's priors).
ADDED_MASS_BAND_Z = 3.0


def added_mass_bounds(dof: int, prior: float, sd: float | None = None) -> tuple[float, float]:
    r"""(lower, upper) plausible added mass of DOF ``dof`` [kg or kg m^2].

    :data:`ADDED_MASS_FACTOR` times the prior's value, intersected, when the 1-sigma method
    uncertainty ``sd`` of the prior's added mass is known (sd of :math:`\ln M_{ii}` [-], the
    lognormal rows of :mod:`stripcoef.study.sources`), with its 99.7 % band

    .. math:: |M_{ii}|\, e^{-z\sigma} \le M'_{ii} \le |M_{ii}|\, e^{z\sigma},
              \quad z = 3

    (``ADDED_MASS_BAND_Z``)."""
    lo, hi = ADDED_MASS_FACTOR["translational" if dof < 3 else "rotational"]
    lo, hi = lo * abs(prior), hi * abs(prior)
    if sd is not None and np.isfinite(sd) and sd > 0:
        lo = max(lo, float(np.exp(-ADDED_MASS_BAND_Z * float(sd))) * abs(prior))
        hi = min(hi, float(np.exp(ADDED_MASS_BAND_Z * float(sd))) * abs(prior))
    return lo, hi


#: The method-table matrix of each calibrated term (:mod:`stripcoef.study.sources`).
TERM_MATRIX = {"M": "added_mass", "D_L": "linear_damping", "D_Q": "quadratic_damping"}
#: The method-table DOF group of each band kind.
KIND_GROUP = {"translational": "translation", "rotational": "rotation"}


@dataclass(frozen=True)
class PriorWidths:
    r"""Widths of the calibration's Gaussian priors from the method table (issue 19).

    The method table (``data/method_uncertainty.csv``, docs/uncertainty.md) gives, per shape
    class, matrix and DOF group, the sd :math:`\sigma` of :math:`\ln c` of a coefficient c:
    measured for the added mass (the ``panels`` rows when the model's added mass is the panel
    method's), measured for the translational quadratic damping of the classes with published
    3D body drag (revolution, bluff) and assumed for the others and for every rotation, and a
    placeholder for the linear damping
    (``not_predicted``: the method does not predict it, so its prior is very wide, 250 % at
    1 sigma). The calibration is additive (a correction :math:`\delta = c - c_0` to the
    prior value :math:`c_0`), so :math:`\sigma` is converted to an absolute sd at the prior
    value by the first-order (delta-method) relation
    :math:`d\ln c = dc / c`,

    .. math:: \delta \sim N\!\left(0, (\sigma\,|c_0|)^2\right)
              \quad [\text{units of } c],

    i.e. a relative band :math:`b = \sigma` [-] in the place of :data:`BANDS` (Tarantola 2005,
    eq. 3.37 for the Gaussian prior; the lognormal's sd of ln, :mod:`stripcoef.study.sources`).
    For :math:`\sigma \gtrsim 1` the lognormal is skewed and the Gaussian only approximates
    it (a wide prior, which is what such a row says); the bounds still apply (no negative
    drag; the added mass within :func:`added_mass_bounds`, its 99.7 % band).

    ``sd_ln``: ``{kind: {term: sigma}}`` (kind ``translational``/``rotational``, term
    ``M``/``D_L``/``D_Q``) [-]; ``rows``: ``{kind: {term: "CLASS MATRIX.GROUP: source
    text"}}``, the row each width came from (CLASS ``panels`` for a panel-method added mass);
    ``shape_class``: the vehicle's geometric class.
    """

    shape_class: str
    sd_ln: Mapping
    rows: Mapping

    @property
    def bands(self) -> dict:
        """The widths in the form of :data:`BANDS` (relative 1-sigma) [-]."""
        return {k: dict(v) for k, v in self.sd_ln.items()}

    @property
    def added_mass_sd(self) -> np.ndarray:
        """(6,) sd of ln M_ii [-] (:func:`method_added_mass_sd`'s form)."""
        return np.array([self.sd_ln["translational" if i < 3 else "rotational"]["M"]
                         for i in range(6)], float)

    def to_dict(self) -> dict:
        return {"shape_class": self.shape_class,
                "sd_ln": {k: dict(v) for k, v in self.sd_ln.items()},
                "rows": {k: dict(v) for k, v in self.rows.items()},
                "description": "1-sigma widths of the calibration's Gaussian priors from the "
                               "method table (sd of ln c, applied as sd |c0| sigma at the "
                               "prior value c0); linear damping: not predicted by the method, "
                               "a very wide prior"}


def method_prior_widths(vehicle, *, panels: bool | None = None) -> PriorWidths:
    """:class:`PriorWidths` of a parsed vehicle: the rows of
    :func:`stripcoef.study.sources.method_sources` (its shape class; the ``panels`` rows for
    the added mass of a panel-method model: ``panels``, default what
    :func:`stripcoef.study.sources.uses_panels` says for the default options)."""
    from stripcoef.study.sources import method_sources, shape_class

    found = {}
    for src in method_sources(vehicle, panels=panels):
        matrix, group = src.name.split(".")
        found[(matrix, group)] = src
    sd_ln, rows = {}, {}
    for kind, group in KIND_GROUP.items():
        sd_ln[kind], rows[kind] = {}, {}
        for term, matrix in TERM_MATRIX.items():
            src = found.get((matrix, group))
            if src is None or src.distribution != "lognormal":
                raise InputError("no lognormal method row", key=f"{matrix}.{group}",
                                 value=None if src is None else src.distribution,
                                 expected="a lognormal row of data/method_uncertainty.csv")
            cls, _, text = src.reason.partition(": ")
            sd_ln[kind][term] = float(src.spread)
            rows[kind][term] = f"{cls} {src.name}: {text}"
    return PriorWidths(shape_class(vehicle), sd_ln, rows)


def _band_sd(data, dof: int):
    """The relative 1-sigma method uncertainty of DOF ``dof``'s added mass the diagnosis of
    ``data`` runs with (:func:`diagnose`'s ``added_mass_sd``), or None."""
    sd = data.__dict__.get("_added_mass_sd")
    return None if sd is None else float(sd[dof])


def method_added_mass_sd(vehicle) -> np.ndarray:
    """1-sigma method uncertainty of each DOF's added mass (6,), as the sd of its logarithm
    [-], for a parsed vehicle: the ``added_mass`` rows of its class (translations share one
    value, rotations another), read as :func:`method_prior_widths` reads them."""
    return method_prior_widths(vehicle).added_mass_sd


def prior_widths(path) -> PriorWidths | None:
    """:func:`method_prior_widths` when ``path`` is a vehicle file, None for a model file
    (it does not say which method or shape it came from: the fixed :data:`BANDS` apply)."""
    vehicle = _vehicle_of(path)
    return None if vehicle is None else method_prior_widths(vehicle)


def _vehicle_of(path):
    """The parsed vehicle of a vehicle file ``path``, None for a model file."""
    from stripcoef.files import load_yaml, read_text
    from stripcoef.geometry.vehicle import load_vehicle

    path = str(path)
    if not path.lower().endswith((".yaml", ".yml")):
        return None
    data = load_yaml(read_text(path, kind="vehicle or model file"), file=path)
    if isinstance(data, dict) and "added_mass" in data and "rigid_body_mass" in data:
        return None
    return load_vehicle(path)


def prior_added_mass_sd(path):
    """``(sd, shape class)`` of :func:`method_added_mass_sd` when ``path`` is a vehicle file,
    ``(None, None)`` for a model file (it does not say which method or shape it came from)."""
    widths = prior_widths(path)
    return (None, None) if widths is None else (widths.added_mass_sd, widths.shape_class)


# ---------------------------------------------------------------------------
# least squares with band priors
# ---------------------------------------------------------------------------

def _solve(y, H, prior_sd, sigma, lower=None, m=None, upper=None):
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

    Returns theta, covariance (the unconstrained one at the solution), weighted residual.
    """
    if m is not None and len(m[0]):
        return _solve_profiled(y, H, prior_sd, sigma, lower, m, upper)
    return _solve_linear(y, H, prior_sd, sigma, lower, upper=upper)


def _solve_linear(y, H, prior_sd, sigma, lower=None, weight=1.0, upper=None):
    p = H.shape[1]
    if p == 0:
        return np.zeros(0), np.zeros((0, 0)), y * weight / sigma
    rows = [H * weight / sigma]
    rhs = [y * weight / sigma]
    finite = np.isfinite(prior_sd)
    if finite.any():
        reg = np.zeros((int(finite.sum()), p))
        reg[np.arange(reg.shape[0]), np.nonzero(finite)[0]] = 1.0 / prior_sd[finite]
        rows.append(reg)
        rhs.append(np.zeros(reg.shape[0]))
    a = np.vstack(rows)
    b = np.concatenate(rhs)
    scale = np.sqrt((a ** 2).sum(axis=0))
    scale[scale == 0] = 1.0
    theta_s, *_ = np.linalg.lstsq(a / scale, b, rcond=None)
    low_bad = lower is not None and np.any(theta_s / scale < lower)
    up_bad = upper is not None and np.any(theta_s / scale > upper)
    if low_bad or up_bad:
        lb = (np.full(p, -np.inf) if lower is None
              else np.where(np.isfinite(lower), lower * scale, -np.inf))
        ub = (np.full(p, np.inf) if upper is None
              else np.where(np.isfinite(upper), upper * scale, np.inf))
        theta_s = lsq_linear(a / scale, b, bounds=(lb, ub), method="bvls").x
    theta = theta_s / scale
    cov = np.linalg.pinv((a / scale).T @ (a / scale)) / np.outer(scale, scale)
    return theta, cov, b - a @ theta


def _solve_profiled(y, H, prior_sd, sigma, lower, m, upper=None):
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

    def inner(mu):
        th, cov, res = _solve_linear(y - mu * rate, X, sdx, sigma, lowx, upper=upx)
        extra = np.array([mu / mu_sd]) if np.isfinite(mu_sd) else np.zeros(0)
        return th, cov, np.concatenate([res, extra])

    def cost(mu):
        return float(np.sum(inner(mu)[2] ** 2)) - y.size * (m_total + mu) ** 2 * noise_var \
            / sigma ** 2

    hi = 5.0 * m_total
    if upper is not None:
        hi = min(hi, float(np.min(upper[mcols])))
    # without active bounds the profiled cost is exactly quadratic in mu (a linear
    # least-squares residual of y - mu * rate, plus quadratic prior and noise terms):
    # three evaluations give its vertex; otherwise fall back to a bounded search
    h = 0.1 * m_total
    c0, cp, cm = cost(0.0), cost(h), cost(-h)
    curv = (cp - 2 * c0 + cm) / h ** 2
    mu = None
    if curv > 0:
        cand = float(np.clip(-(cp - cm) / (2 * h) / curv, lo, hi))
        if cost(cand) <= min(c0, cp, cm) + 1e-9 * max(abs(c0), 1.0):
            mu = cand
    if mu is None:
        sol = minimize_scalar(cost, bounds=(lo, hi), method="bounded",
                              options={"xatol": 1e-6 * m_total})
        mu = float(sol.x)
    th, covx, res = inner(mu)
    if not (curv > 0 and lo + h <= mu <= hi - h):
        c0, cp, cm = cost(mu), cost(min(mu + h, hi)), cost(max(mu - h, lo))
        curv = (cp - 2 * c0 + cm) / h ** 2
    var_mu = 2.0 / curv if curv > 0 else np.inf
    theta = np.zeros(H.shape[1])
    cov = np.zeros((H.shape[1], H.shape[1]))
    theta[keep] = th
    cov[np.ix_(keep, keep)] = covx
    # the inertia change goes to the last inertia column (the released one if any)
    j = mcols[-1] if not np.isfinite(mu_sd) and len(mcols) > 1 else mcols[0]
    if not np.isfinite(mu_sd):
        j = next((c for c in mcols if not np.isfinite(prior_sd[c])), mcols[-1])
    theta[j] = mu
    cov[j, j] = var_mu
    return theta, cov, res


class _Config:
    """Calibration columns + accepted effects (+ a candidate) for one DOF."""

    def __init__(self, data: WindowData, dof: int, cal_cols, cal_sd, terms, cal_lower=None):
        self.data, self.dof = data, dof
        self.cal_cols, self.cal_sd = cal_cols, cal_sd
        self.cal_names = None  # names of the calibration columns (for recomputing them)
        if cal_lower is None:
            cal_lower = np.full(len(cal_sd), -np.inf)
            if cal_sd is not None and len(cal_sd):
                cache = data.__dict__.setdefault("_cal_prior", {})
                names = data.__dict__.setdefault("_cal_names", {})
                if dof not in cache:
                    cal = _calibration(data, dof)
                    cache[dof] = np.asarray(cal[3], float)
                    names[dof] = list(cal[2])
                if self.cal_names is None and len(names[dof]) == len(cal_sd):
                    self.cal_names = names[dof]
                if cache[dof].size == len(cal_sd):
                    # the calibrated coefficient stays >= 0: no negative added mass or drag
                    cal_lower = -np.abs(cache[dof])
        self.cal_lower = np.asarray(cal_lower, float)
        self.cal_upper = np.full(self.cal_lower.size, np.inf)
        prior = data.__dict__.get("_cal_prior", {}).get(dof)
        if self.cal_names and prior is not None and prior.size == self.cal_lower.size:
            for j, key in enumerate(self.cal_names):
                if key == "M" or key.startswith("M_"):
                    owner = dof if key == "M" else parse_dof(key[2:])
                    lo, hi = added_mass_bounds(owner, prior[j], _band_sd(data, owner))
                    self.cal_lower[j] = max(self.cal_lower[j], lo - prior[j])
                    self.cal_upper[j] = hi - prior[j]
        self.cal_has_m = (cal_sd is not None and len(cal_sd) > 0
                          and float(data.model.added_mass[dof, dof]) != 0.0
                          and (self.cal_names is None or self.cal_names[:1] == ["M"]))
        self.terms = terms  # list of (effect, hyper)

    def hyper_terms(self, hyper_override=None):
        """(effect, hyper) of each term, the last one's hyper replaced by ``hyper_override``
        when given (the candidate whose nonlinear parameters are being profiled)."""
        last = len(self.terms) - 1
        return [(eff, hyper_override if (hyper_override is not None and k == last) else hyper)
                for k, (eff, hyper) in enumerate(self.terms)]

    def lower(self, hyper_override=None):
        """Lower bounds of all parameters (calibration: coefficient >= 0)."""
        out = [self.cal_lower]
        for eff, h in self.hyper_terms(hyper_override):
            lo = eff.lower_bounds(self.data, self.dof, h) if hasattr(eff, "lower_bounds") \
                else np.full(eff.design(self.data, self.dof, h)[1].shape[1], -np.inf)
            out.append(lo)
        return np.concatenate(out)

    def upper(self, hyper_override=None):
        """Upper bounds of all parameters (calibration: added mass within its factor)."""
        out = [self.cal_upper]
        for eff, h in self.hyper_terms(hyper_override):
            n = eff.design(self.data, self.dof, h)[1].shape[1]
            up = eff.upper_bounds(self.data, self.dof, h) if hasattr(eff, "upper_bounds") \
                else np.full(n, np.inf)
            out.append(up)
        return np.concatenate(out)

    def m_info(self, hyper_override=None):
        """(indices of the inertia columns, prior inertia of the DOF) for :func:`_solve`."""
        cols = []
        if self.cal_has_m:
            cols.append(0)
        k = self.cal_cols.shape[1]
        for eff, h in self.hyper_terms(hyper_override):
            n = eff.design(self.data, self.dof, h)[1].shape[1]
            if getattr(eff, "inertia", False):
                cols.append(k + n - 1)
            k += n
        return (cols, float(self.data.model.mass_matrix[self.dof, self.dof]),
                self.data.rate_noise_variance(self.dof))

    def calibration_columns(self, hyper_override=None):
        """The calibration columns, at the velocity relative to the water when a term (the
        current) defines it -- drag and added mass act on nu_r (Fossen 2011, eq. 10.1)."""
        for eff, h in self.hyper_terms(hyper_override):
            if h is not None and hasattr(eff, "relative_velocity") and self.cal_names:
                nur = eff.relative_velocity(self.data, h)
                return np.column_stack([coefficient_column(self.data, self.dof, key, nur)
                                        for key in self.cal_names])
        return self.cal_cols

    def design(self, hyper_override=None):
        _check_budget()
        y = self.data.e0[:, self.dof].copy()
        cols = [self.calibration_columns(hyper_override)]
        sd = [self.cal_sd]
        for eff, h in self.hyper_terms(hyper_override):
            off, c = eff.design(self.data, self.dof, h)
            if off is not None:
                y = y - off
            cols.append(c)
            if hasattr(eff, "prior_sd"):
                sd.append(eff.prior_sd(self.data, self.dof, h))
            else:
                sd.append(np.full(c.shape[1], np.inf))
        return y, np.hstack(cols), np.concatenate(sd)


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


def _sigma(y, H, sd=None, lower=None, m=None, upper=None):
    """Noise level of the window residual: iterate the MAP fit from sigma = RMS(y) (a free
    fit could follow the scale degeneracy of the force balance to sigma = 0)."""
    if H.shape[1] == 0:
        return max(float(np.sqrt(np.mean(y ** 2))), 1e-12)
    sd = np.full(H.shape[1], np.inf) if sd is None else sd
    sigma = max(float(np.sqrt(np.mean(y ** 2))), 1e-12)
    for _ in range(4):
        theta, _, _ = _solve(y, H, sd, sigma, lower, m, upper)
        r = y - H @ theta

        p_eff = min(H.shape[1], y.size - 1)
        sigma = max(float(np.sqrt(r @ r / max(y.size - p_eff, 1))), 1e-12)
    return sigma


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
        theta, _, wres = _solve(yy, HH, sd, sigma0, cfg.lower(h), cfg.m_info(h), cfg.upper(h))
        return wres

    if hasattr(eff, "grid"):
        # one nonlinear parameter on a bounded range (a time constant, a delay): a grid,
        # then a bounded scalar search between the neighbours of the best grid point
        from scipy.optimize import minimize_scalar
        grid = eff.grid(cfg.data, cfg.dof)

        def cost1(c):
            return float(np.sum(cost_vec(np.array([c])) ** 2))
        costs = np.array([cost1(c) for c in grid])
        k = int(np.argmin(costs))
        lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, grid.size - 1)]
        if hi > lo:
            sol = minimize_scalar(cost1, bounds=(lo, hi), method="bounded",
                                  options={"xatol": 1e-3 * (hi - lo)})
            if sol.fun <= costs[k]:
                return np.array([float(sol.x)])
        return np.array([float(grid[k])])

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
        return _solve(y, H, sd, sigma, cfg.lower(h), cfg.m_info(h), cfg.upper(h))[2] * sigma

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


# ---------------------------------------------------------------------------
# evaluation of one configuration
# ---------------------------------------------------------------------------

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
            "hyper": hyper}


def _calibration(data: WindowData, dof: int, bands=None, cross=None):
    r"""Calibration columns and band standard deviations for one DOF.

    The relative bands: ``bands`` if given, else the :class:`PriorWidths` the diagnosis runs
    with (a vehicle file's method-table rows), else :data:`BANDS`; the standard deviation of
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
    whose added mass this DOF may calibrate: excited, and not diagnosed themselves, so that
    one coefficient has one value; None = all).
    """
    widths = data.__dict__.get("_prior_widths")
    bands = bands or (widths.bands if widths is not None else BANDS)
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
    cols = np.column_stack(cols) if cols else np.zeros((data.n_windows, 0))
    return cols, np.asarray(sd, float), names, prior, b


def _band_sources(data: WindowData, dof: int, names) -> dict:
    """Where each calibrated coefficient's band came from: the method-table row (its text)
    with a vehicle file's :class:`PriorWidths`, else the fixed :data:`BANDS`."""
    widths = data.__dict__.get("_prior_widths")
    out = {}
    for n in names:
        owner = dof if n in TERM_MATRIX else parse_dof(n[2:])
        kind = "translational" if owner < 3 else "rotational"
        term = n if n in TERM_MATRIX else "M"
        if widths is not None:
            out[n] = widths.rows[kind][term]
        elif data.__dict__.get("_bands_given"):
            out[n] = f"the bands given to diagnose ({kind} {term})"
        else:
            out[n] = f"BANDS {kind} {term}: Wang & Clark 2006 Table I"
    return out


def _identifiability(data: WindowData, dof: int, cols, sd, names, excited) -> dict:
    r"""Which calibration coefficients the log can determine, and why not the others.

    A coefficient is kept at the prior when (1) the DOF it belongs to is not excited
    (:func:`excited_dofs`), or (2) its conditional Fisher information is too small: with
    the window residual's noise :math:`\sigma` (MAP fit of all columns) the Cramer-Rao
    standard deviation of coefficient j given the others is
    :math:`s_j = \sigma\sqrt{[(H^T H)^{-1}]_{jj}}`; it is calibrated only if
    :math:`b_j / s_j \ge` :data:`MIN_INFORMATION_RATIO`, b_j its band (Ljung 1999,
    sec. 9.2, eq. 9.29; a near-collinear pair has a large conditional variance, which is
    the condition check).

    Returns ``{"kept_at_prior": {name: reason}, "information_ratio": {name: b_j/s_j}}``.
    """
    reasons, ratios = {}, {}
    for n in names:
        owner = dof if n in ("M", "D_L", "D_Q") else parse_dof(n[2:])
        if owner not in excited:
            reasons[n] = f"{DOF[owner]} is not excited in this log"
    keep = [j for j, n in enumerate(names) if n not in reasons]
    if keep:
        H = cols[:, keep]
        sigma = _sigma(data.e0[:, dof], H, np.asarray(sd, float)[keep])
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


def _physical_problems(data: WindowData, dof: int, totals: dict) -> list:
    """Reasons a set of total coefficients of DOF ``dof`` is impossible: negative drag, an
    added mass outside :func:`added_mass_bounds`. ``totals``: name (M, D_L, D_Q, M_<dof>)
    -> the coefficient's total value (prior + calibration + released part)."""
    m = data.model
    out = []
    for key, total in totals.items():
        if key in ("D_L", "D_Q") and total < 0.0:
            out.append(f"negative {key} ({total:.3g})")
        if key == "M" or key.startswith("M_"):
            j = dof if key == "M" else parse_dof(key[2:])
            lo, hi = added_mass_bounds(j, float(m.added_mass[j, j]), _band_sd(data, j))
            if not lo * (1 - 1e-9) <= total <= hi * (1 + 1e-9):
                out.append(f"{key} {total:.3g} outside its plausible range [{lo:.3g}, {hi:.3g}]")
    return out


def _structure(data: WindowData, dof: int, resid, candidates):
    """Descriptive statistics of a residual (bias, autocorrelation, sign dependence...)."""
    r = np.asarray(resid, float)
    n = r.size
    v = data.mean(data.nu[:, dof])
    f = data.mean_held(data.tau[:, dof])
    out = {"bias": float(np.mean(r)),
           "bias_z": float(np.mean(r) / (np.std(r, ddof=1) / math.sqrt(n))) if n > 1 else 0.0,
           "lag1_autocorrelation": float(residual_autocorrelation(r, 1)[1]),
           "runs_z": float(runs_test_z(r))}
    for name, x in (("velocity", v), ("force", f)):
        pos, neg = r[x > 0], r[x < 0]
        out[f"mean_when_{name}_positive"] = float(np.mean(pos)) if pos.size else None
        out[f"mean_when_{name}_negative"] = float(np.mean(neg)) if neg.size else None
    corr = {}
    for eff in candidates:
        if not eff.applicable(data, dof)[0]:
            continue
        off, cols = eff.design(data, dof, eff.hyper_start(data, dof) if eff.hyper else None)
        x = off if cols.shape[1] == 0 else cols[:, 0]
        if x is None or np.std(x) == 0 or np.std(r) == 0:
            continue
        corr[eff.name] = float(np.corrcoef(x, r)[0, 1])
    out["correlation_with_candidates"] = corr
    return out


def _generic_basis(data: WindowData, dof: int):
    """Generic regressors for the structure test: shapes in the DOF's own velocity and
    force the library does not use (cube, sign), the heading, other logged channels and
    the thruster commands. Small on purpose: it must not overfit the held-out windows."""
    v = data.nu[:, dof]
    cols = [data.mean(v ** 3), data.mean(np.sign(v)), data.mean(np.sqrt(np.abs(v)) * v)]
    f = data.tau[:, dof]
    if np.std(f) > 0:
        cols += [data.mean_held(f * np.abs(f)), data.mean_held(np.abs(f))]
    psi = data.eta[:, 5]
    if np.ptp(psi) > 0.1:
        cols += [data.mean(np.cos(psi)), data.mean(np.sin(psi))]
    from stripcoef.logfile import KNOWN_COLUMNS
    for name, x in data.columns.items():
        if name not in KNOWN_COLUMNS and not name.startswith("n_") and np.std(x) > 0:
            cols += [data.mean(x)]
    if data.commands is not None:
        others = [k for k in range(data.commands.shape[1]) if k not in data.acting(dof)]
        if others:
            cols += [data.mean_held(np.abs(data.commands[:, others]).mean(axis=1))]
    cols.append(np.ones(data.n_windows))
    return np.column_stack(cols)


# ---------------------------------------------------------------------------
# the diagnosis of one DOF
# ---------------------------------------------------------------------------

def diagnose_dof(data: WindowData, dof: int, *, effects=None, bands=None,
                 max_steps: int = MAX_STEPS, excited=None, cross=None):
    """Run steps 1-5 for one DOF; returns the per-DOF result (the JSON-ready dictionary of
    :attr:`Diagnosis.per_dof`, see module) and its :class:`DofFit`.

    ``excited``: the excited DOFs (default: :func:`excited_dofs`); ``cross``: the other DOFs
    whose added mass this DOF may calibrate (:func:`_calibration`). Coefficients the log
    does not determine are kept at the prior (:func:`_identifiability`)."""
    names = list(effects) if effects is not None else list(EFFECTS)
    library = [get_effect(n) for n in names]
    excited = excited_dofs(data) if excited is None else list(excited)
    cal_cols, cal_sd, cal_names, cal_prior, band = _calibration(data, dof, bands, cross)
    ident = _identifiability(data, dof, cal_cols, cal_sd, cal_names, excited)
    keep = [j for j, n in enumerate(cal_names) if n not in ident["kept_at_prior"]]
    cal_cols = cal_cols[:, keep]
    cal_sd = np.asarray(cal_sd, float)[keep]
    cal_names = [cal_names[j] for j in keep]
    cal_prior = [cal_prior[j] for j in keep]
    data.__dict__.setdefault("_cal_prior", {})[dof] = np.asarray(cal_prior, float)
    data.__dict__.setdefault("_cal_names", {})[dof] = list(cal_names)
    e0 = data.e0[:, dof]
    unit = "N" if dof < 3 else "N m"
    result = {"dof": DOF[dof], "metric": METRIC, "units": unit,
              "baseline_error": _rms(e0), "baseline_held_out_error": _rms(e0)}

    cfg = _Config(data, dof, cal_cols, cal_sd, [])
    cur = _evaluate(cfg)
    th = cur["full"]["theta"]
    sd = np.sqrt(np.clip(np.diag(cur["full"]["cov"]), 0, None))
    result["calibration"] = {
        "parameters": {n: float(v) for n, v in zip(cal_names, th)},
        "std": {n: float(s) for n, s in zip(cal_names, sd)},
        "prior": dict(zip(cal_names, cal_prior)),
        "band_relative": {n: band[n] for n in cal_names},
        "band_source": _band_sources(data, dof, cal_names),
        "band_z": {n: float(v / s) for n, v, s in zip(cal_names, th, cal_sd)},
        "kept_at_prior": ident["kept_at_prior"],
        "information_ratio": ident["information_ratio"],
    }
    result["calibrated_error"] = cur["error"]
    result["calibrated_held_out_error"] = cur["held_out_error"]
    result["structure_before"] = _structure(data, dof, cur["full"]["resid"], library)

    steps, evaluated = [], []
    accepted_names = set()
    for step_index in range(max_steps):
        trials = []
        for eff in track(library, desc=f"diagnose {DOF[dof]}: step {step_index + 1}, effects",
                         unit="effect"):
            if eff.name in accepted_names:
                continue
            ok, why = eff.applicable(data, dof)
            if not ok:
                if not steps:
                    evaluated.append({"effect": eff.name, "applicable": False, "reason": why})
                continue
            trial_cfg = _Config(data, dof, cal_cols, cal_sd, list(cfg.terms) + [(eff, None)])
            try:
                ev = _evaluate(trial_cfg)
                ref = cur
                if eff.nuisance(data, dof) is not None:
                    ref = _evaluate(_Config(data, dof, cal_cols, cal_sd,
                                            list(cfg.terms) + [(_Nuisance(eff), None)]))
            except (np.linalg.LinAlgError, ValueError) as exc:
                evaluated.append({"effect": eff.name, "applicable": False,
                                  "reason": f"fit failed: {exc}"})
                continue
            trials.append(_judge(eff, trial_cfg, ev, ref, data, dof, cal_names, cal_sd,
                                 bands))
        if not steps:
            evaluated += [{k: v for k, v in t.items() if not k.startswith("_")} for t in trials]
        good = [t for t in trials if t["significant"]]
        if not good:
            break
        good.sort(key=lambda t: t["held_out_error_after"])
        best = good[0]
        ties = [t for t in good[1:]
                if t["held_out_error_after"] <= best["held_out_error_after"] * (1 + TIE)]
        if not best["signature"]:
            with_sig = [t for t in ties if t["signature"]]
            if with_sig:
                ties = [best] + [t for t in ties if t is not with_sig[0]]
                best = with_sig[0]
        step = {k: v for k, v in best.items() if not k.startswith("_")}
        step["error_before"] = cur["error"]
        step["held_out_error_before"] = cur["held_out_error"]
        step["alternatives"] = [{"effect": t["effect"], "parameters": t["parameters"],
                                 "held_out_error_after": t["held_out_error_after"],
                                 "signature": t["signature"]} for t in ties]
        step["dof"] = DOF[dof]
        steps.append(step)
        accepted_names.add(best["effect"])
        cfg = best["_cfg"]
        cur = best["_ev"]

    # parameters of every added effect refitted with all the others (the step's own values
    # are those it had when it was added)
    k = len(cal_names)
    th_all = cur["full"]["theta"]
    for step, (eff, hyper) in zip(steps, cfg.terms):
        ncol = eff.design(data, dof, hyper)[1].shape[1]
        nuis = eff.nuisance(data, dof)
        kn = 0 if nuis is None else nuis.shape[1]
        step["final_parameters"] = eff.to_parameters(th_all[k + kn:k + ncol], hyper,
                                                     th_all[k:k + kn])
        k += ncol
    th = cur["full"]["theta"]
    result["calibration"]["final_parameters"] = {n: float(v) for n, v in
                                                 zip(cal_names, th[:len(cal_names)])}
    result["steps"] = steps
    result["candidates"] = evaluated
    result["final_error"] = cur["error"]
    result["final_held_out_error"] = cur["held_out_error"]
    result["structure_after"] = _structure(data, dof, cur["full"]["resid"], library)
    result["unexplained"], result["unexplained_evidence"] = _unexplained(cfg, cur)
    return result, DofFit(config=cfg, evaluation=cur, prior_residual=e0)


def _judge(eff, cfg, ev, cur, data, dof, cal_names, cal_sd, bands_used=None):
    full = ev["full"]
    ncal = len(cal_names)
    n_lin_before = sum(c.design(data, dof, h)[1].shape[1] for c, h in cfg.terms[:-1])
    k0 = ncal + n_lin_before
    nuis = eff.nuisance(data, dof)
    kn = 0 if nuis is None else nuis.shape[1]
    theta_nuis = full["theta"][k0:k0 + kn]
    full_cov = full["cov"][k0:, k0:]
    theta_eff = full["theta"][k0 + kn:]
    cov_eff = full["cov"][k0 + kn:, k0 + kn:]
    sd_eff = np.sqrt(np.clip(np.diag(cov_eff), 0, None))
    hyper = ev["hyper"]
    hyper_sd = _hyper_std(cfg, hyper, full["sigma"]) if hyper is not None else np.zeros(0)
    params = eff.to_parameters(theta_eff, hyper, theta_nuis)
    std = eff.std_of(theta_eff, cov_eff, hyper_sd, full_cov)
    zc = eff.z_columns if eff.z_columns is not None else range(theta_eff.size)
    z_vals = [abs(theta_eff[j]) / sd_eff[j] if sd_eff[j] > 0 else math.inf for j in zc]
    if hyper is not None:
        z_vals += [abs(h) / s if s > 0 else math.inf
                   for h, s in zip(np.atleast_1d(hyper), hyper_sd)]
    z = max(z_vals) if z_vals else 0.0
    gain = 1.0 - ev["held_out_error"] / cur["held_out_error"] if cur["held_out_error"] > 0 \
        else 0.0
    dbic = ev["bic"] - cur["bic"]
    signature = eff.signature(data, dof)
    reasons = []
    key = eff.mimics
    mimic = not signature and key in cal_names and theta_eff.size > 0
    band_excess = None
    if mimic:
        # no signature: the effect is the prior coefficient released from its band. The
        # calibration may already have absorbed it (the data outweigh the band), so the
        # test is how far the released coefficient sits from the prior, in bands.
        j = cal_names.index(key)
        total = full["theta"][j] + theta_eff[0]
        band_excess = float(total / cal_sd[j])
        sd_total = math.sqrt(max(full["cov"][j, j] + cov_eff[0, 0]
                                 + 2 * full["cov"][j, k0 + kn], 0.0))
        z = abs(total) / sd_total if sd_total > 0 else math.inf
        params = eff.to_parameters(np.concatenate([[total], theta_eff[1:]]), hyper, theta_nuis)
        std = eff.std_of(np.concatenate([[total], theta_eff[1:]]), cov_eff, hyper_sd, full_cov)
        std[next(iter(eff.parameters))] = sd_total
        if abs(band_excess) < MIMIC_BANDS:
            reasons.append(f"no signature in this log and the {key} change it implies "
                           f"({total:.3g}) is within {MIMIC_BANDS:g} bands "
                           f"({MIMIC_BANDS * cal_sd[j]:.3g})")
    else:
        if gain < MIN_HELD_OUT_GAIN:
            reasons.append(f"held-out gain {100 * gain:.1f}% < {100 * MIN_HELD_OUT_GAIN:.0f}%")
        if dbic > -MIN_DELTA_BIC:
            reasons.append(f"delta BIC {dbic:.1f} > -{MIN_DELTA_BIC:g}")
    if z < MIN_Z:
        reasons.append(f"z = {z:.1f} < {MIN_Z:g} (parameter / its std)")
    why = eff.implausible(params, data, dof)
    if why:
        reasons.append(why)
    if getattr(eff, "scales_prior", False) and eff.magnitude(params) > 0:
        # a thrust scale s acts like inertia and drag all scaled by 1/s, which the prior's
        # own coefficients reproduce: like an effect without a signature, it must imply a
        # change beyond MIMIC_BANDS bands of the added mass -- the translational band in
        # every DOF (the thrusters' shortfall does not depend on the axis; with the
        # rotational band, 2.5 x 100 %, a yaw shortfall of 0.38 was left to the yaw
        # coefficients and the yaw free simulation lost to hold-last-velocity:
        # benchmarks/diagnose_heldout.py, docs/performance.md)
        band_m = (bands_used or BANDS)["translational"]["M"]
        implied = abs(1.0 / eff.magnitude(params) - 1.0)
        if implied < MIMIC_BANDS * band_m:
            reasons.append(f"the scale implies a common change of inertia and drag of "
                           f"{100 * implied:.0f}%, within {MIMIC_BANDS:g} bands "
                           f"({100 * MIMIC_BANDS * band_m:.0f}%)")
    # the totals the model would carry: prior + calibration + what the effect releases
    priors = {"M": float(data.model.added_mass[dof, dof]),
              "D_L": float(data.model.linear_damping[dof, dof]),
              "D_Q": float(data.model.quadratic_damping[dof, dof])}
    totals = {}
    for name, value in zip(eff.nuisance_names if kn else (), theta_nuis):
        if name in priors:
            cal = full["theta"][cal_names.index(name)] if name in cal_names else 0.0
            totals[name] = priors[name] + cal + float(value)
    if mimic and key in priors:
        totals[key] = priors[key] + float(band_excess * cal_sd[cal_names.index(key)])
    reasons += _physical_problems(data, dof, totals)
    low = cfg.lower(hyper)[k0:]
    fin = np.isfinite(low)
    tol = 1e-4 * np.maximum(1.0, np.abs(np.where(fin, low, 0.0)))
    at_bound = fin & (full["theta"][k0:] <= np.where(fin, low, 0.0) + tol)
    if np.any(at_bound):
        reasons.append("a parameter is pinned at its physical bound (e.g. zero added mass)")
    if not signature and not mimic and key:
        reasons.append(f"no signature in this log and the prior has no {key} to compare")
    nuisance = {n: float(v) for n, v in zip(eff.nuisance_names, theta_nuis)} if kn else {}
    return {"effect": eff.name, "applicable": True, "parameters": params, "std": std,
            "released": {k: v for k, v in nuisance.items() if k in ("M", "D_L", "D_Q")},
            "units": dict(eff.parameters), "signature": signature or None,
            "mimics": None if signature else eff.mimics,
            "band_excess": band_excess,
            "error_after": ev["error"], "held_out_error_after": ev["held_out_error"],
            "held_out_gain": gain, "delta_bic": dbic, "z": z,
            "significant": not reasons, "rejected_because": reasons,
            "magnitude": eff.magnitude(params), "source": eff.source,
            "_cfg": cfg, "_ev": ev}


def _unexplained(cfg, cur):
    """Fit a generic basis on top of the final model; structured when it cuts the
    cross-validated error by ``UNEXPLAINED_GAIN`` and lowers BIC by ``MIN_DELTA_BIC``."""
    data = cfg.data
    basis = _generic_basis(data, cfg.dof)
    generic = _Generic(basis)
    ev = _evaluate(_Config(data, cfg.dof, cfg.cal_cols, cfg.cal_sd,
                           list(cfg.terms) + [(generic, None)]))
    gain = 1.0 - ev["held_out_error"] / cur["held_out_error"] if cur["held_out_error"] > 0 \
        else 0.0
    dbic = ev["bic"] - cur["bic"]
    structured = gain >= UNEXPLAINED_GAIN and dbic < -MIN_DELTA_BIC
    # the noise floor: velocity noise through the rate term alone, F = M_ii sqrt(var(rate))
    floor = float(data.model.mass_matrix[cfg.dof, cfg.dof]) * math.sqrt(
        data.rate_noise_variance(cfg.dof))
    ratio = cur["held_out_error"] / floor if floor > 0 else math.inf
    above = ratio > NOISE_FLOOR_FACTOR and gain > 0.0
    return bool(structured or above), {
        "generic_basis_columns": int(basis.shape[1]), "held_out_gain": float(gain),
        "delta_bic": float(dbic), "threshold": UNEXPLAINED_GAIN, "noise_floor": floor,
        "held_out_error_over_noise_floor": float(ratio),
        "above_noise_floor": bool(above)}


class _Generic:
    """The generic basis as a term (free columns)."""

    hyper = ()
    name = "generic"

    def __init__(self, basis):
        self.basis = basis

    def design(self, data, dof, hyper=None):
        return None, self.basis


# ---------------------------------------------------------------------------
# public API
# ---------------------------------------------------------------------------

@dataclass(frozen=True)
class DofFit:
    """The final fit of one DOF's diagnosis, beyond its JSON: what the calibrated model and
    the residual plots are computed from.

    Attributes
    ----------
    config : the calibration columns and the accepted effects (with their nonlinear
        parameters) of the final fit
    evaluation : dict
        Its fit on all windows (``full``: ``theta``, ``cov``, ``resid``, ...) and held-out
        errors
    prior_residual : (n_windows,) array
        The prior's window force residual e_i [N or N m]
    """

    config: _Config
    evaluation: dict
    prior_residual: np.ndarray


#: the keys of :meth:`Diagnosis.to_dict`, in order (the JSON contract of ``diagnose --json``)
_JSON_FIELDS = ("metric", "metric_description", "window_s", "log", "vehicle", "dof", "units",
                "baseline_error", "calibrated_error", "steps", "final_error", "unexplained",
                "per_dof", "dropped_dofs", "excited_dofs", "dofs_not_diagnosed",
                "kept_at_prior", "bounds_hit", "added_mass_band", "prior_widths", "fitted_on_s",
                "validation", "holdout",
                "resimulated_velocity_rms", "resimulated_velocity_description")


def _finite_or_none(x):
    """``x`` (plain JSON types, :func:`stripcoef.model.plain`) with non-finite floats as None."""
    if isinstance(x, dict):
        return {k: _finite_or_none(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_finite_or_none(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    return x


@dataclass(frozen=True)
class Diagnosis:
    """The result of :func:`diagnose`.

    Attributes
    ----------
    metric, metric_description : str
        The error metric (:data:`METRIC`; ``..._relative`` for several DOFs)
    window_s : float
        Window of the one-step residual [s]
    log, vehicle : str
        The log's source and the prior model's name
    dof, units : str
        The DOF diagnosed (or ``all``) and the metric's units
    baseline_error, calibrated_error, final_error : float
        The metric for the prior, after the calibration, after the added effects (several
        DOFs: RMS over the DOFs of each DOF's error relative to its baseline)
    steps : tuple of dict
        The effects added, in order (effect, parameters, std, errors before and after ...)
    unexplained : bool
        A structured residual remains that no library effect explains
    per_dof : mapping
        DOF name -> its detailed result (calibration, candidates, structure, steps ...)
    model : HydroModel
        The calibrated model (the prior with its calibration and the added effects)
    resimulated_velocity_rms : dict, optional
        DOF -> RMS re-simulated velocity error of the prior, the calibrated prior and the
        final model [m/s or rad/s] (with ``resimulate``)
    resimulated_velocity_description : str, optional
    dropped_dofs : mapping
        DOFs ``dof='all'`` left out, and why (no column, no applied force, not excited)
    excited_dofs : tuple of str
        The DOFs the log excites (:func:`select_dofs`)
    dofs_not_diagnosed : mapping
        Every DOF not diagnosed -> why; its coefficients are those of the prior
    kept_at_prior : mapping
        DOF -> {coefficient (or ``all coefficients``): why the log does not determine it}
        (not excited, too little Fisher information: :func:`_identifiability`)
    bounds_hit : mapping
        DOF -> {coefficient: text} for each calibrated coefficient at a physical bound
        (:func:`bounds_hit`)
    prior_widths : dict, optional
        :meth:`PriorWidths.to_dict` of the method-table widths the calibration's Gaussian
        priors took (a vehicle file), None with the fixed :data:`BANDS` (a model file)
    added_mass_band : dict, optional
        The method uncertainty of the prior's added mass the calibration was bounded by
        (``relative_sd`` per DOF, ``z``), when known (``added_mass_sd``)
    fitted_on_s : tuple
        (start, end) [s] of the part of the log the coefficients were fitted on
    validation : dict, optional
        Free-simulation validation of every change (:func:`validate_changes`), or
        ``{"skipped": reason}``
    holdout : dict, optional
        With ``holdout``: the held-out free-simulation errors [m/s or rad/s] of the prior,
        the calibrated model as written and hold-last-velocity (:func:`heldout_errors`)
    fits : mapping
        DOF name -> :class:`DofFit` (for :meth:`residual_curves`)
    test_log : Log, optional
        The held-out end of the log (not in the JSON)
    diagnosed : tuple of int
        Indices of the diagnosed DOFs (not in the JSON)
    """

    metric: str
    metric_description: str
    window_s: float
    log: str
    vehicle: str
    dof: str
    units: str
    baseline_error: float
    calibrated_error: float
    steps: tuple
    final_error: float
    unexplained: bool
    per_dof: Mapping
    model: object
    resimulated_velocity_rms: dict | None = None
    resimulated_velocity_description: str | None = None
    #: DOFs of dof='all' left out, and why (no column, no applied force, not excited)
    dropped_dofs: Mapping = field(default_factory=dict)
    excited_dofs: tuple = ()
    dofs_not_diagnosed: Mapping = field(default_factory=dict)
    kept_at_prior: Mapping = field(default_factory=dict)
    bounds_hit: Mapping = field(default_factory=dict)
    fitted_on_s: tuple | None = None
    validation: dict | None = None
    holdout: dict | None = None
    added_mass_band: dict | None = None
    prior_widths: dict | None = None
    fits: Mapping = field(default_factory=dict, repr=False, compare=False)
    test_log: object = field(default=None, repr=False, compare=False)
    diagnosed: tuple = field(default=(), repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "steps", tuple(self.steps))
        object.__setattr__(self, "per_dof", frozen_mapping(self.per_dof))
        object.__setattr__(self, "fits", frozen_mapping(self.fits))
        for key in ("dropped_dofs", "dofs_not_diagnosed", "kept_at_prior", "bounds_hit"):
            object.__setattr__(self, key, frozen_mapping(getattr(self, key)))

    def to_dict(self) -> dict:
        """The JSON output of ``diagnose --json`` (no model; non-finite numbers as null)."""
        out = {}
        for key in _JSON_FIELDS:
            value = getattr(self, key)
            if value is not None or not key.startswith("resimulated"):
                out[key] = value
        return _finite_or_none(plain(out))

    def residual_curves(self, dof: str):
        """Window mid-times [s] and the window force residual [N or N m] of DOF ``dof``:
        ``(t, [(label, residual), ...])`` for the prior, the calibrated prior and after
        each added effect."""
        fit = self.fits[dof]
        cfg = fit.config
        data = cfg.data
        tw = 0.5 * (data.t[data.i0] + data.t[data.i1])
        curves = [("prior", fit.prior_residual)]
        for k in range(len(cfg.terms) + 1):
            c = _Config(data, cfg.dof, cfg.cal_cols, cfg.cal_sd, cfg.terms[:k])
            label = "calibrated" if k == 0 else f"+ {cfg.terms[k - 1][0].name}"
            curves.append((label, _fit(c)["resid"]))
        return tw, curves


def excited_dofs(data: WindowData) -> list:
    """The DOFs the log excites (:func:`select_dofs`)."""
    return select_dofs(data)[0]


def _excitation(data: WindowData, i: int):
    r"""(velocity std / its noise, reason the DOF is not excited or '').

    The noise of the velocity :math:`\sigma_{v,i}` [m/s or rad/s] is estimated from second
    differences, :math:`\mathrm{var}(\Delta^2\nu) = 6\sigma_v^2`, by the median absolute
    deviation (scale 1.4826 for a normal distribution; Rousseeuw & Croux 1993, J. Am. Stat.
    Assoc. 88) -- the estimator of :meth:`WindowData.rate_noise_variance`."""
    v = data.nu[:, i]
    d2 = v[2:] - 2 * v[1:-1] + v[:-2]
    noise = 1.4826 * float(np.median(np.abs(d2 - np.median(d2)))) / math.sqrt(6.0) \
        if d2.size else 0.0
    std = float(np.std(v))
    unit = "m/s" if i < 3 else "rad/s"
    snr = std / noise if noise > 0 else (math.inf if std > 1e-12 else 0.0)
    if np.ptp(data.tau[:, i]) == 0.0:
        return snr, (f"no applied force moves in {DOF[i]} ({FORCES[i]} is constant "
                     f"at {float(data.tau[0, i]):.3g})")
    if snr < EXCITATION_SNR:
        return snr, (f"not excited (std of {VELOCITIES[i]} {std:.3g} {unit} is {snr:.2g}x "
                     f"its noise {noise:.3g}, less than {EXCITATION_SNR:g}x)")
    return snr, ""


def select_dofs(data: WindowData) -> tuple:
    r"""The DOFs the log excites (those ``dof="all"`` diagnoses) and, for each other one, why.

    A DOF is excited when the log has its velocity column, an applied force acts in it and
    moves, and its velocity varies: standard deviation above ``EXCITATION_STD`` [m/s or
    rad/s] and at least :data:`EXCITATION_SNR` times its white noise,
    :math:`\mathrm{std}(\nu_i) \ge 3\,\sigma_{v,i}` (:func:`_excitation`); a missing column
    is never read as zeros.

    Returns
    -------
    (list of int, dict of DOF name -> reason)
    """
    out, dropped = [], {}
    for i in range(6):
        v = VELOCITIES[i]
        unit = "m/s" if i < 3 else "rad/s"
        if v not in data.log:
            dropped[DOF[i]] = f"no column {v} in the log"
        elif not np.any(data.tau[:, i] != 0):
            dropped[DOF[i]] = f"no applied force in {DOF[i]} ({FORCES[i]} is zero throughout)"
        elif not np.std(data.nu[:, i]) > EXCITATION_STD:
            dropped[DOF[i]] = (f"not excited (std of {v} {np.std(data.nu[:, i]):.2g} {unit} "
                               f"<= {EXCITATION_STD:g})")
        elif _excitation(data, i)[1]:
            dropped[DOF[i]] = _excitation(data, i)[1]
        else:
            out.append(i)
    return out, dropped


def diagnose(log, model, *, dof="all", window: float = DEFAULT_WINDOW, effects=None,
             resimulate: bool = False, bands=None, max_steps: int = MAX_STEPS,
             time_limit: float | None = None,
             validation: float | None = VALIDATION_FRACTION,
             holdout: float | None = None, added_mass_sd=None,
             prior_widths: PriorWidths | None = None) -> Diagnosis:
    """Diagnose a log against a prior model (module docstring).

    Parameters
    ----------
    log : Log
        Time series with ``t``, velocities and inputs (commands or forces).
    model : HydroModel
        The prior (strip-theory) model; its ``effects`` (a calibrated model's) are part of
        the residual, so they are not found again.
    dof : str
        A DOF name (surge..yaw, u..r, X..N) or ``"all"`` (every excited DOF).
    window : float
        Window length of the one-step residual [s].
    effects : list of str, optional
        Candidate effects (default: the whole library).
    resimulate : bool
        Also report the RMS of the re-simulated velocity (baseline, calibrated, final).
    time_limit : float, optional
        Wall-clock budget [s] (default :data:`TIME_LIMIT`; ``inf``: none); past it an
        :class:`~stripcoef.errors.UnreachableError` says so instead of grinding.
    validation : float or None
        Fraction of the fitting log (its end) kept to validate every change by free
        simulation (:func:`validate_changes`); None or 0 keeps every change.
    holdout : float or None
        Fraction of the log (its end) never used for fitting: the held-out free-simulation
        errors of the prior, the calibrated model (as written) and hold-last-velocity are
        reported on it (:attr:`Diagnosis.holdout`).
    added_mass_sd : (6,) array, optional
        Relative 1-sigma method uncertainty [-] of the prior's added mass per DOF
        (:func:`method_added_mass_sd`; NaN where unknown): the calibrated added mass stays
        within its 99.7 % band (:func:`added_mass_bounds`); one outside it is clipped to it
        and listed in ``bounds_hit``. Default: that of ``prior_widths``.
    prior_widths : PriorWidths, optional
        The widths of the calibration's Gaussian priors from the method table
        (:func:`method_prior_widths`, :func:`prior_widths` of a vehicle file), in the place
        of :data:`BANDS`; ``bands``, when given, overrides them. Recorded in the JSON with
        the row each width came from (``prior_widths``, ``per_dof.<dof>.calibration.
        band_source``).

    Returns
    -------
    Diagnosis
        ``metric``, ``baseline_error``, ``calibrated_error``, ``steps`` (each with
        ``effect``, ``parameters``, ``std``, ``error_before``, ``error_after``,
        ``held_out_error_before``, ``held_out_error_after``), ``final_error``,
        ``unexplained``, ``excited_dofs``, ``dofs_not_diagnosed``, ``kept_at_prior``,
        ``bounds_hit``, ``validation``, ``holdout``, ``per_dof`` details, ``model`` (the
        calibrated HydroModel); :meth:`Diagnosis.to_dict` is the JSON contract (everything
        but the model).
    """
    limit = TIME_LIMIT if time_limit is None else float(time_limit)
    if not limit > 0:
        raise InputError("not a positive time budget", key="time_limit", value=time_limit,
                         expected="a number of seconds > 0 (inf: none)")
    for key, value in (("holdout", holdout), ("validation", validation)):
        if value is not None and not (isinstance(value, (int, float))
                                      and 0.0 <= float(value) < 1.0):
            raise InputError("not a fraction", key=key, value=value,
                             expected="a number in [0, 1), e.g. 0.3")
    if prior_widths is not None and not isinstance(prior_widths, PriorWidths):
        raise InputError("not prior widths", key="prior_widths",
                         value=type(prior_widths).__name__,
                         expected="a PriorWidths (method_prior_widths(vehicle)) or None")
    if added_mass_sd is None and prior_widths is not None:
        added_mass_sd = prior_widths.added_mass_sd
    if added_mass_sd is not None:
        added_mass_sd = np.asarray(added_mass_sd, float).reshape(-1)
        if added_mass_sd.size != 6 or np.any(added_mass_sd[np.isfinite(added_mass_sd)] < 0):
            raise InputError("not six relative standard deviations", key="added_mass_sd",
                             value=added_mass_sd.tolist(),
                             expected="6 numbers >= 0 (NaN where unknown), one per DOF")
    _deadline.update(at=time.monotonic() + limit if math.isfinite(limit) else None,
                     limit=limit, rows=len(log), source=log.source)
    try:
        return _diagnose(log, model, dof=dof, window=window, effects=effects,
                         resimulate=resimulate, bands=bands, max_steps=max_steps,
                         validation=validation or None, holdout=holdout or None,
                         added_mass_sd=added_mass_sd, prior_widths=prior_widths)
    finally:
        _deadline["at"] = None


def _diagnose(log, model, *, dof, window, effects, resimulate, bands, max_steps,
              validation, holdout, added_mass_sd=None, prior_widths=None) -> Diagnosis:
    """:func:`diagnose` inside its time budget."""
    from stripcoef.diagnose.heldout import split

    if str(dof).lower() != "all":
        log.require(VELOCITIES[parse_dof(dof)])       # never a missing column read as zeros
    fit_log, test_log = (log, None) if not holdout else split(log, holdout, key="holdout")
    train_log, val_log, skipped = fit_log, None, None
    if validation:
        try:
            train_log, val_log = split(fit_log, validation, key="validation")
            window_data(train_log, model, window=window)
        except InputError as exc:  # too short to spare a validation part: fit on all of it
            train_log, val_log, skipped = fit_log, None, str(exc)
    data = window_data(train_log, model, window=window)
    data.__dict__["_added_mass_sd"] = added_mass_sd
    # the calibration's prior widths: the bands given, else the method table's, else BANDS
    data.__dict__["_prior_widths"] = prior_widths if bands is None else None
    data.__dict__["_bands_given"] = bands is not None
    if model.effects:  # a calibrated model: its effects are part of its prediction
        data.e0 = data.e0 - effect_window_forces(data, model)
    excited, not_excited = select_dofs(data)
    dropped = {}
    if str(dof).lower() == "all":
        dofs, dropped = excited, dict(not_excited)
        if not dofs:
            raise InputError("no excited degree of freedom", file=log.source,
                             expected="a log where some DOF has its velocity column, an "
                             "applied force and motion above its noise (" + "; ".join(
                                 f"{k}: {v}" for k, v in dropped.items()) + ")")
        if dropped:
            warnings.warn(f"{log.source}: dof='all' diagnoses " + ", ".join(DOF[i] for i in dofs)
                          + " and drops " + "; ".join(f"{k} ({v})" for k, v in dropped.items()),
                          ModelWarning, stacklevel=3)
    else:
        dofs = [parse_dof(dof)]
    not_diagnosed = {k: v for k, v in not_excited.items() if parse_dof(k) not in dofs}
    absent = [v for v in VELOCITIES if v not in log]
    if absent:
        warnings.warn(f"{log.source}: no column {', '.join(absent)}: the coupling terms "
                      "(C(nu) nu of the diagnosed DOFs) take them as 0", ModelWarning,
                      stacklevel=3)
    cross = [j for j in excited if j not in dofs]
    per, fits = {}, {}
    for i in dofs:
        per[DOF[i]], fits[DOF[i]] = diagnose_dof(data, i, effects=effects, bands=bands,
                                                 max_steps=max_steps, excited=excited,
                                                 cross=cross)
    exclude, record = set(), None
    if val_log is not None:
        exclude, record = validate_changes(val_log, model, per, fits, dofs)
    calibrated = calibrated_model(model, per, fits, exclude)
    calibrated, clipped = clip_added_mass(model, calibrated, added_mass_sd)
    if len(dofs) == 1:
        r = per[DOF[dofs[0]]]
        summary = {"metric": METRIC, "dof": r["dof"], "units": r["units"],
                   "baseline_error": r["baseline_error"],
                   "calibrated_error": r["calibrated_error"],
                   "steps": r["steps"], "final_error": r["final_error"],
                   "unexplained": r["unexplained"]}
    else:
        def rel(key):
            return float(np.sqrt(np.mean([(per[d][key] / per[d]["baseline_error"]) ** 2
                                          for d in per])))
        summary = {"metric": METRIC + "_relative", "dof": "all",
                   "units": "relative to each DOF's baseline",
                   "baseline_error": 1.0, "calibrated_error": rel("calibrated_error"),
                   "steps": [s for d in per for s in per[d]["steps"]],
                   "final_error": rel("final_error"),
                   "unexplained": any(per[d]["unexplained"] for d in per)}
    kept = {d: dict(per[d]["calibration"]["kept_at_prior"]) for d in per}
    for d, why in not_diagnosed.items():
        kept[d] = {"all coefficients": why}
    if resimulate:
        summary["resimulated_velocity_rms"] = resimulated_errors(train_log, model, per, fits,
                                                                 calibrated, exclude)
        summary["resimulated_velocity_description"] = (
            "RMS of logged minus re-simulated velocity [m/s or rad/s] of each diagnosed DOF "
            "on the fitting log: the prior, the prior with its calibrated coefficients, and "
            "the final model")
    result = Diagnosis(metric_description=METRIC_TEXT, window_s=window, log=log.source,
                       vehicle=model.name, per_dof=per, model=calibrated, fits=fits,
                       dropped_dofs=dropped, excited_dofs=tuple(DOF[i] for i in excited),
                       dofs_not_diagnosed=not_diagnosed, kept_at_prior=kept,
                       bounds_hit=bounds_hit(model, calibrated, added_mass_sd, clipped),
                       added_mass_band=_band_record(added_mass_sd),
                       prior_widths=(prior_widths.to_dict() if prior_widths is not None
                                     and bands is None else None),
                       validation=record if skipped is None else {"skipped": skipped},
                       fitted_on_s=(float(train_log["t"][0]), float(train_log["t"][-1])),
                       test_log=test_log, diagnosed=tuple(dofs), **summary)
    if test_log is not None:
        # recomputed from the model as it is written (its dictionary form, read back)
        written = type(calibrated).from_dict(calibrated.to_dict())
        result = replace(result, holdout=heldout_errors(result, model, written))
    return result


def heldout_errors(result: Diagnosis, prior, written) -> dict:
    """Held-out free-simulation errors of the prior, the model as written and
    hold-last-velocity on the held-out part of the log of a :func:`diagnose` result
    (:mod:`stripcoef.diagnose.heldout`) [m/s or rad/s]."""
    from stripcoef.diagnose.heldout import HORIZON, compare

    test_log, dofs = result.test_log, list(result.diagnosed)
    errors = compare(test_log, {"prior": prior, "calibrated": written}, dofs)
    return {"description": "RMS free-simulation velocity error on the held-out end of the log "
                           f"[m/s or rad/s]: {HORIZON:g}-s simulations from the logged state; "
                           "hold_last_velocity predicts the velocity at each start",
            "held_out_s": [float(test_log["t"][0]), float(test_log["t"][-1])],
            "horizon_s": HORIZON, "errors": errors}


def _band_record(added_mass_sd):
    """The JSON record of the added-mass bands a diagnosis ran with (None without)."""
    if added_mass_sd is None:
        return None
    return {"relative_sd": {DOF[i]: (float(v) if np.isfinite(v) else None)
                            for i, v in enumerate(added_mass_sd)},
            "z": ADDED_MASS_BAND_Z,
            "description": "method uncertainty of the prior's added mass (1 sigma of ln M, "
                           "about relative; stripcoef.study.sources); the calibrated added mass "
                           f"stays within a factor e^(+-{ADDED_MASS_BAND_Z:g} sigma) (99.7 %)"}


def clip_added_mass(prior, calibrated, added_mass_sd=None):
    """``(model, clipped)``: ``calibrated`` with each diagonal added mass clipped to
    :func:`added_mass_bounds` of the prior's (a new model if anything moved), and
    ``{dof: (value before, value after)}`` [kg or kg m^2] of the clipped ones. The fits are
    bounded already; this catches what an effect adds to the matrix afterwards."""
    ma = np.array(calibrated.added_mass, float)
    clipped = {}
    for i in range(6):
        ma0 = float(prior.added_mass[i, i])
        if ma0 == 0.0 or ma[i, i] == ma0:
            continue
        lo, hi = added_mass_bounds(i, ma0, None if added_mass_sd is None
                                   else float(added_mass_sd[i]))
        value = float(np.clip(ma[i, i], lo, hi))
        if value != ma[i, i]:
            clipped[DOF[i]] = (float(ma[i, i]), value)
            ma[i, i] = value
    if not clipped:
        return calibrated, clipped
    return replace(calibrated, added_mass=ma), clipped


def bounds_hit(prior, calibrated, added_mass_sd=None, clipped=None) -> dict:
    """The coefficients of a calibrated model at a physical bound: DOF -> {name: text}, for
    an added mass at a limit of :func:`added_mass_bounds` (the 99.7 % method band with
    ``added_mass_sd``; ``clipped``: :func:`clip_added_mass`'s record) and a drag at zero."""
    out = {}
    clipped = clipped or {}
    for i in range(6):
        hits = {}
        ma0, ma = float(prior.added_mass[i, i]), float(calibrated.added_mass[i, i])
        if ma0 != 0.0:
            sd = None if added_mass_sd is None else float(added_mass_sd[i])
            lo, hi = added_mass_bounds(i, ma0, sd)
            band = (f"the 99.7 % band of its method uncertainty ({100 * sd:g} % at 1 sigma) "
                    "and its plausible range" if sd is not None and np.isfinite(sd) and sd > 0
                    else "its plausible range")
            for value, name in ((lo, "lower"), (hi, "upper")):
                # within the bounded scalar search's tolerance (1e-6 of the DOF's whole
                # inertia M_RB + M_A, a few 1e-6 of M_A): at the bound
                if ma != ma0 and abs(ma - value) <= 1e-5 * max(abs(value), 1e-12):
                    hits["M"] = (f"added mass {ma:.4g} at the {name} bound of {band} "
                                 f"[{lo:.4g}, {hi:.4g}]")
                    if DOF[i] in clipped:
                        hits["M"] += f", clipped from {clipped[DOF[i]][0]:.4g}"
        for key, attr in (("D_L", "linear_damping"), ("D_Q", "quadratic_damping")):
            d0, d = float(getattr(prior, attr)[i, i]), float(getattr(calibrated, attr)[i, i])
            if d0 != 0.0 and d != d0 and abs(d) <= 1e-9 * abs(d0):
                hits[key] = f"{key} {d:.3g} at its bound 0 (no negative drag)"
        if hits:
            out[DOF[i]] = hits
    return out


def _changes(per: dict) -> list:
    """The changes a diagnosis makes to the prior: each DOF's calibration and each effect."""
    out = []
    for d, r in per.items():
        if any(v != 0.0 for v in r["calibration"]["final_parameters"].values()):
            out.append(("calibration", d))
        out += [("effect", d, s["effect"]) for s in r["steps"]]
    return out


def validate_changes(val_log, prior, per: dict, fits: dict, dofs) -> tuple[set, dict]:
    r"""Keep a change only if it improves the free simulation of data it was not fitted on.

    Backward elimination (Hastie, Tibshirani & Friedman 2009, sec. 3.3.2) on the validation
    log: with :math:`r_i = E_i / E_i^{prior}` the free-simulation error of DOF i [m/s or
    rad/s] (:func:`stripcoef.diagnose.heldout.free_simulation_errors`) relative to the
    prior's, a model's score is the pair (number of DOFs with :math:`r_i > 1`,
    :math:`\sum_i r_i^2`), compared in that order; the change (a DOF's calibration or one
    effect) whose removal gives the best score is removed while that score is no worse than
    the current one (ties go to the simpler model), so the result never simulates an
    excited DOF worse than the prior on the validation data unless every subset does.

    Returns ``(excluded changes, record)``.
    """
    from stripcoef.diagnose.heldout import free_simulation_errors, hold_last_velocity_errors

    base = free_simulation_errors(val_log, prior, dofs)
    ref = base if base is not None else hold_last_velocity_errors(val_log, dofs)
    ref = [max(e, 1e-12) for e in ref]
    cache = {}

    def score(excl):
        key = frozenset(excl)
        if key not in cache:
            _check_budget()
            e = free_simulation_errors(val_log, calibrated_model(prior, per, fits, key), dofs)
            if e is None:
                cache[key] = ((math.inf, math.inf), None)
            else:
                r = [a / b for a, b in zip(e, ref)]
                cache[key] = ((sum(x > 1.0 + 1e-9 for x in r), float(sum(x * x for x in r))),
                              e)
        return cache[key]

    changes = _changes(per)
    excl = set()
    cur = score(excl)
    first = cur[1]
    while len(excl) < len(changes):
        trials = [(score(excl | {c}), c) for c in
                  track([c for c in changes if c not in excl],
                        desc="diagnose: validating the changes", unit="model")]
        (best, _), c = min(trials, key=lambda x: x[0][0])
        if best[0] > cur[0][0] or (best[0] == cur[0][0] and best[1] > cur[0][1]):
            break
        excl.add(c)
        cur = score(excl)

    def named(e):
        return None if e is None else {DOF[i]: float(v) for i, v in zip(dofs, e)}

    for d, r in per.items():
        r["calibration"]["kept"] = ("calibration", d) not in excl
        for s in r["steps"]:
            s["kept"] = ("effect", d, s["effect"]) not in excl
    record = {"description": "RMS free-simulation velocity error [m/s or rad/s] on the last "
                             "part of the fitting log, not used to fit: each change is kept "
                             "only if removing it makes this worse",
              "validation_s": [float(val_log["t"][0]), float(val_log["t"][-1])],
              "prior": named(base), "all_changes": named(first), "kept_changes": named(cur[1]),
              "removed": [" ".join(c[1:][::-1]) if c[0] == "effect" else f"{c[1]} calibration"
                          for c in changes if c in excl]}
    return excl, record


def _writable_matrices(model) -> dict:
    """Writable copies of a model's M_A, D_L, D_Q under the calibration's names."""
    return {"M": np.array(model.added_mass, float), "D_L": np.array(model.linear_damping, float),
            "D_Q": np.array(model.quadratic_damping, float)}


def _with_matrices(model, mats: dict):
    """``model`` with the matrices of :func:`_writable_matrices` (a new model)."""
    return replace(model, added_mass=mats["M"], linear_damping=mats["D_L"],
                   quadratic_damping=mats["D_Q"])


def calibrated_model(model, per: dict, fits: dict, exclude=frozenset()):
    """The prior with its calibrated coefficients and the added effects (a new model);
    ``per``: DOF -> its result (:func:`diagnose_dof`), ``fits``: DOF -> its :class:`DofFit`;
    ``exclude``: changes left out, ``("calibration", dof)`` or ``("effect", dof, name)``
    (see :func:`validate_changes`).

    The calibration of DOF i adds its own M, D_L, D_Q and the other DOFs' added mass
    ``M_<dof>`` seen through C_A -- unless that DOF is diagnosed itself, whose own
    calibration then holds."""
    m = model
    mats = _writable_matrices(m)
    record = []
    for d, r in per.items():
        i = parse_dof(d)
        cal = r["calibration"]["final_parameters"]
        cfg = fits[d].config
        theta = fits[d].evaluation["full"]["theta"]
        k = len(r["calibration"]["parameters"])
        dropped = [t for t in cfg.terms if ("effect", d, t[0].name) in exclude]
        if dropped:
            # the kept terms refitted without the removed ones (their nonlinear parameters
            # as selected), so that no kept parameter compensates a term that is not there
            cfg = _Config(cfg.data, i, cfg.cal_cols, cfg.cal_sd,
                          [t for t in cfg.terms if t not in dropped])
            theta = _fit(cfg)["theta"]
            cal = {n: float(v) for n, v in zip(cal, theta[:k])}
        if ("calibration", d) not in exclude:
            for key, value in cal.items():
                if key in ("M", "D_L", "D_Q"):
                    mats[key][i, i] += value
                elif key.startswith("M_") and key[2:] not in per:
                    j = parse_dof(key[2:])
                    mats["M"][j, j] += value
        kept_effects = []
        for eff, hyper in cfg.terms:
            ncol = eff.design(cfg.data, i, hyper)[1].shape[1]
            nuis = eff.nuisance(cfg.data, i)
            kn = 0 if nuis is None else nuis.shape[1]
            tn = theta[k:k + kn]
            params = eff.to_parameters(theta[k + kn:k + ncol], hyper, tn)
            k += ncol
            if ("effect", d, eff.name) in exclude:
                continue
            for name, value in zip(eff.nuisance_names, tn):
                if name in mats:  # a prior coefficient released by this effect
                    mats[name][i, i] += float(value)
            step = next((s for s in r["steps"] if s["effect"] == eff.name), {})
            # a native effect adds its term to the matrices calibrated so far
            m = eff.apply(_with_matrices(m, mats), i, params, step.get("std"))
            mats = _writable_matrices(m)
            kept_effects.append(eff.name)
        record.append({"dof": d, "calibration": cal if ("calibration", d) not in exclude
                       else {}, "effects": kept_effects})
    m = _with_matrices(m, mats).with_provenance(diagnose=record)
    return replace(m, name=f"{model.name}-calibrated")


def resimulated_errors(log, prior, per: dict, fits: dict, calibrated,
                       exclude=frozenset()) -> dict:
    """RMS of the re-simulated velocity of each diagnosed DOF for the prior, the prior with
    only its calibrated coefficients, and the final model [m/s or rad/s] (None when the
    simulation diverges)."""
    no_effects = set(exclude) | {c for c in _changes(per) if c[0] == "effect"}
    only_cal = calibrated_model(prior, per, fits, no_effects)
    dofs = [parse_dof(d) for d in per]
    rows = {name: resimulate_rms(log, m, dofs) for name, m in
            track((("baseline", prior), ("calibrated", only_cal), ("final", calibrated)),
                  desc="diagnose: re-simulating", unit="model")}
    return {DOF[i]: {name: (None if rows[name] is None else rows[name][k])
                     for name in rows} for k, i in enumerate(dofs)}


#: Horizon of the re-simulated velocity error [s] (:data:`stripcoef.diagnose.heldout.HORIZON`).
RESIMULATION_HORIZON = 10.0


def resimulate_rms(log, model, dofs, *, horizon: float = RESIMULATION_HORIZON):
    """RMS differences between the logged and the re-simulated velocities of ``dofs``
    (list) over segments of ``horizon`` seconds, or None if a simulation diverges
    (:func:`stripcoef.diagnose.heldout.free_simulation_errors`, tolerances 1e-6, 1e-8)."""
    from stripcoef.diagnose.heldout import free_simulation_errors
    return free_simulation_errors(log, model, dofs, horizon=horizon, tolerances=(1e-6, 1e-8))


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
    cal_cols, cal_sd, cal_names, _, _ = _calibration(data, i, bands)
    cfg = _Config(data, i, cal_cols, cal_sd, [])
    ev = _evaluate(cfg)
    for name in effects:
        cfg = _Config(data, i, cal_cols, cal_sd, list(cfg.terms) + [(get_effect(name), None)])
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
            probe = _Config(data, i, cal_cols, cal_sd,
                            [t for t in cfg.terms if t[0] is not eff] + [(eff, hyper)])
            hsd = _hyper_std(probe, hyper, full["sigma"])
        params[eff.name] = eff.to_parameters(theta[own], hyper, theta[k:k + kn])
        std[eff.name] = eff.std_of(theta[own], cov[own, own], hsd, cov[k:k + ncol, k:k + ncol])
        k += ncol
    return EffectFit(parameters=params, std=std,
                     calibration={n: float(v) for n, v in zip(cal_names, theta[:len(cal_names)])},
                     error=float(ev["error"]), held_out_error=float(ev["held_out_error"]))
