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
"""

from __future__ import annotations

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
