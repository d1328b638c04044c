r"""Grid convergence of a discretised result: observed order and the grid convergence index.

The panel method's added mass is computed on a family of panellings of one surface, of
representative panel sizes :math:`h_1 < h_2 < h_3` (fine to coarse; for a surface of N panels
:math:`h \propto N^{-1/2}`, so :math:`r_{21} = h_2/h_1 = \sqrt{N_1/N_2}`).  With the results
:math:`f_1, f_2, f_3` of one quantity and :math:`\varepsilon_{21} = f_2 - f_1`,
:math:`\varepsilon_{32} = f_3 - f_2`, the observed order of convergence p solves (Celik et al.
2008, "Procedure for estimation and reporting of uncertainty due to discretization in CFD
applications", J. Fluids Eng. 130(7) 078001, eqs. 3-5; for a constant ratio it is Roache 1998
eq. 5.10.6.1, :math:`p = \ln(\varepsilon_{32}/\varepsilon_{21})/\ln r`)

.. math::
    p = \frac{1}{\ln r_{21}}\,\Big|\ln\Big|\frac{\varepsilon_{32}}{\varepsilon_{21}}\Big|
        + q(p)\Big|,\qquad
    q(p) = \ln\frac{r_{21}^p - s}{r_{32}^p - s},\qquad
    s = \operatorname{sign}(\varepsilon_{32}/\varepsilon_{21}) \quad [-]

and the grid convergence index of the fine solution (Roache 1994, "Perspective: a method for
uniform reporting of grid refinement studies", J. Fluids Eng. 116(3) 405-413; Roache 1998,
"Verification and Validation in Computational Science and Engineering", Hermosa, ch. 5;
ASME V&V 20-2009, sec. 5.4) is the error band

.. math::
    \mathrm{GCI}_1 = F_s\,\frac{|f_2 - f_1|}{r_{21}^{p} - 1} \quad [\text{the unit of } f]

with the safety factor and the order chosen as Oberkampf & Roy prescribe (Oberkampf & Roy
2010, "Verification and Validation in Scientific Computing", Cambridge Univ. Press,
sec. 8.6.3.2; Roy 2005, "Review of code and solution verification procedures for
computational simulation", J. Comput. Phys. 205, 131-156): where the observed order lies
within 10 % of the formal one, :math:`|\hat p - p_f| \le 0.1\,p_f`, the solutions are in the
asymptotic range and :math:`F_s = 1.25`, :math:`p = p_f`; otherwise :math:`F_s = 3` and
:math:`p = \min(\max(0.5, \hat p), p_f)`.  Two grids: :math:`F_s = 3`, p the formal order
(Roache 1994).  An oscillating sequence (s < 0) or one with no observed order falls back to the
two-grid index on the larger of the two changes.  Nothing here is fitted to a benchmark.

Why not Roache's plain three-grid rule (:math:`F_s = 1.25` with any observed order up to the
formal one): the panel levels of bodies with sharp edges and thin members are often not in the
asymptotic range (the observed order of the three finest levels moves from 0.6 to 3 between
terms of one body), and on the CAD-style shapes of benchmarks/cad_shapes.py the 1.25 band
covered 276 of 310 terms (89 %); with the rule above, the same levels cover 287 (93 %),
docs/validation.md.

Four levels or more: the least-squares procedure of Eça & Hoekstra (2014), "A procedure for
the estimation of the numerical uncertainty of CFD calculations based on grid refinement
studies", J. Comput. Phys. 262, 104-130 (:func:`eca_hoekstra`).  The error of level i of
size :math:`h_i` is modelled as (their sec. 2, eq. 1 with p free; the alternatives with fixed
orders, eqs. 5-7)

.. math::
    \delta_{RE} = \phi_i - \phi_0 = \alpha h_i^{p},\quad
    \delta_1 = \alpha h_i,\quad \delta_2 = \alpha h_i^2,\quad
    \delta_{12} = \alpha_1 h_i + \alpha_2 h_i^2 \quad [\text{the unit of } \phi]

each fitted to all :math:`n_g \ge 4` levels by least squares, without weights and with the
weights :math:`w_i = (1/h_i)/\sum_j (1/h_j)` that favour the fine levels (sec. 2.2, eq. 16;
App. B), of standard deviation

.. math::
    \sigma = \sqrt{\frac{\sum_i n_g w_i\,(\phi_i - \phi_{fit}(h_i))^2}{n_g - n_p}}
    \quad (w_i = 1/n_g \text{ without weights};\ n_p \text{ the fit's parameters}).

The procedure (sec. 3, App. A): of the two fits of :math:`\delta_{RE}` the one of the smaller
:math:`\sigma` gives the observed order p (a fit with p <= 0 is discarded; none left: the data
are "anomalous").  For :math:`0.5 \le p \le 2` that fit is the error estimate; for p > 2 the
best (smallest :math:`\sigma`) of :math:`\delta_1, \delta_2` with and without weights; for
p < 0.5 or anomalous data the best of :math:`\delta_1, \delta_2, \delta_{12}`, with and without
weights.  With the data range :math:`\Delta_\phi = (\phi_{max} - \phi_{min})/(n_g - 1)`
(eq. 19), :math:`\varepsilon_\phi = |\phi_{fit}(h_1) - \phi_0|` the fit's error of the finest
level and the safety factor :math:`F_s = 1.25` where :math:`0.5 \le p < 2.1` and
:math:`\sigma < \Delta_\phi`, else :math:`F_s = 3`, the uncertainty of the finest level is
(eqs. 20-21)

.. math::
    U_\phi = F_s\,\varepsilon_\phi + \sigma + |\phi_1 - \phi_{fit}(h_1)|
    \quad (\sigma < \Delta_\phi),\qquad
    U_\phi = 3\,\frac{\sigma}{\Delta_\phi}\,\big(\varepsilon_\phi + \sigma
    + |\phi_1 - \phi_{fit}(h_1)|\big) \quad (\sigma \ge \Delta_\phi)

with :math:`\phi_1 - U_\phi \le \phi_{exact} \le \phi_1 + U_\phi` at about 95 % (eq. 18).  The
formal order the paper assumes (2, the reason for the thresholds 2 and 2.1) is that of
constant panels, whose error goes as 1/N.  ``extra_orders`` adds one-term fits
:math:`\alpha h^{q}` of fixed orders q to the alternatives (for example an order that an
edge singularity implies); the paper's own set is the default.  Section and equation
numbers as the paper's Appendix A cites them (read from published implementations of it that
quote the paper; to be checked against the paper).

An edge's order, as a hypothesis (not a default): in a wedge of fluid of angle
:math:`\omega` the potential goes as :math:`r^{\lambda}`, :math:`\lambda = \pi/\omega` (2/3
at a right-angled convex edge, 1/2 at a plate's rim; the edge singularities of von
Petersdorff & Stephan 1990, Math. Methods Appl. Sci. 12, 229-249).  A Galerkin boundary
element solution on uniform panels then converges in the energy norm as :math:`h^{\lambda}`
(ibid.: the reduced rate that their graded meshes restore), and a smooth linear functional such as an added-mass term, by the duality
argument, as :math:`h^{2\lambda}`: order 4/3 at a right-angled edge, 1 at a plate's rim
(the latter is :math:`\delta_1`).  Collocation, which Capytaine and the panel method use,
has no such estimate on polyhedral surfaces (Atkinson 1997, "The Numerical Solution of
Integral Equations of the Second Kind", Cambridge, ch. 9), so the order stays an
alternative the standard deviation chooses or not: on the CAD shapes' BEM levels 4/3 is
chosen for one diagonal term in 216 and changes no count of
``python -m benchmarks.bem_fine_references compare ... --edge-orders 1.3333333333333333``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Safety factor of the grid convergence index with three grids and the observed order [-]
#: (Roache 1998, sec. 5.6; ASME V&V 20-2009, sec. 5.4).
SAFETY_THREE_GRIDS = 1.25
#: Safety factor with two grids (order not observed) [-] (Roache 1994; Roache 1998, sec. 5.6).
SAFETY_TWO_GRIDS = 3.0
#: Lowest order the three-grid index uses [-] (Oberkampf & Roy 2010, sec. 8.6.3.2: p =
#: min(max(0.5, observed), formal) with F_s = 3 outside the asymptotic range).
MIN_ORDER = 0.5
#: Largest relative distance of the observed order from the formal one, :math:`|\hat p - p_f|
#: / p_f`, for which the solutions count as asymptotic and :data:`SAFETY_THREE_GRIDS` applies
#: [-] (Oberkampf & Roy 2010, sec. 8.6.3.2).
ASYMPTOTIC_ORDER_TOLERANCE = 0.1


def observed_order(f1, f2, f3, r21, r32, *, iterations: int = 50):
    r"""Observed order p [-] of each term of three solutions, fine ``f1`` to coarse ``f3``
    (arrays of one shape), refinement ratios ``r21`` = h_2/h_1 > 1, ``r32`` = h_3/h_2 > 1
    (module docstring; Celik et al. 2008 eqs. 3-5 by fixed-point iteration).  NaN where the
    sequence oscillates or does not change."""
    f1, f2, f3 = (np.asarray(x, float) for x in (f1, f2, f3))
    e21, e32 = f2 - f1, f3 - f2
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ratio = e32 / e21
        s = np.sign(ratio)
        lr = np.log(np.abs(ratio))
        p = np.abs(lr) / np.log(r21)
        for _ in range(iterations):
            q = np.log((r21 ** p - s) / (r32 ** p - s))
            p = np.abs(lr + q) / np.log(r21)
    ok = np.isfinite(p) & (s > 0)
    return np.where(ok, p, np.nan)


def grid_convergence_index(levels, counts, *, formal_order: float = 2.0, dimension: int = 2,
                           asymptotic_possible: bool = True):
    r"""Per term, the grid convergence index of the finest of ``levels`` (arrays of one shape,
    coarse to fine) [their unit], the order used [-] and the safety factor used [-].

    ``counts``: the number of cells of each level; :math:`h \propto N^{-1/\mathrm{dimension}}`
    (``dimension`` = 2 for a surface of panels).  ``formal_order`` in h (2 for constant panels,
    whose error goes as 1/N).  Three levels or more: the last three and the observed order
    :math:`\hat p`; within :data:`ASYMPTOTIC_ORDER_TOLERANCE` of the formal order
    :math:`F_s = 1.25`, :math:`p = p_f`, else :math:`F_s = 3`, :math:`p = \min(\max(0.5,
    \hat p), p_f)` (Oberkampf & Roy 2010, sec. 8.6.3.2); an oscillating sequence or one with
    no observed order: the two-grid index on the larger of the last two changes
    (:math:`F_s = 3`, formal order).  Two levels: :math:`F_s = 3` (module docstring).
    ``asymptotic_possible=False``: levels known to be outside the asymptotic range (a panel
    larger than the body's thinnest member, :mod:`stripcoef.hull.panels`): no term takes
    :math:`F_s = 1.25`, whatever its observed order (1.25 only where the asymptotic range is
    shown, Oberkampf & Roy 2010, sec. 8.6.3.2)."""
    mats = [np.asarray(m, float) for m in levels]
    n = np.asarray(counts, float)
    h = n ** (-1.0 / dimension)
    fine, mid = mats[-1], mats[-2]
    r21 = h[-2] / h[-1]
    e21 = np.abs(mid - fine)
    two = SAFETY_TWO_GRIDS * e21 / (r21 ** formal_order - 1.0)
    if len(mats) < 3:
        shape = np.shape(fine)
        return two, np.full(shape, formal_order), np.full(shape, SAFETY_TWO_GRIDS)
    coarse = mats[-3]
    r32 = h[-3] / h[-2]
    p = observed_order(fine, mid, coarse, r21, r32)
    observed = np.isfinite(p)
    p_obs = np.where(observed, p, formal_order)
    asymptotic = observed & (np.abs(p_obs - formal_order)
                             <= ASYMPTOTIC_ORDER_TOLERANCE * formal_order) & asymptotic_possible
    p_used = np.where(asymptotic, formal_order,
                      np.minimum(np.maximum(p_obs, MIN_ORDER), formal_order))
    safety = np.where(asymptotic, SAFETY_THREE_GRIDS, SAFETY_TWO_GRIDS)
    three = safety * e21 / (r21 ** p_used - 1.0)
    # no observed order: the two-grid index on the larger change, the coarser scaled to the
    # fine step by the formal order (Roache 1998, sec. 5.6)
    e32 = np.abs(coarse - mid) / r32 ** formal_order
    fallback = SAFETY_TWO_GRIDS * np.maximum(e21, e32) / (r21 ** formal_order - 1.0)
    gci = np.where(observed, three, fallback)
    return (gci, np.where(observed, p_used, formal_order),
            np.where(observed, safety, SAFETY_TWO_GRIDS))


def richardson(coarse, fine, n_coarse, n_fine, order: float = 2.0, dimension: int = 2):
    r"""Richardson extrapolation of two levels [their unit] (Richardson 1911; Roache 1998 eq.
    5.4.1): :math:`f = f_1 + (f_1 - f_2)/(r^p - 1)`, :math:`r = (N_1/N_2)^{1/\mathrm{dimension}}`
    (for p = 2 on a surface: :math:`(N_1 f_1 - N_2 f_2)/(N_1 - N_2)`)."""
    r = (float(n_fine) / float(n_coarse)) ** (1.0 / dimension)
    fine, coarse = np.asarray(fine, float), np.asarray(coarse, float)
    return fine + (fine - coarse) / (r ** order - 1.0)


# ----------------------------------------------------------------- Eça & Hoekstra (2014)
#: Fewest levels of the least-squares procedure [-] (Eça & Hoekstra 2014, App. A: n_g >= 4).
EH_MIN_LEVELS = 4
#: Safety factor where the observed order lies in [EH_ORDER_LOW, EH_ORDER_HIGH) and the fit's
#: standard deviation is below the data range [-] (Eça & Hoekstra 2014, sec. 3): Roache's
#: three-grid factor, :data:`SAFETY_THREE_GRIDS`, as they adopt it.
EH_SAFETY_GOOD = SAFETY_THREE_GRIDS
#: Safety factor otherwise [-] (Eça & Hoekstra 2014, sec. 3): Roache's factor of an order not
#: established, :data:`SAFETY_TWO_GRIDS`.
EH_SAFETY_POOR = SAFETY_TWO_GRIDS
#: Observed orders in [EH_ORDER_LOW, EH_ORDER_FIXED] take the fit of free order; below, the
#: fixed orders 1, 2 and 1 & 2; above, 1 and 2 [-] (Eça & Hoekstra 2014, sec. 3, App. A).
EH_ORDER_LOW = 0.5
EH_ORDER_FIXED = 2.0
#: Upper end (exclusive) of the observed orders that take :data:`EH_SAFETY_GOOD` [-]
#: (Eça & Hoekstra 2014, sec. 3).
EH_ORDER_HIGH = 2.1
#: Range searched for the free order [-]: the least-squares minimum over |p| <= this (a fit of
#: p <= 0 is discarded, Eça & Hoekstra 2014, sec. 2.2).  A bracket, not a fitted constant.
EH_ORDER_SEARCH = 8.0


@dataclass(frozen=True)
class GridUncertainty:
    """One quantity's least-squares grid uncertainty (:func:`eca_hoekstra`)."""

    uncertainty: float      #: U of the finest level [unit of phi] (eqs. 20-21)
    extrapolated: float     #: phi_0 of the chosen fit [unit of phi]
    order: float            #: observed order p of the free-order fit [-]; NaN: anomalous
    fit: str                #: the chosen error model: "p", "1", "2", "12" or an extra order
    weighted: bool          #: the chosen fit is the weighted one
    safety: float           #: F_s [-]
    sigma: float            #: the chosen fit's standard deviation [unit of phi]
    data_range: float       #: Delta_phi [unit of phi] (eq. 19)
    error: float            #: epsilon_phi = |fit(h_1) - phi_0| [unit of phi]
    residual: float         #: |phi_1 - fit(h_1)| [unit of phi]

    @property
    def fit_order(self) -> float:
        """The order in h the chosen fit converges at [-]: p of the free-order fit, the fixed
        order of a one-term fit, 1 for delta_12 (its leading term), NaN for constant data."""
        if self.fit == "p":
            return self.order
        if self.fit == "12":
            return 1.0
        return float(self.fit) if self.fit != "constant" else float("nan")


def _weights(h, weighted: bool):
    """Eça & Hoekstra 2014 eq. 16: w_i = (1/h_i)/sum(1/h_j); without weights 1/n_g."""
    w = 1.0 / h if weighted else np.ones_like(h)
    return w / w.sum()


def _free_order_scan(h, phi, w, orders):
    """Weighted least squares of phi = phi_0 + alpha h^p for each p of ``orders`` (closed
    form, linear in phi_0 and alpha): (sum of w * residual^2, phi_0, alpha) per p."""
    x = h[None, :] ** orders[:, None]
    xm = x @ w
    fm = phi @ w
    dx = x - xm[:, None]
    with np.errstate(divide="ignore", invalid="ignore"):
        alpha = (dx * (phi - fm)) @ w / ((dx * dx) @ w)
    phi0 = fm - alpha * xm
    res = phi[None, :] - phi0[:, None] - alpha[:, None] * x
    return (res * res) @ w, phi0, alpha


def _free_order_fit(h, phi, w):
    """The least-squares fit of free order (Eça & Hoekstra 2014, sec. 2.2, eq. 1): the
    minimum of the residual over p by a scan of [-EH_ORDER_SEARCH, EH_ORDER_SEARCH] polished
    by a bounded scalar search; returns (p, phi_0, alpha, residuals)."""
    from scipy.optimize import minimize_scalar

    grid = np.concatenate([-np.geomspace(EH_ORDER_SEARCH, 1e-3, 400),
                           np.geomspace(1e-3, EH_ORDER_SEARCH, 400)])
    s, _, _ = _free_order_scan(h, phi, w, grid)
    s = np.where(np.isfinite(s), s, np.inf)
    k = int(np.argmin(s))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    if lo < 0 < hi:
        lo, hi = (grid[k - 1], grid[k]) if grid[k] < 0 else (grid[k], grid[k + 1])
    best = minimize_scalar(lambda q: float(_free_order_scan(h, phi, w, np.array([q]))[0][0]),
                           bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-10 * max(1.0, abs(grid[k]))})
    p = float(best.x) if best.fun <= s[k] else float(grid[k])
    _, phi0, alpha = _free_order_scan(h, phi, w, np.array([p]))
    return p, float(phi0[0]), float(alpha[0]), phi - phi0[0] - alpha[0] * h ** p


