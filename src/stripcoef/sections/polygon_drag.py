r"""2D cross-flow drag of an arbitrary (multi-part) section, from its shape.

The rule (documented in docs/meshes.md and docs/theory.md):

1. The section is split into its solid parts (each outer ring; holes do not
   change the outline that the cross-flow sees).
2. For a flow along y (sway) each part has a depth ``d`` along the flow and a
   height ``h`` across it (its bounding box); along z (heave) the roles swap.
3. Each part's coefficient on its own height ``h``:

   - rounded outline (no vertex turning by more than 25 deg): elliptic cylinder
     of the same d/h, :math:`C_D = C_{D,ell}(d/h)\,C_{D,circle}(Re_h)/1.2`
     (White, *Fluid Mechanics*, table 7.2; DNV-RP-C205 sec. 6.7 for the circle's
     Reynolds dependence);
   - sharp outline: rectangular cylinder of the same d/h,
     :math:`C_D = C_{D,rect}(d/h)` (White table 7.2 after Delany & Sorensen 1953;
     DNV-RP-C205 App. E; Hoerner 1965 ch. 3), Reynolds-independent.

4. Parts behind one another along the flow (tandem): the part of a
   downstream part's height that lies in the shadow of an upstream part counts
   with the factor :data:`TANDEM_SHIELDING` = 0.5 (Hoerner 1965, ch. 4, tandem
   cylinders: the rear body's drag is 0-0.8 of its free value at spacings of 1-5
   diameters; 0.5 is a middle value -- an assumption), averaged over the two
   flow senses (+y and -y).
5. The section's force per unit length is :math:`f = \tfrac12\rho U|U| \sum_p
   C_{D,p}\, w_p`, with :math:`w_p` the exposed heights; it is returned as one
   coefficient on the section's full height across the flow, ``2 h`` for flow
   along y and ``2 b`` along z (the reference heights of
   :data:`stripcoef.sections.SHAPES`):

   .. math:: C_{D,section} = \frac{\sum_p C_{D,p} w_p}{H_{ref}}

Gaps between parts are not counted in the force (only the parts' heights are),
so an open frame gets a smaller coefficient on its overall height than a solid
block, as it should.
"""

from __future__ import annotations

import numpy as np

from stripcoef.sections import drag
from stripcoef.sections.panel import _ring_set, orient_contours, part_rings

#: Weight of the shadowed height of a part behind another part along the flow.
TANDEM_SHIELDING = 0.5


def _interval_overlap(lo, hi, others):
    """Length of [lo, hi] covered by the union of intervals ``others`` (list of (a, b))."""
    if not others:
        return 0.0
    segs = sorted((max(a, lo), min(b, hi)) for a, b in others if b > lo and a < hi)
    covered, cur_a, cur_b = 0.0, None, None
    for a, b in segs:
        if cur_b is None or a > cur_b:
            if cur_b is not None:
                covered += cur_b - cur_a
            cur_a, cur_b = a, b
        else:
            cur_b = max(cur_b, b)
    if cur_b is not None:
        covered += cur_b - cur_a
    return covered


def _exposed_heights(along_lo, along_hi, across_lo, across_hi):
    """Exposed height of each part, shadowing averaged over both flow senses [m]."""
    n = along_lo.size
    h = across_hi - across_lo
    if n < 2:
        return h                                # one part: nothing shadows it
    centre = 0.5 * (along_lo + along_hi)
    shadow = np.zeros(n)
    for sense in (1.0, -1.0):
        order = np.argsort(sense * centre)
        seen: list[tuple[float, float]] = []
        for i in order:
            shadow[i] += 0.5 * _interval_overlap(across_lo[i], across_hi[i], seen)
            seen.append((across_lo[i], across_hi[i]))
    return h - (1.0 - TANDEM_SHIELDING) * shadow


def _cd_terms(rounded, ratio, h, w, height, re):
    """sum_p C_D,p w_p per section (vectorised over all parts of all sections)."""
    re_p = np.maximum(re * h / np.maximum(height, 1e-300), 1.0)
    if np.all(rounded):          # no sharp part: skip the rectangle curve (it never warns)
        cd_p = drag.ellipse_cd(ratio, re_p)
    else:
        cd_p = np.where(rounded, drag.ellipse_cd(ratio, re_p), drag.rectangle_cd(ratio))
    return cd_p * w


