"""The 3D panel method's estimated error of its extrapolated added mass, and the rule that
flags a term as not converged (issue 32: "Convergence you can see").

:func:`extrapolation_error` is the estimate of three or more levels (the extrapolation's step
plus its last change), :func:`richardson_error` that of two (the two-grid index about the finer
level plus the step), both through :func:`estimated_error`'s symmetrised band;
:func:`relative_error` scales a term's estimate to the diagonal scale of issue 32's acceptance
and :data:`ERROR_TOLERANCE` is the bound above which :mod:`stripcoef.hull.panels` reports the
matrix as not converged.

With four levels or more the error *shown* and the estimate *warned on* are two numbers, as
Eça & Hoekstra (2014) and the ASME V&V 20 standard keep the error estimate and the
uncertainty apart: the step plus the last change (the extrapolated terms' measured change,
issue 32's "refine until the extrapolated terms change by less than a tolerance") decides
the refinement and the warning, and the band shown is Eça & Hoekstra's least-squares
uncertainty of the levels moved to the value (:func:`least_squares_error`), meant to cover
the error at about 95 %.  Measured on the four-level ladder of the base install
(``python -m benchmarks.ladder_estimate_rules``, benchmarks/data/ladder_estimate_rules.md):
the step plus the change covers 86.2 % and 81.6 % of the terms of two CAD seeds, the
least-squares band 95.4 % and 91.2 %, the warnings unchanged (9 of 38 and 7 of 13 shapes,
the one shape of the ladder off by more than 5 % warned); the band is a median 9 times the
actual error, the step plus the change 3.3 times.  Split from :mod:`stripcoef.hull.panels` (which re-exports every
name) to keep that module under the house limit of 1000 lines.
"""

from __future__ import annotations

import numpy as np


def estimated_error(fine, extrapolated, gci) -> np.ndarray:
    r"""Estimated error of each term of the extrapolated added mass [kg, kg m, kg m^2].

    .. math:: E_{ij} = \max\big(\mathrm{GCI}_{ij} + |A_{ij} - A^{(1)}_{ij}|,\
              |A^{(1)}_{ij} - A^{(1)}_{ji}|\big)

    symmetrised: the grid convergence index of the finest level :math:`A^{(1)}`
    (:func:`stripcoef.hull.convergence.grid_convergence_index`, Roache 1998 ch. 5: a band about
    :math:`A^{(1)}`) moved to the extrapolated value by the step between them (triangle
    inequality), and no smaller than the finest solve's asymmetry (the exact matrix is
    symmetric, Newman 1977 eq. 4.150).  ``fine`` is not symmetrised."""
    fine = np.asarray(fine, float)
    band = np.asarray(gci, float) + np.abs(np.asarray(extrapolated, float) - fine)
    band = np.maximum(band, band.T)
    return np.maximum(band, np.abs(fine - fine.T))


def extrapolation_error(levels, counts, order: float) -> np.ndarray:
    r"""Estimated error [kg, kg m, kg m^2] of the Richardson extrapolation of the two finest
    of three or more ``levels`` (6x6 matrices, coarse to fine, not symmetrised; ``counts``
    panels; the extrapolation's ``order`` in the panel size, :func:`stripcoef.hull.panels.edge_order`):

    .. math:: E_{ij} = \max\big(|A_{ij} - A^{(1)}_{ij}| + |A_{ij} - A'_{ij}|,\
              |A^{(1)}_{ij} - A^{(1)}_{ji}|\big),

    :math:`A` the extrapolation of the finest two levels, :math:`A'` that of the two before
    them at the same order (Roache 1998 eq. 5.4.1), :math:`A^{(1)}` the finest level;
    symmetrised.  Two parts, each measured, no safety factor fitted or borrowed:

    - the **step** :math:`|A - A^{(1)}|`, the extrapolation's correction: where the error's
      true order is at least the formal one (the formal order is the largest the data may
      show, Oberkampf & Roy 2010 sec. 8.6.3.2), the exact value lies between
      :math:`A^{(1)}` and :math:`A`, so the step bounds the error of A;
    - the **change** :math:`|A - A'|`, how far the extrapolated value itself moved when the
      finest level was added: the part of the level-to-level differences that no power law
      in h explains (independent remeshes of one surface are not nested; their panelling
      noise enters the extrapolation amplified by :math:`1/(r^p - 1)`).

    The grid convergence index about the finest level plus the step (:func:`estimated_error`)
    bounds the same error by the triangle inequality, but about four times the step at
    :math:`F_s = 3`, and sixteen times the last change where the observed order falls to 0.5:
    on the CAD shapes of seed 1375923287 a median 6 times the actual error, above the 5 %
    tolerance on 37 of 38 shapes, 30 of them within 5 % on every term
    (benchmarks/data/panel_estimate_rule.md)."""
    from stripcoef.hull.convergence import richardson

    mats = [np.asarray(m, float) for m in levels]
    if len(mats) < 3:
        raise ValueError(f"the extrapolation's change needs three levels or more; got {len(mats)}")
    a = richardson(mats[-2], mats[-1], counts[-2], counts[-1], order=order)
    before = richardson(mats[-3], mats[-2], counts[-3], counts[-2], order=order)
    a, before = 0.5 * (a + a.T), 0.5 * (before + before.T)
    fine = mats[-1]
    step = np.abs(a - 0.5 * (fine + fine.T))
    band = step + np.abs(a - before)
    band = np.maximum(band, band.T)
    return np.maximum(band, np.abs(fine - fine.T))