def _fixed_order_fit(h, phi, w, exponents):
    """Weighted linear least squares of phi = phi_0 + sum_k alpha_k h^q_k (Eça & Hoekstra
    2014, eqs. 5-7 for q = 1, 2, (1, 2)): (phi_0, coefficients, residuals)."""
    a = np.column_stack([np.ones_like(h)] + [h ** q for q in exponents])
    sw = np.sqrt(w)
    c, *_ = np.linalg.lstsq(a * sw[:, None], phi * sw, rcond=None)
    return float(c[0]), c[1:], phi - a @ c


def _sigma(res, w, n_params):
    """The fit's standard deviation (Eça & Hoekstra 2014, sec. 2.2 and App. B):
    sqrt(n_g sum w_i res_i^2 / (n_g - n_p))."""
    n = len(res)
    return float(np.sqrt(n * float(w @ (res * res)) / (n - n_params)))


def eca_hoekstra(counts, values, *, dimension: int = 2,
                 extra_orders=()) -> GridUncertainty:
    r"""The numerical uncertainty of the finest of ``values`` (one quantity on n_g >= 4
    levels, coarse to fine, of ``counts`` cells; :math:`h \propto N^{-1/\mathrm{dimension}}`)
    by the least-squares procedure of Eça & Hoekstra (2014) (module docstring: sec. 2.2 the
    fits and their standard deviations, eqs. 1, 5-7, 16; sec. 3 and App. A the choice of fit
    and safety factor; eqs. 18-21 the uncertainty).  ``extra_orders``: fixed orders q of
    one-term fits :math:`\alpha h^q` that join the alternative fits (:math:`\delta_1,
    \delta_2[, \delta_{12}]`) where the free order is out of [0.5, 2] (not in the paper: a
    hypothesis to test, named in the result's ``fit``).  Raises ValueError below four
    levels or with counts not all distinct.

    A limit measured on exact power laws (four levels, h ratio sqrt 2): U covers the finest
    level's error for orders from about 0.35 up (1.25 times it in [0.5, 2], 1.1 at 0.35, 6
    to 36 times it at 2.5 to 4), but not below: U is 0.62 of the error at p = 0.2 and 0.94
    at 0.3, the fixed orders 1 and 2 extrapolating too little (tests/
    test_convergence_eca_hoekstra.py)."""
    n = np.asarray(counts, float)
    phi = np.asarray(values, float)
    if len(n) < EH_MIN_LEVELS or len(phi) != len(n):
        raise ValueError(f"Eça & Hoekstra need at least {EH_MIN_LEVELS} levels with one value "
                         f"each; got {len(n)} counts and {len(phi)} values")
    order = np.argsort(-n)                      # finest first, as the paper numbers them
    n, phi = n[order], phi[order]
    if np.any(np.diff(n) == 0):
        raise ValueError(f"levels of equal cell counts {n.tolist()}: expected distinct ones")
    h = (n[0] / n) ** (1.0 / dimension)         # h_1 = 1: the fits do not depend on the scale
    ng = len(h)
    data_range = float(phi.max() - phi.min()) / (ng - 1)
    if data_range == 0.0:
        return GridUncertainty(0.0, float(phi[0]), float("nan"), "constant", False,
                               EH_SAFETY_GOOD, 0.0, 0.0, 0.0, 0.0)
    fits = []                                   # (sigma, name, weighted, phi0, fitted h_1)
    best_p = None
    for weighted in (False, True):
        w = _weights(h, weighted)
        p, phi0, alpha, res = _free_order_fit(h, phi, w)
        if p > 0:
            sig = _sigma(res, w, 3)
            if best_p is None or sig < best_p[0]:
                best_p = (sig, "p", weighted, phi0, phi0 + alpha, p)
    p_obs = best_p[5] if best_p is not None else float("nan")
    if best_p is not None and EH_ORDER_LOW <= p_obs <= EH_ORDER_FIXED:
        fits = [best_p[:5]]
    else:
        models = [("1", (1.0,)), ("2", (2.0,))]
        if not (best_p is not None and p_obs > EH_ORDER_FIXED):
            models.append(("12", (1.0, 2.0)))
        models += [(f"{float(q):g}", (float(q),)) for q in extra_orders]
        for name, exps in models:
            for weighted in (False, True):
                w = _weights(h, weighted)
                phi0, _, res = _fixed_order_fit(h, phi, w, exps)
                fits.append((_sigma(res, w, 1 + len(exps)), name, weighted, phi0,
                             phi[0] - res[0]))
    sigma, name, weighted, phi0, fit1 = min(fits, key=lambda f: f[0])
    good = (best_p is not None and EH_ORDER_LOW <= p_obs < EH_ORDER_HIGH
            and sigma < data_range)
    safety = EH_SAFETY_GOOD if good else EH_SAFETY_POOR
    error, residual = abs(fit1 - phi0), abs(phi[0] - fit1)
    u = _eh_uncertainty(safety, error, sigma, residual, data_range)
    return GridUncertainty(float(u), float(phi0), float(p_obs), name, bool(weighted),
                           float(safety), float(sigma), data_range, float(error),
                           float(residual))


