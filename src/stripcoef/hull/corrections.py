r"""3D corrections of strip theory from an axisymmetric boundary-element solution.

Strip theory integrates 2D section added mass along the body, which ignores the
flow around the ends: it overestimates the transverse terms (sway/heave) by
5-10 % and the rotational ones (pitch/yaw) by 20-30 % on typical hulls, and
gives no axial (surge) added mass at all.

This module has the 3D potential flow solved exactly (to discretisation error)
about the *equivalent body of revolution* of the strips -- the body with the
same section area at every x, :math:`r_{eq}(x) = \sqrt{A(x)/\pi}` -- with an
axisymmetric boundary-element method, and returns

- its axial added mass :math:`m_{11}` (used directly for surge), and
- the 3D/strip ratios of its transverse and rotational added mass,

  .. math:: f_t = \frac{m_{22}^{3D}}{\int \rho\pi r_{eq}^2 dx},\qquad
            f_r = \frac{m_{66}^{3D}}{\int \rho\pi r_{eq}^2 (x - x_c)^2 dx}

  which scale the strip-theory matrix of the real sections (end correction).

For a spheroid both are Lamb's exact values; for blunt bodies (capsules,
Myring hulls with flat tails, boxes) they replace the equal-volume spheroid of
:func:`stripcoef.hull.lamb.end_correction_factors`, whose axial term is 30 % low on
a capsule.

The axisymmetric solver itself is :mod:`stripcoef.hull.axisymmetric`.

References
----------
Newman (1977) sec. 4.13-4.15 and 7.4 (slender bodies and their end effects), Lamb (1932)
sec. 373 (the exact spheroid), Hess & Smith (1967): the solver's references, in full in
:mod:`stripcoef.hull.axisymmetric` and docs/bibliography.md.
"""

from __future__ import annotations

from dataclasses import dataclass


import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.shapes import has_rings, section_half_chord
from stripcoef.model import frozen_array
from stripcoef.geometry.mesh import ring_integrals, section_geometry
from stripcoef.hull.finsheet import FinPlanform, fins_added_mass
from stripcoef.hull.memo import array_memo
from stripcoef.sections import get_shape, section_added_mass
from stripcoef.sections.added_mass import fin_edgewise
from stripcoef.hull.axisymmetric import (DEFAULT_PANELS, body_of_revolution_added_mass,
                                         mode_inertia, ring_body_added_mass)

#: Lateral-equivalent bodies closed to r = 0 at the ends (False: blunt ends keep their flat faces,
#: which rock in pitch and yaw; measured: no difference on the open-frame ROV benchmark).
CLOSED_ENDS = False
#: 2D roll added mass below this fraction of rho A^2 is round-off, not roll (a circle's panel
#: solution gives ~1e-29 of it): :func:`roll_relief` has nothing to relieve [-]
ROLL_ROUNDOFF = 1e-9
#: sway and heave sections equal to this relative tolerance share one equivalent body [-]
SAME_BODY_RTOL = 1e-10


def strip_section_added_mass(strips, rho: float) -> np.ndarray:
    r"""Per-strip 2D added mass (n, 3, 3), the sum of the parts' sections [kg/m, kg, kg m].

    .. math:: m^{2D}(x_i) = \sum_p c_{p,i}\, m_p(x_i)

    with coverage fractions :math:`c_{p,i}` [-] and ``rho`` [kg/m^3]. Translation terms only
    are used by :func:`hull_corrections` (they do not depend on the roll reference point).
    [assumption] sections add without interaction (strip theory, Newman 1977, sec. 7.4).
    """
    out = np.zeros((strips.n, 3, 3))
    for p in strips.parts:
        np.add.at(out, p.index, section_added_mass(p, rho) * _coverage(p)[:, None, None])
    return out


def _coverage(part) -> np.ndarray:
    """Fraction of each covered strip's width that the part spans (1 if not recorded)."""
    cov = getattr(part, "coverage", None)
    return np.ones(part.index.size) if cov is None else np.asarray(cov, dtype=float)


def _equivalent_radius(strips, per_strip, *, closed_ends: bool = False, steps: bool = False):
    """Profile (x, r) with pi r^2 = per_strip (an area [m^2]), ends extrapolated linearly
    (or closed to r = 0 at the body's ends); with ``steps``, a fin edge inside a strip
    (:func:`fin_edges`) replaces that strip's station by a step at the edge.

    r = sqrt(A / pi) [m] at the strip centres x [m], plus end stations at x_min, x_max with
    A_end = max(A_0 + (A_1 - A_0)/(x_1 - x_0) (x_end - x_0), 0). [assumption] linear
    end extrapolation; equal-area body of the module docstring.
    """
    x = strips.x
    if strips.n < 2:
        raise InputError("too few strips for the 3D correction", key="strips", value=strips.n,
                         expected=">= 2")

    def end(i0, i1, xe):
        slope = (per_strip[i1] - per_strip[i0]) / (x[i1] - x[i0])
        return max(per_strip[i0] + slope * (xe - x[i0]), 0.0)

    a_lo = 0.0 if closed_ends else end(0, 1, strips.x_min)
    a_hi = 0.0 if closed_ends else end(-1, -2, strips.x_max)
    xs = np.r_[strips.x_min, x, strips.x_max]
    a = np.r_[a_lo, per_strip, a_hi]
    edges = fin_edges(strips) if steps else []
    if edges:      # a fin's edge strip: the step at the edge (the neighbours' areas each side)
        xs_l, a_l, last = [], [], 0
        for i, xe, outside, inside in edges:
            j = i + 1                                   # station of strip i in xs
            xs_l.append(xs[last:j])
            a_l.append(a[last:j])
            lo, hi = (outside, inside) if outside < inside else (inside, outside)
            xs_l.append(np.array([xe, xe]))
            a_l.append(np.array([per_strip[lo], per_strip[hi]]))
            last = j + 1
        xs_l.append(xs[last:])
        a_l.append(a[last:])
        xs, a = np.concatenate(xs_l), np.concatenate(a_l)
    rs = np.sqrt(np.maximum(a, 0.0) / np.pi)
    return xs, rs