def ladder_extrapolation(levels, counts, order: float) -> tuple:
    r"""(extrapolated M_A, its estimated error) [kg, kg m, kg m^2] of the input family's four
    levels :math:`L_1 < L_2 < L_3 < L_4` (6x6 matrices, not symmetrised; ``counts`` panels),
    two nested pairs :math:`(L_1, L_3)` and :math:`(L_2, L_4)`, each one polyhedron with the
    panel size halved (:func:`stripcoef.hull.input_ladder.ladder_levels`):

    .. math:: A = R(L_2, L_4),\quad A' = R(L_1, L_3),\quad
              E_{ij} = \max\big(|A_{ij} - L_{4,ij}| + |A_{ij} - A'_{ij}|,\
              |L_{4,ij} - L_{4,ji}|\big)

    R the Richardson extrapolation at ``order`` (Roache 1998 eq. 5.4.1), A and A' and the
    error symmetrised: the rule of :func:`extrapolation_error` (the step plus the last
    change, no safety factor), its two extrapolations each of one pair of similar meshes."""
    from stripcoef.hull.convergence import richardson

    m = [np.asarray(x, float) for x in levels]
    if len(m) != 4:
        raise ValueError(f"the ladder has four levels; got {len(m)}")
    a = richardson(m[1], m[3], counts[1], counts[3], order=order)
    before = richardson(m[0], m[2], counts[0], counts[2], order=order)
    a, before = 0.5 * (a + a.T), 0.5 * (before + before.T)
    fine = m[3]
    band = np.abs(a - 0.5 * (fine + fine.T)) + np.abs(a - before)
    band = np.maximum(band, band.T)
    return a, np.maximum(band, np.abs(fine - fine.T))


def least_squares_error(levels, counts, extrapolated) -> tuple:
    r"""(the band shown [kg, kg m, kg m^2], its safety factor per term [-]) of the value
    ``extrapolated`` from four or more ``levels`` (6x6 matrices, coarse to fine, not
    symmetrised; ``counts`` panels):

    .. math:: E_{ij} = \max\big(U_{ij} + |A_{ij} - A^{(1)}_{ij}|,\ |A^{(1)}_{ij} - A^{(1)}_{ji}|\big)

    symmetrised, :math:`U` the least-squares uncertainty of the finest level
    :math:`A^{(1)}` over every level (Eça & Hoekstra 2014, J. Comput. Phys. 262, 104-130,
    eqs. 18-21, their safety factors 1.25 and 3:
    :func:`stripcoef.hull.convergence.least_squares_band`), moved to the value by the step
    (:func:`estimated_error`).  The warning does not read it (module docstring)."""
    from stripcoef.hull.convergence import EH_MIN_LEVELS, least_squares_band

    mats = [np.asarray(m, float) for m in levels]
    if len(mats) < EH_MIN_LEVELS:
        raise ValueError(f"the least-squares band needs {EH_MIN_LEVELS} levels or more; "
                         f"got {len(mats)}")
    u, _, safety = least_squares_band(counts, [0.5 * (m + m.T) for m in mats])
    a = np.asarray(extrapolated, float)
    return estimated_error(mats[-1], 0.5 * (a + a.T), u), safety


def richardson_error(coarse, fine, extrapolated) -> np.ndarray:
    r"""Estimated error [kg, kg m, kg m^2] of a two-level extrapolation: the two-grid index
    (:math:`F_s = 3`, Roache 1994) about the finer level plus the step to the extrapolation
    (:func:`estimated_error`).  ``coarse``, ``fine``: the two levels' matrices (not
    symmetrised), ``extrapolated``: their extrapolation."""
    fine = np.asarray(fine, float)
    step = np.abs(np.asarray(extrapolated, float) - fine)
    from stripcoef.hull.convergence import SAFETY_TWO_GRIDS

    return estimated_error(fine, extrapolated, SAFETY_TWO_GRIDS * step)


#: Largest estimated error of a term (:func:`richardson_error`) relative to the diagonal scale
#: :math:`\sqrt{A_{ii} A_{jj}}` before the result is flagged as not converged [-] (the 5 % of
#: issue 32's acceptance: every term within 5 % of the converged BEM).
ERROR_TOLERANCE = 0.05


#: A diagonal term that its estimate cannot tell from zero is scaled by at least this fraction
#: of the largest of its block (translations or rotations) [-]: the roll added mass of a body
#: of revolution is zero, and an error relative to a vanishing term says nothing (the same 1 %
#: below which the benchmarks call a coupling insignificant).
NEGLIGIBLE = 0.01