def eca_hoekstra_terms(counts, levels, *, dimension: int = 2, extra_orders=()):
    """:func:`eca_hoekstra` on every term of ``levels`` (arrays of one shape, coarse to
    fine): (extrapolated value [their unit], uncertainty of the finest level [their unit],
    observed order [-], safety factor [-]) as arrays of that shape."""
    mats = np.stack([np.asarray(m, float) for m in levels])
    shape = mats.shape[1:]
    flat = mats.reshape(len(mats), -1)
    out = np.empty((4, flat.shape[1]))
    for k in range(flat.shape[1]):
        r = eca_hoekstra(counts, flat[:, k], dimension=dimension, extra_orders=extra_orders)
        out[:, k] = r.extrapolated, r.uncertainty, r.order, r.safety
    return tuple(x.reshape(shape) for x in out)



def _eh_uncertainty(safety: float, error: float, sigma: float, residual: float,
                    data_range: float) -> float:
    r"""Eça & Hoekstra's uncertainty of the finest level [the unit of :math:`\phi`]
    (2014, J. Comput. Phys. 262, 104-130, eqs. 20-21): with a fit standard deviation
    :math:`\sigma` below the data range :math:`\Delta_\phi`,
    :math:`F_s\,\varepsilon + \sigma + |\phi_1 - \phi_{fit}|`; else
    :math:`3\,\sigma/\Delta_\phi\,(\varepsilon + \sigma + |\phi_1 - \phi_{fit}|)`, where
    :math:`\varepsilon` (``error``) is the fit's distance from the finest to the limit and
    ``residual`` the finest level's distance from the fit."""
    if sigma < data_range:
        return safety * error + sigma + residual
    return EH_SAFETY_POOR * sigma / data_range * (error + sigma + residual)