def section_cross_flow_drag(contours, *, reynolds_y=1e5, reynolds_z=1e5) -> dict:
    r"""Cross-flow drag of one section for flow along y and along z.

    .. math:: C_{D,k} = \frac{1}{H_k}\sum_p C_{D,p}(d_p/h_p, Re_p)\, w_p

    Parameters
    ----------
    contours : list of (n, 2) arrays
        Rings of (y, z) points [m] (any orientation; holes found by nesting).
    reynolds_y, reynolds_z : float
        Reynolds numbers on the section's full height across the flow [-]
        (each part uses ``Re * h_p / H``).

    Returns
    -------
    dict
        ``cd_y``, ``cd_z`` [-] on the reference heights ``height_y`` (extent along z,
        for flow along y) and ``height_z`` (extent along y) [m]; ``parts`` (number
        of solid parts); ``rounded`` (list of bool per part).

    References
    ----------
    White, *Fluid Mechanics*, table 7.2; DNV-RP-C205 App. E and sec. 6.7;
    Hoerner (1965) *Fluid-Dynamic Drag*, ch. 3 and 4.
    """
    c = _ring_set_geometry(_ring_set([contours], "contours", single=True), [contours])
    out = {"parts": int(c["owner"].size), "rounded": [bool(v) for v in c["rounded"]]}
    for key, re in (("y", reynolds_y), ("z", reynolds_z)):
        ratio, h, w, height = c[key]
        terms = _cd_terms(c["rounded"], ratio, h, w, height[0], float(re))
        out[f"cd_{key}"] = float(terms.sum() / max(height[0], 1e-300))
        out[f"height_{key}"] = float(height[0])
    return out


def _ring_set_geometry(rs, sections):
    """Cross-flow geometry of every section of the ring set ``rs`` of ``sections`` (the
    contours it was built from: an empty one raises its error), all parts at once.

    Per solid part (outer ring; holes do not change the outline the flow sees, rule 1 of
    the module): ``owner`` (its section), ``rounded`` (no sharp corner), and per flow
    direction ``"y"``/``"z"`` the tuple (d/h, h, exposed height w, section height H), with
    h, w [m] per part and H [m] per section (rules 2-4 of the module).
    """
    for s in np.nonzero(np.diff(rs.rings_of) == 0)[0]:
        orient_contours(sections[s])             # an empty section: its error
    outer = rs.area > 0
    y, z = rs.pts[outer, :, 0], rs.pts[outer, :, 1]          # padding repeats a vertex
    g = np.column_stack([y.min(axis=1), y.max(axis=1), z.min(axis=1), z.max(axis=1)])
    owner = rs.section[outer]
    first = np.searchsorted(owner, np.arange(rs.nsec + 1))     # each section's first part
    several = np.nonzero(np.diff(first) > 1)[0]
    data = {"owner": owner, "rounded": ~rs.corner[outer].any(axis=1)}
    for key, along, across in (("y", 0, 2), ("z", 2, 0)):
        # the tandem shadowing only where a section has several parts
        a_lo, a_hi, c_lo, c_hi = g[:, along], g[:, along + 1], g[:, across], g[:, across + 1]
        h = c_hi - c_lo
        ratio = (a_hi - a_lo) / np.maximum(h, 1e-300)
        w = h.copy()
        for s in several:
            sl = slice(first[s], first[s + 1])
            w[sl] = _exposed_heights(a_lo[sl], a_hi[sl], c_lo[sl], c_hi[sl])
        height = np.maximum.reduceat(c_hi, first[:-1]) - np.minimum.reduceat(c_lo, first[:-1])
        data[key] = (ratio, h, w, height)
    return data


def _part_cache(part):
    """:func:`_ring_set_geometry` of ``part``'s sections, computed once per part (from the
    ring set :func:`stripcoef.sections.panel.part_rings`, shared with the panel method)."""
    cache = getattr(part, "_polygon_drag_cache", None)
    if cache is not None and cache[0] is part.contours:
        return cache[1]
    data = _ring_set_geometry(part_rings(part), part.contours)
    part._polygon_drag_cache = (part.contours, data)
    return data


def cross_flow_cd(part, re_y, re_z):
    r"""Registry entry for ``polygon`` parts: (cd_y, cd_z) per strip of ``part``.

    .. math:: C_{D,y} = \frac{\sum_p C_{D,p} w_p}{2h}, \qquad
              C_{D,z} = \frac{\sum_p C_{D,p} w_p}{2b}

    Coefficients on the reference heights ``2 * part.half_height`` (flow along y)
    and ``2 * part.half_breadth`` (flow along z), by the rule of
    :func:`section_cross_flow_drag` applied to each strip's contours (geometry
    cached on the part; vectorised over strips).

    Parameters
    ----------
    part : Part
        A ``polygon`` part with ``contours``.
    re_y, re_z : float or (k,) arrays
        Reynolds numbers on ``2 h`` and ``2 b`` [-]

    Returns
    -------
    (cd_y, cd_z) : (k,) arrays [-]

    References
    ----------
    See :func:`section_cross_flow_drag`.
    """
    k = part.index.size
    c = _part_cache(part)
    own = c["owner"]
    out = []
    for key, re, ref in (("y", re_y, 2 * part.half_height), ("z", re_z, 2 * part.half_breadth)):
        ratio, h, w, height = c[key]
        re = np.broadcast_to(np.asarray(re, dtype=float), (k,))
        terms = _cd_terms(c["rounded"], ratio, h, w, height[own], re[own])
        out.append(np.bincount(own, weights=terms, minlength=k) / np.maximum(ref, 1e-300))
    return out[0], out[1]
