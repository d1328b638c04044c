r"""The input family's four levels: two nested pairs of the input's own faces (no remesher).

Without the remesher a small input (at most N/4 faces for N panels asked; boxes and plates
excepted, :mod:`stripcoef.hull.graded_panels`) was solved on two levels, the input bisected to
:math:`N_1 = \max(N/4, 2F)` panels and that split in four (:func:`stripcoef.hull.panels.
panel_levels`).  Two levels have no change to measure: their estimate is Roache's two-grid
index (:math:`F_s = 3`) plus the step, which warned on 28 of the 30 CAD shapes of seed
1375923287 that are neither boxes nor plates (8 of them off by more than 5 %), and cannot
see a term whose two values agree by chance.

:func:`ladder_levels` adds a second pair of the same kind: the input bisected to
:math:`2N_1` (Rivara 1984's longest-edge bisection, :func:`stripcoef.hull.bisection.refine`)
and that split in four, :math:`N_1 < 2N_1 < 4N_1 < 8N_1` (the remesher's N/4 ... 2N).  Each
pair is one polyhedron with h halved (its two meshes similar, so one error constant), the two
pairs one refinement apart; the value is the finer pair's Richardson extrapolation and its
estimate, which the warning reads, the step to the finest level plus the change since the
coarser pair's (:func:`stripcoef.hull.panel_error.ladder_extrapolation`).  Measured on those
30 shapes against the most resolved references (``python -m benchmarks.base_levels --whole``,
docs/performance.md): 179 of 180 diagonal terms within 5 % (168 with two levels), 9 of 30
shapes warned (28), 207 of 235 terms covered (226) by that estimate.  The band shown is Eça &
Hoekstra's least-squares uncertainty of the four levels moved to the value
(:func:`stripcoef.hull.panel_error.least_squares_error`): 233 of those 235 terms, and 95.1 %
and 97.3 % of the ladder's terms on two more seeds, the warnings unchanged
(``python -m benchmarks.ladder_estimate_rules``, benchmarks/data/ladder_estimate_rules.md).
"""

from __future__ import annotations

import numpy as np

from stripcoef.hull.bisection import refine, split_in_four
from stripcoef.hull.remesh import LEAST_FACE_RATIO


def ladder_levels(vertices, faces, panels: int, limit: int):
    """The four levels (coarse to fine, (vertices, faces) each) of a closed mesh of at most
    ``panels`` / 4 faces: the input bisected to N_1 = max(N/4, 2F) and 2 N_1 panels, each
    split in four at the edge midpoints (:func:`stripcoef.hull.bisection.split_in_four`), or
    ``None`` when the input is larger or the finest level would exceed ``limit`` panels or the
    bisection cannot reach a second pair (the caller's two levels then)."""
    v, f = np.asarray(vertices, float), np.asarray(faces, np.int64)
    if 4 * len(f) > panels:
        return None
    n1 = max(panels // 4, 2 * len(f))
    b1, b2 = refine(v, f, n1), refine(v, f, 2 * n1)
    # (the bisection to a count moves in steps: a uniform input may not reach 2 N_1 and
    # then returns N_1 again; the second pair is kept where it has at least
    # LEAST_FACE_RATIO times the first's panels, the remeshed families' least step)
    if 4 * len(b2[1]) > limit or len(b2[1]) < LEAST_FACE_RATIO * len(b1[1]):
        return None
    return [b1, b2, split_in_four(*b1), split_in_four(*b2)]