def fin_edges(strips) -> list:
    r"""The leading and trailing edges of vehicle-file fins that fall inside a strip.

    For a fin part whose first (last) strip i is covered over the fraction c < 1, its edge is at
    :math:`x_e = x_i + dx_i/2 - c\,dx_i` (:math:`x_e = x_i - dx_i/2 + c\,dx_i`) [m]: the finned
    section holds on the fin's side of x_e and the bare one on the other.  Returns sorted
    (i, x_e, outside, inside) tuples, ``outside``/``inside`` the neighbouring strip indices on
    either side; only fins of at least 3 strips (the neighbours must be a bare and a wholly
    covered strip).  Used by :func:`_equivalent_radius` to put the step of the equivalent body
    where the fins end instead of smearing it over the strip.
    """
    out = {}
    for p in strips.parts:
        if p.role != "fin" or p.index.size < 3:
            continue
        order = np.argsort(p.index)
        idx, cov = p.index[order], _coverage(p)[order]
        for i, c, outside, inside, first in ((idx[0], cov[0], idx[0] - 1, idx[1], True),
                                             (idx[-1], cov[-1], idx[-1] + 1, idx[-2], False)):
            if c >= 1.0 - 1e-9 or outside < 0 or outside >= strips.n:
                continue
            half = 0.5 * strips.dx[i]
            xe = strips.x[i] + half - c * 2 * half if first else strips.x[i] - half + c * 2 * half
            out[int(i)] = (int(i), float(xe), int(outside), int(inside))
    return [out[k] for k in sorted(out)]


def _strip_area(strips) -> np.ndarray:
    """Section area of every strip, all parts that displace water summed [m^2]."""
    area = np.zeros(strips.n)
    for p in strips.parts:
        np.add.at(area, p.index, p.area * _coverage(p))
    return area


def equivalent_profile(strips):
    r"""Equal-area body of revolution of a set of strips: :math:`r_{eq} = \sqrt{A(x)/\pi}`.

    Section areas of all parts that displace water are summed per strip; the ends
    are extrapolated linearly in area to the body's first and last x (a pointed
    end gets r = 0, a blunt one keeps its area and gets a flat cap).

    Returns
    -------
    (x, r) arrays [m]

    References
    ----------
    See module docstring (equivalent body of revolution; Newman 1977, sec. 7.4).
    """
    return _equivalent_radius(strips, _strip_area(strips))


def _fin_span_interval(part, i):
    """(lateral axis, lateral offset, low, high) of fin part ``part`` at its row ``i``: the fin's
    span runs along z (a vertical fin, lateral offset y) or y, from low to high [m]."""
    if part.half_height[i] > part.half_breadth[i]:
        return "z", part.y[i], part.z[i] - part.half_height[i], part.z[i] + part.half_height[i]
    return "y", part.z[i], part.y[i] - part.half_breadth[i], part.y[i] + part.half_breadth[i]


def _section_chord(part, i, axis, offset):
    """The intervals that section ``i`` of hull part ``part`` covers on the line at ``offset``
    across ``axis`` (the line runs along ``axis``: z for a vertical fin) [m]: an ellipse or a
    rectangle exactly, a polygon through its contours (shapely)."""
    if axis == "z":
        d, half_lat, centre, half_span = offset - part.y[i], part.half_breadth[i], part.z[i], \
            part.half_height[i]
    else:
        d, half_lat, centre, half_span = offset - part.z[i], part.half_height[i], part.y[i], \
            part.half_breadth[i]
    if abs(d) >= half_lat:
        return []
    if not has_rings(part):
        h = float(section_half_chord(part.shape, half_lat, half_span, d))
        return [(centre - h, centre + h)]
    from shapely.geometry import LineString

    geom = section_geometry(part.contours[i])
    big = 10.0 * (half_span + half_lat + abs(offset) + abs(centre) + 1.0)
    line = (LineString([(offset, -big), (offset, big)]) if axis == "z"
            else LineString([(-big, offset), (big, offset)]))
    cut = geom.intersection(line)
    pieces = getattr(cut, "geoms", [cut])
    out = []
    for g in pieces:
        if g.is_empty or g.length <= 0:
            continue
        coords = np.asarray(g.coords)[:, 1 if axis == "z" else 0]
        out.append((float(coords.min()), float(coords.max())))
    return out