def relative_error(matrix, error, length: float | None = None) -> np.ndarray:
    r"""Each term's estimated error over the diagonal scale of issue 32's acceptance,
    :math:`E_{ij} / \sqrt{d_i d_j}` [-]: a diagonal term relative to itself, a coupling to
    :math:`\sqrt{A_{ii} A_{jj}}`, :math:`d_i = |A_{ii}|`.

    A diagonal term that its estimate cannot tell from zero (:math:`|A_{ii}| \le E_{ii}`) is
    scaled by at least :data:`NEGLIGIBLE` of the largest of its block (a body of revolution's
    roll).  Given the body's ``length`` L [m] (its largest extent), where none of the three
    rotations stands out of its estimate they are scaled by at least the moment scale
    :math:`\max_{k \le 3} |A_{kk}|\,(L/2)^2` [kg m^2] (the largest translational added
    mass at the body's half length): a sphere's rotations are exactly zero, all three (Lamb
    1932 sec. 92), its panel solution's are round-off within their estimate, and the block's
    largest is such round-off too.  A term larger than its estimate is judged on its own
    value however small (a thin plate's in-plane surge, sway and yaw, 0.3-2 % of the largest
    of their blocks: the acceptance counts them, and their errors reach 5-12 %), and a coarse
    frame's rotation whose estimate exceeds it is flagged by its block's scale, not excused."""
    d = np.abs(np.diag(np.asarray(matrix, float))).copy()
    e = np.abs(np.diag(np.asarray(error, float)))
    zero = d <= e
    for block in (slice(0, 3), slice(3, 6)):
        d[block] = np.where(zero[block], np.maximum(d[block], NEGLIGIBLE * d[block].max()),
                            d[block])
    if length is not None and zero[3:].all():
        d[3:] = np.maximum(d[3:], d[:3].max() * (0.5 * float(length)) ** 2)
    d = np.sqrt(d)
    scale = np.outer(d, d)
    return np.asarray(error, float) / np.where(scale > 0, scale, np.inf)


def finest_pair_under_refined(counts) -> bool:
    r"""Whether the value of four or more levels (``counts`` panels, coarse to fine) is
    extrapolated from the two nested pairs :math:`(L_{n-2}, L_n)` and
    :math:`(L_{n-3}, L_{n-1})` (:func:`ladder_extrapolation` on the last four levels) instead of
    the two finest: where the finest pair refines by less than Celik et al.'s
    :math:`r = h_{coarse}/h_{fine} \ge 1.3` (2008, J. Fluids Eng. 130, 078001, "Procedure for
    estimation and reporting of uncertainty due to discretization in CFD applications", sec.
    2, step 2: :data:`stripcoef.hull.remesh.MIN_FACE_RATIO` in panels, :math:`h \sim N^{-1/2}`)
    and each nested pair does.

    Why: the Richardson step multiplies the finest pair's change by :math:`1/(r^p - 1)`, and
    two independent remeshes of one surface differ by a panelling noise that no power law in
    h describes (:func:`extrapolation_error`); a level added at the refinement's fallback
    ratio (:data:`stripcoef.hull.remesh.LEAST_FACE_RATIO`, 1.25 in panels, where creases hold
    the count) has :math:`r = 1.12` and at the order 4/3 of a right-angled edge multiplies it
    by 5.8.  Frame 22 of seed 1795919297 (30-mm plates; no-flip levels 944/1682/3010/3830,
    the last pair r = 1.13): its surge levels lie 1.7 to 4.5 % below the 3,000-face reference
    and the two finest were extrapolated to -10.0 %; the nested pairs' r are 1.51 and 1.79
    (benchmarks/data/frame32d_trace.md).

    An option (:func:`stripcoef.hull.panels.panel_added_mass`'s ``value_pair="nested"``), not
    the default: on the frames it helped (fresh seed 1795939009's frames 8, 12 and 13: worst
    diagonal -10.0, -4.2, -6.0 % -> -3.5, -1.5, -3.0 %), but on the public meshes it moved the
    WHOI hybrid glider's sway -0.5 -> -6.1 % and pitch -1.9 -> -7.5 % (levels
    1206/2050/3218/4334; both covered by their bands and warned), two of 108 diagonal terms
    beyond 5 % that were within it.  Since the refinement's added level refines the finest by
    r >= 1.3 wherever that fits (:func:`stripcoef.hull.remesh.added_level`), the finest pair is
    under-refined only where it does not (benchmarks/data/frame32g_trace.md)."""
    from stripcoef.hull.remesh import MIN_FACE_RATIO

    n = [float(c) for c in counts]
    return (len(n) >= 4 and n[-1] < MIN_FACE_RATIO * n[-2]
            and n[-1] >= MIN_FACE_RATIO * n[-3] and n[-2] >= MIN_FACE_RATIO * n[-4])