def least_squares_band(counts, levels):
    r"""Per term of ``levels`` (n_g >= 4 matrices of one square shape, coarse to fine, of
    ``counts`` cells), the uncertainty U of the finest level by Eça & Hoekstra's least squares
    over all the levels [their unit] (:func:`eca_hoekstra`, eqs. 18-21), the observed order
    [-] (the free-order fit's; where it is anomalous, the order of the chosen fixed-order fit)
    and the safety factor [-]: the band of :func:`grid_convergence_index`, taken from every
    level instead of the three finest.  The upper triangle is computed and mirrored (the
    panel method's estimate is symmetrised, :func:`stripcoef.hull.panels.estimated_error`).

    Measured on the CAD-style shapes of seed 1375923287 (the panel method's own levels, 400 to
    3,200 panels; benchmarks/data/panel_extra_levels.md): with the Richardson value and the
    step to it added (:func:`stripcoef.hull.panels.estimated_error`), the diagonal terms'
    estimate covers 219 of 228 against the stored references (223 with the three-grid index)
    and its median ratio to the actual error falls from 15.2 to 11.5."""
    mats = np.stack([np.asarray(m, float) for m in levels])
    k = mats.shape[1]
    band, order, safety = (np.zeros((k, k)) for _ in range(3))
    for i in range(k):
        for j in range(i, k):
            r = eca_hoekstra(counts, mats[:, i, j])
            p = r.order if np.isfinite(r.order) else r.fit_order
            band[i, j] = band[j, i] = r.uncertainty
            order[i, j] = order[j, i] = p if np.isfinite(p) else 2.0
            safety[i, j] = safety[j, i] = r.safety
    return band, order, safety