def fin_exposed_area(strips, fin) -> float:
    r"""Side area of a fin outside the hull [m^2]: :math:`A_e = \sum_i c_i\,dx_i\,s_i` with
    :math:`s_i` the length of the fin's span at strip i outside every hull part's section there
    (a tail fin whose root is set at the hull's smallest radius under it runs into the hull
    where the hull is wider), :math:`c_i` the coverage and :math:`dx_i` the strip width [m]."""
    hulls = [p for p in strips.parts if p.role == "hull"]
    cov = _coverage(fin)
    area = 0.0
    for row, i in enumerate(fin.index):
        axis, offset, lo, hi = _fin_span_interval(fin, row)
        inside = 0.0
        for h in hulls:
            rows = np.nonzero(h.index == i)[0]
            for j in rows:
                for a, b in _section_chord(h, int(j), axis, offset):
                    inside += max(0.0, min(hi, b) - max(lo, a))
        area += cov[row] * strips.dx[i] * max(hi - lo - inside, 0.0)
    return float(area)


def _fin_axial_added_mass(strips, fin, rho) -> float:
    r"""Surge added mass of a flat fin [kg]: its chordwise section moving along the chord
    (:func:`stripcoef.sections.added_mass.fin_edgewise`) over its span outside the hull,

    .. math:: m_{11} = C_A(t/c)\,\rho\pi(t/2)^2\,\frac{A_e}{c}

    (A_e: :func:`fin_exposed_area`; c = the covered length :math:`\sum c_i dx_i`, the chord;
    t the fin's thickness [m]).  Strip theory across the span: no relief at the tip [assumption],
    and none at the root, where the hull wall mirrors the fin; [assumption] the hull's own surge
    flow at the fin is not included.  Against the Capytaine BEM of six finned Myring hulls
    (benchmarks/finned_bodies.py) the fins' share of surge is within -15 % ... +37 % and the
    total within 1.3 %; the equal-area body of revolution it replaces gave -22 % ... +84 % and
    up to +5.0 % (docs/theory.md sec. 6)."""
    cov = _coverage(fin)
    chord = float(np.sum(cov * strips.dx[fin.index]))
    if chord <= 0:
        return 0.0
    thickness = 2.0 * float(np.min(np.minimum(fin.half_breadth, fin.half_height)))
    return fin_edgewise(thickness, chord, rho=rho) * fin_exposed_area(strips, fin) / chord


def _axial_added_mass(strips, rho, panels):
    """Surge added mass: the equal-area body of the hull parts, plus each other part as its
    own equal-area body (appendages are not smeared into rings round the hull), and each flat
    fin as its chordwise section moving along the chord (:func:`_fin_axial_added_mass`).

    m_11 = m_11^BEM[r_hull] + sum_parts m_11^BEM[r_part] + sum_fins m_11^fin [kg] (module
    docstring, Newman 1977, eq. 4.148); a part of < 3 strips gets the sphere's
    m_11 = rho V / 2 (Lamb 1932, sec. 373, k_1 = 1/2). ``rho`` [kg/m^3]. [assumption] no
    interaction between parts.
    """
    area = np.zeros(strips.n)
    others = []
    for p in strips.parts:
        if p.role == "hull":
            np.add.at(area, p.index, p.area * _coverage(p))
        else:
            others.append(p)
    m11 = 0.0
    if np.any(area > 0):
        m11 += _equivalent_bodies(strips, area, rho, 0.0, panels, (0,))[0, 0]
    for p in others:
        if p.role == "fin" and get_shape(p.shape).plate:
            m11 += _fin_axial_added_mass(strips, p, rho)
            continue
        cov = _coverage(p)
        vol = float(np.sum(p.area * cov * strips.dx[p.index]))
        if p.index.size < 3 or vol <= 0:
            m11 += 0.5 * rho * vol                  # too short to resolve: a sphere's k1 = 1/2
            continue
        order = np.argsort(p.index)
        idx, a, cov = p.index[order], p.area[order], cov[order]
        x = strips.x[idx]
        half = 0.5 * strips.dx[idx]
        # a part ending inside a strip covers the fraction cov of it from the inner side:
        # its end is there (not smeared over the strip), extrapolated in area
        x_lo = x[0] + half[0] - cov[0] * 2 * half[0]
        x_hi = x[-1] - half[-1] + cov[-1] * 2 * half[-1]
        a_lo = max(a[1] + (a[1] - a[2]) / (x[2] - x[1]) * (x[1] - x_lo), 0.0)
        a_hi = max(a[-2] + (a[-2] - a[-3]) / (x[-2] - x[-3]) * (x_hi - x[-2]), 0.0)
        px = np.r_[x_lo, x[1:-1], x_hi]
        pr = np.sqrt(np.r_[a_lo, a[1:-1], a_hi] / np.pi)
        m11 += body_of_revolution_added_mass(px, pr, rho=rho, panels=max(40, panels // 2),
                                             modes=(0,), area_linear=True)[0, 0]
    return m11


def _lateral(strips, per_strip, rho, xc, panels, closed_ends=CLOSED_ENDS):
    r"""3D/strip factors and coupling increment of the body of revolution pi r^2 = per_strip.

    .. math:: f_t = \frac{m_{22}^{3D}}{\rho\sum A\,dx},\quad
              f_r = \frac{m_{66}^{3D}}{\rho\sum A X^2 dx},\quad
              \Delta_{26} = m_{26}^{3D} - \sqrt{f_t f_r}\,\rho\sum A X\,dx,\quad X = x - x_c

    ``per_strip`` A [m^2], ``rho`` [kg/m^3], ``xc`` [m]; returns f_t, f_r [-],
    Delta_26 [kg m] and the 6x6 BEM matrix. See module docstring and :func:`hull_corrections`.
    """
    per_strip = np.asarray(per_strip, dtype=float)
    if not np.any(per_strip > 0):                  # nothing to correct in this direction
        return 1.0, 1.0, 0.0, np.zeros((6, 6))
    m3 = _equivalent_bodies(strips, per_strip, rho, xc, panels, (1,), closed_ends, steps=True)
    # the strip sums of the same body (its stations; a fin's step is already in the strip means)
    a = np.pi * np.sqrt(np.maximum(per_strip, 0.0) / np.pi) ** 2
    s22 = rho * np.sum(a * strips.dx)
    s26 = rho * np.sum(a * (strips.x - xc) * strips.dx)
    s66 = rho * np.sum(a * (strips.x - xc) ** 2 * strips.dx)
    ft, fr = float(m3[1, 1] / s22), float(m3[5, 5] / s66)
    return ft, fr, float(m3[1, 5] - np.sqrt(ft * fr) * s26), m3


def _positive_runs(per_strip):
    """Maximal runs (first, last) of consecutive strips with per_strip > 0."""
    on = np.r_[False, np.asarray(per_strip) > 0, False].astype(int)
    edges = np.diff(on)
    return list(zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0] - 1))


def _equivalent_bodies(strips, per_strip, rho, xc, panels, modes, closed_ends=False,
                       steps=False):
    """6x6 added mass (Fourier ``modes``) about x = ``xc`` of the equivalent body of revolution
    pi r^2 = ``per_strip`` [m^2]: one body when every strip has A > 0 (ends extrapolated, fin
    edges as steps with ``steps``: :func:`_equivalent_radius`), else one per run of strips with
    A > 0 (:func:`_run_added_mass`).
    ``rho`` [kg/m^3], ``xc`` [m]; Newman (1977) sec. 4.13."""
    runs = _positive_runs(per_strip)
    if len(runs) == 1 and runs[0] == (0, strips.n - 1):
        xs, rs = _equivalent_radius(strips, per_strip, closed_ends=closed_ends, steps=steps)
        return body_of_revolution_added_mass(xs, rs, rho=rho, x_ref=xc, panels=panels,
                                             modes=modes, area_linear=True)
    return sum(_run_added_mass(strips, per_strip, j, k, rho, xc, panels, modes)
               for j, k in runs)


def _run_added_mass(strips, per_strip, j, k, rho, xc, panels, modes=(1,)):
    r"""6x6 added mass (Fourier ``modes``) about x = ``xc`` of the equivalent body of revolution of the
    strips j..k, :math:`\pi r^2 = A(x)` (``per_strip`` A [m^2], ``rho`` [kg/m^3], [m]).

    Where the 2D added mass in a direction vanishes on whole strips (a member with no section
    there, a plate edge-on), the equivalent body touches the axis along a length: it is then
    several bodies of revolution, one per run of strips with A > 0, ends at the run's strip
    edges (area extrapolated linearly from the run's last two strips, clipped at 0; a single
    strip keeps its area, a flat disc).  [assumption] the runs' 3D interaction is neglected
    (they are separated by strips of no added mass in that direction); without this split the
    meridian had panels lying on the axis, whose ring kernels are singular (the all-NaN
    matrix of issue 14).  Newman (1977) sec. 4.13 (bodies of revolution).
    """
    x, dx, a = strips.x[j:k + 1], strips.dx[j:k + 1], per_strip[j:k + 1]
    lo, hi = x[0] - 0.5 * dx[0], x[-1] + 0.5 * dx[-1]
    if a.size >= 2:
        a_lo = max(a[0] + (a[0] - a[1]) / (x[1] - x[0]) * (x[0] - lo), 0.0)
        a_hi = max(a[-1] + (a[-1] - a[-2]) / (x[-1] - x[-2]) * (hi - x[-1]), 0.0)
    else:
        a_lo = a_hi = a[0]
    xs = np.r_[lo, x, hi]
    rs = np.sqrt(np.r_[a_lo, a, a_hi] / np.pi)
    return body_of_revolution_added_mass(xs, rs, rho=rho, x_ref=xc, panels=panels, modes=modes,
                                         area_linear=True)


def roll_symmetry_order(contours, max_order: int = 6) -> int:
    r"""Rotational symmetry order k of a section about its area centroid, at least 2.

    The largest k <= ``max_order`` for which the section rotated by :math:`2\pi/k` covers
    itself (symmetric difference < 1 % of its area); 2 when there is none (the roll flow of
    a rigid rotation has no source and its dipole is the sway/heave coupling, so its own far
    field is at least a quadrupole, Newman 1977, sec. 4.13).  ``contours`` (y, z) rings [m].
    """
    from shapely import affinity

    geom = section_geometry(contours)
    if geom.is_empty:
        return 2
    c = geom.centroid
    for k in range(max_order, 2, -1):
        rot = affinity.rotate(geom, 360.0 / k, origin=c)
        if geom.symmetric_difference(rot).area < 0.01 * geom.area:
            return k
    return 2


def roll_relief(strips, m44, *, rho: float, mode: int = 2, panels: int = DEFAULT_PANELS):
    r"""3D/strip ratio of the roll added mass from the roll-equivalent body of revolution.

    Each run of strips with roll added mass gets the body of revolution whose mode-m
    inertia per unit length (:func:`mode_inertia`, :math:`\rho\pi r^4/m` on a cylinder)
    equals the section's 2D roll added mass about its centroid,

    .. math:: r_p(x) = \left(\frac{m\,m_{44}^{2D}(x)}{\rho\pi}\right)^{1/4},\qquad
              f_p = \frac{\sum_{runs} I_m^{3D}[r_p]}{\int m_{44}^{2D}\,dx}

    with m the sections' rotational symmetry order (:func:`roll_symmetry_order`; 2 for a
    plate, 4 for a cruciform): the order of the 2D roll far field, whose decay along x sets
    the 3D relief.  Exact in the 2D limit (long cylinders) and for a sphere's mode 2
    (:math:`I_2 = 16\pi\rho R^5/45`, spherical harmonic of degree 2); [assumption] for other
    sections, checked against Lamb's exact elliptic plates (Lamb 1932, sec. 373, rotation
    about a diameter of the ellipsoid with c -> 0): the factor is 9 % low at aspect ratio 1,
    19 % low at 3.6 (docs/theory.md sec. 6).  ``m44`` [kg m] per strip, ``rho`` [kg/m^3].

    Returns the factor f_p [-] (1 if no strip has roll added mass, or only round-off: below
    :data:`ROLL_ROUNDOFF` times :math:`\int\rho A^2 dx`, e.g. a circle's panel solution).
    """
    m44 = np.clip(np.asarray(m44, dtype=float), 0.0, None)
    total = float(np.sum(m44 * strips.dx))
    if _roll_is_roundoff(strips, m44, rho):
        return 1.0
    on = m44 > 1e-3 * m44.max()
    i3d = 0.0
    j = 0
    n = strips.n
    while j < n:
        if not on[j]:
            j += 1
            continue
        k = j
        while k + 1 < n and on[k + 1]:
            k += 1
        x = strips.x[j:k + 1]
        r = (mode * m44[j:k + 1] / (rho * np.pi)) ** 0.25
        lo, hi = x[0] - 0.5 * strips.dx[j], x[-1] + 0.5 * strips.dx[k]
        i3d += mode_inertia(np.r_[lo, x, hi], np.r_[r[0], r, r[-1]], mode=mode, rho=rho,
                            panels=max(40, panels // 2))
        j = k + 1
    return i3d / total


def fin_sheet_3d(strips, rho: float) -> np.ndarray | None:
    r"""The fins' 3D share of the 6x6 added mass [kg, kg m, kg m^2], about the strips' origin, of
    a vehicle file's flat fins on a hull of revolution, by the thin-sheet panel method with the
    fins' thickness as an equivalent planform (:func:`stripcoef.hull.finsheet.fins_added_mass`;
    a read-only array), or None where it does not apply:
    parts other than one hull and its fins, a hull section that is not a circle on the x axis,
    a fin that is not a radial rectangle (span along y or z through the axis), or fins whose
    section is neither a cruciform nor an opposite pair (the 2D thickness equivalence needs one
    of the two).  ``rho`` [kg/m^3]."""
    hulls = [p for p in strips.parts if p.role == "hull"]
    fins = [p for p in strips.parts if p.role == "fin"]
    if len(hulls) != 1 or not fins or len(hulls) + len(fins) != len(strips.parts):
        return None
    hull = hulls[0]
    b, h = hull.half_breadth, hull.half_height
    if not get_shape(hull.shape).elliptic or not np.allclose(b, h, rtol=1e-6) \
            or np.any(np.abs(hull.y) > 1e-9 * b.max()) or np.any(np.abs(hull.z) > 1e-9 * b.max()):
        return None
    xh = strips.x[hull.index]
    x_aft = xh[0] - 0.5 * strips.dx[hull.index[0]]
    x_fore = xh[-1] + 0.5 * strips.dx[hull.index[-1]]
    planforms, thickness = [], []
    for f in fins:
        if not get_shape(f.shape).plate or len(f.index) < 2:
            return None
        axis, offset, lo, hi = _fin_span_interval(f, len(f.index) // 2)
        tip = max(abs(lo), abs(hi))
        if abs(offset) > 1e-6 * tip or lo * hi < 0:
            return None
        angle = {("y", True): 0.0, ("z", True): 0.5 * np.pi, ("y", False): np.pi,
                 ("z", False): 1.5 * np.pi}[(axis, hi > 0)]
        cov, i0, i1 = _coverage(f), f.index[0], f.index[-1]
        aft = strips.x[i0] + 0.5 * strips.dx[i0] - cov[0] * strips.dx[i0]
        fore = strips.x[i1] - 0.5 * strips.dx[i1] + cov[-1] * strips.dx[i1]
        planforms.append(FinPlanform(angle, float(aft), float(fore), float(tip)))
        thickness.append(2.0 * float(np.mean(f.half_breadth if axis == "z" else f.half_height)))
    tips = []
    for f in planforms:
        group = {round(g.angle / (0.5 * np.pi)) % 4 for g in planforms
                 if g.x_aft < f.x_fore and f.x_aft < g.x_fore}
        if group == {0, 1, 2, 3}:
            tips.append(4)
        elif group in ({0, 2}, {1, 3}):
            tips.append(2)
        else:
            return None
    return frozen_array(_fins_sheet(np.ascontiguousarray(xh, dtype=float),
                                    np.asarray(b, dtype=float), float(x_aft), float(x_fore),
                                    tuple(planforms), tuple(thickness), tuple(tips), float(rho)))


@array_memo(maxsize=16)
def _fins_sheet(x, r, x_aft, x_fore, planforms, thickness, tips, rho) -> np.ndarray:
    """:func:`stripcoef.hull.finsheet.fins_added_mass` of the hull radius ``r`` at the
    stations ``x`` (float64 arrays; the memo of :func:`stripcoef.hull.memo.array_memo`, so
    that the roll correction and the assembly of one estimate solve it once)."""
    return fins_added_mass(lambda s: np.interp(s, x, r), x_aft, x_fore, list(planforms),
                           list(thickness), list(tips), rho=rho)


def _roll_is_roundoff(strips, m44, rho) -> bool:
    r"""No roll added mass but round-off: :math:`\int m_{44}^{2D} dx \le`
    :data:`ROLL_ROUNDOFF` :math:`\int\rho A^2 dx` (``m44`` [kg m] per strip, ``rho``
    [kg/m^3])."""
    total = float(np.sum(np.clip(m44, 0.0, None) * strips.dx))
    return not total > ROLL_ROUNDOFF * rho * float(np.sum(_strip_area(strips) ** 2 * strips.dx))


def _fin_roll_mode(strips, m44) -> int | None:
    """Symmetry order of a vehicle file's finned section with the largest roll added mass: 4 for
    a cruciform (a vertical and a horizontal fin pair), 2 for one pair; None without fins."""
    fins = [p for p in strips.parts if p.role == "fin"]
    if not fins:
        return None
    k = int(np.argmax(np.asarray(m44)))
    here = [p for p in fins if np.any(p.index == k)]
    vertical = {bool(p.half_height[0] > p.half_breadth[0]) for p in here}
    return 4 if len(vertical) == 2 else 2


def _polygon_roll_mode(strips, m44) -> int | None:
    """Symmetry order of the section with the largest roll added mass, for bodies made of
    polygon parts only (meshes); for vehicle files the finned section's
    (:func:`_fin_roll_mode`); None otherwise (roll left uncorrected)."""
    if not strips.parts or not all(has_rings(p) for p in strips.parts):
        return _fin_roll_mode(strips, m44)
    if len(strips.parts) != 1:
        return 2
    p = strips.parts[0]
    k = int(np.argmax(np.asarray(m44)[p.index]))
    return roll_symmetry_order(p.contours[k])


@dataclass(frozen=True)
class CorrectionFactors:
    r"""The 3D corrections of a strip matrix (:func:`hull_corrections`), applied by
    :func:`apply_corrections`: :math:`M = D S D + m_{11} e_1 e_1^T + \Delta_{26}(e_2 e_6^T +
    e_6 e_2^T) + \Delta_{35}(e_3 e_5^T + e_5 e_3^T)`, :math:`D = \operatorname{diag}(\sqrt{scale})`.

    Attributes
    ----------
    scale : (6,) array
        Diagonal of D**2, the factors of the strip matrix' diagonal [-] (read-only)
    axial_added_mass : float
        m_11 [kg]
    coupling_26, coupling_35 : float
        Sway-yaw and heave-pitch increments Delta_26, Delta_35 [kg m]
    method : str
        How they were obtained
    """

    scale: np.ndarray
    axial_added_mass: float
    coupling_26: float
    coupling_35: float
    method: str

    def __post_init__(self):
        object.__setattr__(self, "scale", frozen_array(self.scale))

    @property
    def translation(self) -> float:
        """f_v = scale[1], the sway factor [-]."""
        return self.scale[1]

    @property
    def rotation(self) -> float:
        """f_r = scale[5], the yaw factor [-]."""
        return self.scale[5]

    @property
    def coupling(self) -> float:
        """Delta_26 [kg m], the sway-yaw increment."""
        return self.coupling_26


def hull_corrections(strips, *, rho: float, center, section_added_mass=None,
                     panels: int = DEFAULT_PANELS, axial: bool = True) -> CorrectionFactors:
    r"""3D corrections for :func:`stripcoef.assembly.estimate.added_mass`, per direction.

    Each lateral direction gets its own *added-mass-equivalent* body of revolution,
    whose radius reproduces the strips' 2D added mass in that direction,

    .. math:: \pi\rho\, r_v(x)^2 = m^{2D}_{22}(x),\qquad \pi\rho\, r_w(x)^2 = m^{2D}_{33}(x),

    (for a circular hull both are the hull itself; fins, plates and pods widen them
    where they are).  Its 3D added mass (axisymmetric BEM) against its own strip
    theory gives the factors and the sway-yaw / heave-pitch coupling increments,

    .. math:: f_v = \frac{m_{22}^{3D}[r_v]}{\int\rho\pi r_v^2 dx},\quad
              f_r = \frac{m_{66}^{3D}[r_v]}{\int\rho\pi r_v^2 (x-x_c)^2 dx},\quad
              \Delta_{26} = m_{26}^{3D}[r_v] - \sqrt{f_v f_r}\int\rho\pi r_v^2 (x-x_c) dx

    and likewise :math:`f_w, f_q, \Delta_{35}` from :math:`r_w`.  The axial added mass
    is that of the equal-area body :math:`\pi r_A^2 = A(x)` of the hull parts plus that of
    each other part's own equal-area body (appendages are not smeared into rings).
    Applied to the strip matrix S about ``center``:
    :math:`S \to D S D`, :math:`D = diag(1, \sqrt{f_v}, \sqrt{f_w}, 1, \sqrt{f_q}, \sqrt{f_r})`,
    then :math:`S_{11} += m_{11}`, :math:`S_{26} = S_{62} += \Delta_{26}`,
    :math:`S_{35} = S_{53} += \Delta_{35}`.  For a body of revolution this is its exact
    3D matrix (to the panel discretisation).  A body whose every section has a hole (a duct,
    a ring: :func:`bore_area`) gets one *hollow* equivalent body instead, the tube of its
    outer-contour and bore areas, for surge and both lateral directions
    (:func:`_hollow_corrections`; exact for a circular tube).  Roll: for mesh bodies (polygon
    parts) the section roll terms are scaled by :func:`roll_relief` (``scale[3]``); otherwise 1.

    Parameters
    ----------
    strips : Strips
    rho : float
        Fluid density [kg/m^3]
    center : (3,)
        Point about which the strip matrix is assembled (its x is used) [m]
    section_added_mass : (n, 3, 3) array, optional
        Per-strip 2D added mass (:func:`strip_section_added_mass`); default: the
        equal-area circle, :math:`\rho A(x)` in both directions.
    axial : bool
        Solve the axial added mass (default); False leaves ``axial_added_mass`` = 0 (a caller
        that needs only the lateral factors, e.g. the fins' distribution).

    Returns
    -------
    CorrectionFactors
        ``scale`` (6,) diagonal of D**2, ``axial_added_mass`` [kg], ``coupling_26``,
        ``coupling_35`` [kg m], ``method`` (and the sway-yaw values ``translation``,
        ``rotation``, ``coupling``).

    References
    ----------
    See the module docstring; Newman (1977) sec. 7.4 for strip theory's end error;
    DNV-RP-C205 table A-2 for the finite-length reduction of plates that this
    reproduces for plate-like sections.
    """
    xc = float(np.asarray(center, dtype=float)[0])
    bore = bore_area(strips)            # a bore along the whole body: hollow equivalent body
    if bore is not None:
        m11, fv, fr, d26 = _hollow_corrections(strips, bore, rho, xc, panels)
    else:
        m11 = _axial_added_mass(strips, rho, panels) if axial else 0.0
    if section_added_mass is None:
        mv = mw = _strip_area(strips)
    else:
        m2d = np.asarray(section_added_mass, dtype=float)
        mv, mw = m2d[:, 0, 0] / rho, m2d[:, 1, 1] / rho
    if bore is None:
        fv, fr, d26, _ = _lateral(strips, mv, rho, xc, panels)
    if bore is not None or section_added_mass is None \
            or np.allclose(mv, mw, rtol=SAME_BODY_RTOL, atol=0.0):
        fw, fq, d35 = fv, fr, -d26      # one equivalent body for both directions
    else:
        fw, fq, d62, _ = _lateral(strips, mw, rho, xc, panels)
        d35 = -d62                      # heave-pitch: M[2,4] = -m26 of the heave body
    fp = 1.0
    if section_added_mass is not None:
        m44 = np.asarray(section_added_mass, dtype=float)[:, 2, 2]
        mode = None if _roll_is_roundoff(strips, m44, rho) else _polygon_roll_mode(strips, m44)
        if mode is not None:
            sheet = fin_sheet_3d(strips, rho)
            fp = (sheet[3, 3] / float(np.sum(np.clip(m44, 0.0, None) * strips.dx))
                  if sheet is not None
                  else roll_relief(strips, m44, rho=rho, mode=mode, panels=panels))
    return CorrectionFactors(
        scale=np.array([1.0, fv, fw, fp, fq, fr]), axial_added_mass=float(m11),
        coupling_26=d26, coupling_35=d35,
        method="axisymmetric BEM of the added-mass-equivalent bodies of revolution")


def apply_corrections(strip_matrix, corr: CorrectionFactors) -> np.ndarray:
    r"""Corrected 6x6 added mass from the pure strip matrix about ``center`` (see
    :func:`hull_corrections`): :math:`D S D` plus the axial term and coupling increments.

    .. math:: M = D S D + m_{11} e_1 e_1^T + \Delta_{26}(e_2 e_6^T + e_6 e_2^T)
              + \Delta_{35}(e_3 e_5^T + e_5 e_3^T),\quad D = \operatorname{diag}(\sqrt{scale})

    ``strip_matrix`` S and the result [kg, kg m, kg m^2]; ``scale`` [-], ``axial_added_mass``
    [kg], couplings [kg m]. References: see module docstring (Newman 1977, sec. 7.4).
    """
    s = np.sqrt(np.asarray(corr.scale, dtype=float))
    m = s[:, None] * np.asarray(strip_matrix, dtype=float) * s[None, :]
    m[0, 0] += corr.axial_added_mass
    m[1, 5] += corr.coupling_26
    m[5, 1] += corr.coupling_26
    m[2, 4] += corr.coupling_35
    m[4, 2] += corr.coupling_35
    return m


# --- bodies of revolution whose meridian does not touch the axis (tubes, rings) -------------


def bore_area(strips):
    r"""Per-strip area of the bore of a body whose every section has a hole [m^2], else None.

    .. math:: A_{bore}(x_i) = \sum_{parts} c_{p,i} \sum_{holes} |A_{hole}|

    (holes: the clockwise rings of the polygon parts' contours, ``Strips`` of a mesh;
    coverage :math:`c_{p,i}`).  None when a strip has no hole, or a part is not a polygon:
    a bore along the whole body (a duct, a ring) gets the hollow equivalent bodies of
    :func:`hull_corrections`, anything else the solid ones.
    """
    if not strips.parts or not all(has_rings(p) for p in strips.parts):
        return None
    several = np.zeros(strips.n)        # a hole needs a second ring round it in the section
    for p in strips.parts:
        np.add.at(several, p.index, [len(rings) > 1 for rings in p.contours])
    if not np.all(several > 0):
        return None
    out = np.zeros(strips.n)
    for p in strips.parts:
        holes = np.array([sum(-a for a in (ring_integrals(r)[0] for r in rings) if a < 0)
                          if len(rings) > 1 else 0.0 for rings in p.contours])
        np.add.at(out, p.index, holes * _coverage(p))
    return out if np.all(out > 0) else None


def _hollow_profile(strips, bore):
    """Closed meridian (x, r) of the tube of a bored body: pi r_o^2 = A(x) + A_bore(x) (the
    outer contour's area), pi r_i^2 = A_bore(x) at the strip centres, flat ends at the body's
    first and last x [m]."""
    area = _strip_area(strips)
    ri2 = np.asarray(bore, dtype=float) / np.pi
    ro2 = ri2 + np.maximum(area, 1e-9 * ri2) / np.pi
    x = np.r_[strips.x_min, strips.x, strips.x_max]
    ro = np.sqrt(np.r_[ro2[0], ro2, ro2[-1]])
    ri = np.sqrt(np.r_[ri2[0], ri2, ri2[-1]])
    return np.r_[x, x[::-1]], np.r_[ro, ri[::-1]]


def _hollow_corrections(strips, bore, rho, xc, panels):
    r"""Axial added mass, 3D/strip factors and coupling increment of a bored body.

    A body whose every section has a hole (a duct, a ring) gets, instead of the solid
    equivalent bodies of :func:`hull_corrections`, its *hollow* equivalent body: the tube with
    the same outer-contour and bore areas,

    .. math:: \pi r_o^2 = A(x) + A_{bore}(x),\qquad \pi r_i^2 = A_{bore}(x),

    solved with :func:`ring_body_added_mass` (for a circular tube: the tube itself, so its 3D
    matrix is exact).  In 2D the bore's water moves with the section (its 2D added mass
    counts :math:`\rho A_{bore}`, docs/theory.md sec. 6); in 3D it leaves axially, which the
    tube's 3D flow holds.  The factors are those of the tube against its own strip theory
    (the 2D annulus :math:`\rho\pi(r_o^2 + r_i^2)`), applied to the real sections' strip
    matrix in both lateral directions,

    .. math:: f_t = \frac{m_{22}^{3D}}{\rho\int\pi(r_o^2+r_i^2)dx},\quad
              f_r = \frac{m_{66}^{3D}}{\rho\int\pi(r_o^2+r_i^2)(x-x_c)^2dx},\quad
              \Delta_{26} = m_{26}^{3D} - \sqrt{f_t f_r}\,\rho\int\pi(r_o^2+r_i^2)(x-x_c)dx

    and :math:`m_{11} = m_{11}^{3D}`.  ``bore`` [m^2], ``rho`` [kg/m^3], ``xc`` [m]; returns
    (m11 [kg], f_t, f_r [-], Delta_26 [kg m]).  [assumption] beyond circular tubes: a short
    square ring (outer 0.6 m, wall 0.06 m, length 0.03-0.6 m) against Capytaine is within
    -0.9..+4.0 % on sway and heave, +4.6..+11.0 % on pitch, +3.0..+5.3 % on surge, where the
    solid equivalent bodies gave -8..-15 %, +124..+1600 % and +110..+170 %
    (benchmarks/junction_relief.py rings; Newman 1977 sec. 4.13 for the 2D annulus).
    """
    xm, rm = _hollow_profile(strips, bore)
    m3 = ring_body_added_mass(xm, rm, rho=rho, x_ref=xc, panels=panels)
    n = strips.n
    a = np.pi * (rm[1:n + 1] ** 2 + rm[::-1][1:n + 1] ** 2)
    s22 = rho * np.sum(a * strips.dx)
    s26 = rho * np.sum(a * (strips.x - xc) * strips.dx)
    s66 = rho * np.sum(a * (strips.x - xc) ** 2 * strips.dx)
    ft, fr = float(m3[1, 1] / s22), float(m3[5, 5] / s66)
    return float(m3[0, 0]), ft, fr, float(m3[1, 5] - np.sqrt(ft * fr) * s26)
