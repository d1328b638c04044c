r"""Added mass of the whole vehicle: strip integral, 3D corrections, entrained water.

Added mass (strip theory, Newman 1977 sec. 7.4; Fossen 2011 sec. 6.3.3). A strip at
``x`` whose section has the 2D matrix :math:`m(x)` (sway, heave, roll, about the
reference line) moves with :math:`[v + X r,\ w - X q,\ p] = L(X)\,\nu`,
:math:`X = x - x_0`, hence

.. math:: M_A^{strip} = \int L(X)^T\, m(x)\, L(X)\, dx,\quad
          L = \begin{bmatrix}0&1&0&0&0&X\\0&0&1&0&-X&0\\0&0&0&1&0&0\end{bmatrix}

giving e.g. :math:`Y_{\dot v} = -\int m_{22}`, :math:`Y_{\dot r} = N_{\dot v} = -\int X m_{22}`,
:math:`N_{\dot r} = -\int X^2 m_{22}`, :math:`Z_{\dot q} = M_{\dot w} = \int X m_{33}`.
Parts off the reference line are shifted in 2D by
:math:`H_2 = [[1,0,-\Delta z],[0,1,\Delta y],[0,0,1]]`, :math:`m \to H_2^T m H_2`, which
creates the roll couplings of off-axis appendages (K_vdot from a sonar housing below).
Then the 3D end correction (:func:`stripcoef.hull.lamb.end_correction_factors`), the axial
added mass :math:`k_1\rho V` of the equivalent spheroid (Ferreira et al. 2009, eq. 36), and the water
carried in through-holes and ducts

.. math:: M_{hole} = \rho \int [I,\ -S(r)]^T (I - a a^T) [I,\ -S(r)]\, dV

(the water's velocity component across the hole axis ``a`` moves with the body; along
the axis it passes freely: Ferreira et al. 2009, sec. IV.C).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace

import numpy as np
from stripcoef.conventions import skew, transform_matrix
from stripcoef.errors import InputError, ModelWarning
from stripcoef.hull.lamb import end_correction_factors
from stripcoef.sections import get_shape, section_added_mass
from stripcoef.strips import Strips
from stripcoef.strips import hole_widths, strip_added_mass


def _fin_pairs(hull, ih, fins, s_idx, reach):
    """The symmetric fin pairs of strip ``s_idx`` on the circular hull section ``ih``.

    A pair is two fins spanning the same axis (both along z, or both along y), centred on the
    hull's other coordinate, on opposite sides, with equal tip radius a > R, whose roots touch
    the hull (root radius <= ``reach[k]``, the largest hull radius under fin part k: on a
    tapering tail the root may stand off the hull at the fin's thin end).  Returns a list of (n, a, [(k, i), (k, i)], coverage): n the
    normal direction (0: sway, normal to vertical fins; 1: heave), a [m], the fins' (part,
    position) and the pair's mean coverage of the strip [-].
    """
    b = hull.half_breadth[ih]
    here = []
    for k, f in fins:
        pos = np.nonzero(f.index == s_idx)[0]
        if pos.size:
            here.append((k, f, int(pos[0])))
    pairs, used = [], set()
    for u in range(len(here)):
        for v in range(u + 1, len(here)):
            if u in used or v in used:
                continue
            (ka, fa, ia), (kb, fb, ib) = here[u], here[v]
            vertical = fa.half_height[ia] > fa.half_breadth[ia]
            if vertical != (fb.half_height[ib] > fb.half_breadth[ib]):
                continue
            if vertical:
                off_a, off_b = fa.z[ia] - hull.z[ih], fb.z[ib] - hull.z[ih]
                lat_ok = np.isclose(fa.y[ia], hull.y[ih]) and np.isclose(fb.y[ib], hull.y[ih])
                half_a, half_b = fa.half_height[ia], fb.half_height[ib]
            else:
                off_a, off_b = fa.y[ia] - hull.y[ih], fb.y[ib] - hull.y[ih]
                lat_ok = np.isclose(fa.z[ia], hull.z[ih]) and np.isclose(fb.z[ib], hull.z[ih])
                half_a, half_b = fa.half_breadth[ia], fb.half_breadth[ib]
            tip_a, tip_b = abs(off_a) + half_a, abs(off_b) + half_b
            touching = (abs(off_a) - half_a <= reach[ka] * (1 + 1e-6)
                        and abs(off_b) - half_b <= reach[kb] * (1 + 1e-6))
            if not (lat_ok and off_a * off_b < 0 and np.isclose(tip_a, tip_b, rtol=1e-6)
                    and touching and tip_a > b):
                continue
            used.update((u, v))
            cov = 0.5 * (fa.coverage[ia] + fb.coverage[ib])
            pairs.append((0 if vertical else 1, float(tip_a), [(ka, ia), (kb, ib)], float(cov)))
    return pairs


@dataclass(frozen=True)
class FinShare:
    r"""A fin pair's share of one strip's 2D added mass normal to the pair (:func:`_combine_fins`).

    ``pair``: the two fins' part indices; ``n``: 0 (sway, vertical fins) or 1 (heave);
    ``hull``, ``row``: the hull part and its row holding the finned section; ``strip``: the
    strip index; ``increment``: :math:`c\,(m_n - \rho\pi R^2)\,C_A` [kg/m] (C_A the
    thickness factor of :func:`_fin_thickness_factor`); ``coverage`` c [-];
    ``exposed_span``: a - R, the fin's span outside the hull there [m].
    """

    pair: tuple
    n: int
    hull: int
    row: int
    strip: int
    increment: float
    coverage: float
    exposed_span: float


def _fin_thickness_factor(span, half_thickness) -> float:
    r"""The fins' thickness on their share of a finned section's normal added mass [-].

    The exposed pair is a rectangle 2s x t (s the exposed span [m], t the thickness [m]) moving
    normal to its long side; its added mass over the thin plate's is the rectangle's coefficient

    .. math:: C_A(s / (t/2))

    (:func:`stripcoef.sections.added_mass.rectangle_coefficient`, DNV-RP-C205 table A-1; 1 for
    t = 0), applied to the whole share :math:`m_n - \rho\pi R^2` [assumption: the hull's
    interference scales with it; the 2D panel method of the thick finned circle gives 1.143,
    1.100, 1.093 where this gives 1.130, 1.101, 1.088 for the three finned hulls of
    benchmarks/finned_bodies.py, tests/test_fin_plate.py].
    """
    from stripcoef.sections.added_mass import rectangle_coefficient
    if half_thickness <= 0:
        return 1.0
    return float(rectangle_coefficient(np.array([span / half_thickness]))[0])


def _combine_fins(strips: Strips, mats: list, rho: float) -> list:
    r"""Replace hull + fin sums by the exact finned-circle section where it applies (in place).

    Where a circular hull section carries a symmetric pair of fins (both spanning along z,
    mirrored about the hull axis, or both along y; :func:`_fin_pairs`) whose roots touch the
    hull, the section normal to the fins is the circle with fins of tip radius a, and a
    cruciform (a vertical and a horizontal pair) rolls as one section:

    .. math:: m_n = \rho\pi(a^2 - R^2 + R^4/a^2),\qquad
              m_{44} = m_{44}^{pair}(R, a)\ \text{or}\ m_{44}^{cruciform}(R, a)

    (:func:`stripcoef.sections.added_mass.circle_with_fins`, exact by conformal mapping:
    Newman 1977 sec. 4.13; Blevins 1979 table 14-2; Prestero 2001 sec. 3.4), instead of the
    circle plus isolated plates, which ignores their interaction.  The cruciform's roll is the
    whole section's, counted once and shared by its four fins; with unequal tip radii
    :math:`a_v \ne a_h` it is the mean of the two equal-tip cruciforms' [assumption: exact
    when equal].

    Partial coverage: where the fins cover only the fraction c of a strip (their leading and
    trailing edges), the strip is the finned section over c and the bare circle over 1 - c,

    .. math:: m_{hull,n} = \rho\pi R^2 + c\,(m_n - \rho\pi R^2)\,C_A(s/(t/2))

    (C_A: the fins' thickness t on their share, :func:`_fin_thickness_factor`, s = a - R; the
    fins' own roll entries are weighted by c through their coverage), so the strip
    integral converges with the strip count like the bare hull's.

    Hull radius R and tip radius a [m], rho [kg/m^3]; m_n [kg/m], m_44 [kg m] per unit
    length, written into ``mats`` (per part, (k, 3, 3) [kg/m, kg, kg m]).

    Returns the fins' shares, one :class:`FinShare` per strip and pair: the increment
    :math:`c\,(m_n - \rho\pi R^2)\,C_A` [kg/m] written into the hull's entry (n, n), for the 3D
    correction of :func:`fin_share_corrections`.
    """
    from stripcoef.sections.added_mass import circle_with_fins, finned_circle_roll

    shares: list[FinShare] = []
    hulls = [(k, p) for k, p in enumerate(strips.parts) if p.role == "hull"
              and get_shape(p.shape).elliptic]
    fins = [(k, p) for k, p in enumerate(strips.parts) if p.role == "fin"]
    if not hulls or len(fins) < 2:
        return shares
    fin_strips = np.unique(np.concatenate([p.index for _, p in fins]))
    for kh, hull in hulls:
        pos_h = {int(i): j for j, i in enumerate(hull.index)}
        reach = {}
        for k, f in fins:
            under = [pos_h[int(i)] for i in f.index if int(i) in pos_h]
            reach[k] = float(np.max(hull.half_breadth[under])) if under else 0.0
        for s_idx in np.intersect1d(fin_strips, hull.index):
            ih = pos_h[int(s_idx)]
            b, h = hull.half_breadth[ih], hull.half_height[ih]
            if not np.isclose(b, h, rtol=1e-6):
                continue
            pairs = _fin_pairs(hull, ih, fins, s_idx, reach)
            if not pairs:
                continue
            circle = rho * np.pi * b * b
            for n, tip, members, cov in pairs:
                m_n, _ = circle_with_fins(b, tip, rho=rho)
                half_t = float(np.mean([strips.parts[k].half_breadth[i] if n == 0
                                        else strips.parts[k].half_height[i] for k, i in members]))
                inc = cov * (m_n - circle) * _fin_thickness_factor(tip - b, half_t)
                mats[kh][ih, n, n] = circle + inc
                shares.append(FinShare(pair=tuple(sorted(k for k, _ in members)), n=n, hull=kh,
                                       row=ih, strip=int(s_idx), increment=inc,
                                       coverage=cov, exposed_span=tip - b))
                for k, i in members:
                    mats[k][i, n, n] = 0.0
            vert = [p for p in pairs if p[0] == 0]
            horiz = [p for p in pairs if p[0] == 1]
            if vert and horiz:           # a cruciform: one roll term for the whole section
                m44 = np.mean([finned_circle_roll(b, t, fins=4, rho=rho)
                               for t in {vert[0][1], horiz[0][1]}])
                groups = [(vert[0][2] + horiz[0][2], m44)]
                rest = vert[1:] + horiz[1:]
            else:
                groups, rest = [], pairs
            for _, tip, members, _ in rest:
                groups.append((members, finned_circle_roll(b, tip, fins=2, rho=rho)))
            for members, m44 in groups:
                for k, i in members:
                    mats[k][i, 2, 2] = m44 / len(members)
    return shares


def section_matrices(strips: Strips, rho: float, panels: int | None = None) -> list:
    r"""Per part, the (k, 3, 3) 2D added mass about the part's centre [kg/m, kg, kg m], with
    fin pairs combined (:func:`_combine_fins`) and the open width of holes removed.

    .. math:: m_{33} \leftarrow m_{33}\,(1 - c_z/2b)^2,\qquad m_{22} \leftarrow m_{22}\,(1 - c_y/2h)^2

    with open hole widths c_z, c_y [m] (:func:`hole_widths`), half-breadth b and
    half-height h [m]; ``rho`` [kg/m^3]. Sections: :func:`stripcoef.sections.section_added_mass`
    (``panels``: panels per polygon section, default adaptive).

    References
    ----------
    Holes pass heave (sway) flow: Ferreira et al. 2009, eq. 40; the squared open-width factor is an
    [assumption] (added mass ~ width^2, as for a plate, DNV-RP-C205 table A-1).
    """
    return _sections_and_fin_shares(strips, rho, panels)[0]


def _sections_and_fin_shares(strips: Strips, rho: float, panels: int | None = None):
    """:func:`section_matrices` and the fins' shares of them (:func:`_combine_fins`, their
    increments reduced by the same open-hole factors as the hull entry holding them)."""
    mats = [section_added_mass(p, rho, panels).copy() for p in strips.parts]
    shares = _combine_fins(strips, mats, rho)
    before = {(f.hull, f.row, f.n): mats[f.hull][f.row, f.n, f.n] for f in shares}
    for p, m in zip(strips.parts, mats):
        cy, cz = hole_widths(strips, p)
        if np.any(cz > 0):   # heave passes through vertical holes (Ferreira et al. 2009, eq. 40)
            m[:, 1, 1] *= np.clip(1.0 - cz / (2 * p.half_breadth), 0.0, 1.0) ** 2
        if np.any(cy > 0):   # sway passes through horizontal holes
            m[:, 0, 0] *= np.clip(1.0 - cy / (2 * p.half_height), 0.0, 1.0) ** 2
    shares = [replace(f, increment=f.increment * (mats[f.hull][f.row, f.n, f.n]
                                                  / before[(f.hull, f.row, f.n)]))
              if before[(f.hull, f.row, f.n)] > 0 else f for f in shares]
    return mats, shares


def distribute_fin_shares(bare, folded, fin_parts) -> np.ndarray:
    r"""Corrected 6x6 added mass of a finned body from its hull and its fin pairs' shares.

    The fins' 3D share in sway and yaw (heave and pitch) is the finned equivalent body's,
    :math:`\Delta = M[\text{hull and fins folded into one body}] - M[\text{bare hull}]`
    (:func:`stripcoef.hull.corrections.hull_corrections` on both), which carries the share's
    distribution along x and its 3D interaction with the hull, rescaled so that its translation
    term is the plates' (:func:`fin_share_corrections`),

    .. math:: M_{B} = M^{bare}_{B} + g\,\Delta_{B},\qquad
              g = \frac{\sum_{pairs} \kappa\, S_{pair,jj}}{\Delta_{jj}}

    for the blocks B = {sway, yaw} (j = sway) and {heave, pitch} (j = heave); every other entry
    is :math:`M^{bare} + \sum \kappa S_{pair}`.  [assumption] the collar of the folded body
    has the fins' chordwise distribution but not their magnitude (a ring is relieved round its
    edges unlike a plate): on the three finned hulls of benchmarks/finned_bodies.py the
    corrected share's centroid is 2, 10 and 0.1 mm aft of the BEM's, the strip sum's 23, 28
    and 1.5 mm.  ``bare``, ``folded`` [kg, kg m, kg m^2] about the same point;
    ``fin_parts`` from :func:`fin_share_corrections`.  References: as
    :func:`fin_share_corrections`; Newman (1977) sec. 4.13-4.15.
    """
    out = np.asarray(bare, dtype=float) + sum(k * sp for sp, k, *_ in fin_parts)
    if folded is None:
        return out
    delta = np.asarray(folded, dtype=float) - bare
    target = sum(k * sp for sp, k, *_ in fin_parts)
    for j, block in ((1, (1, 5)), (2, (2, 4))):
        if target[j, j] > 0 and delta[j, j] > 1e-9 * max(target[j, j], 1e-300):
            g = target[j, j] / delta[j, j]
            idx = np.ix_(block, block)
            out[idx] = bare[idx] + g * delta[idx]
    return out


#: Sway, heave, pitch and yaw: the entries whose fins' share the thin sheet gives
#: (:func:`sheet_fin_shares`)
_SHEET_MODES = (1, 2, 4, 5)


def sheet_fin_shares(bare, sheet, fin_parts, center) -> np.ndarray:
    r"""Corrected 6x6 added mass of a finned hull of revolution from its bare hull and the fins'
    3D share by the thin-sheet panel method.

    .. math:: M_{ij} = M^{bare}_{ij} + \Delta^{sheet}_{ij}\quad (i, j \in
              \{\text{sway, heave, pitch, yaw}\}),\qquad
              M_{ij} = M^{bare}_{ij} + \sum_{pairs} \kappa S_{pair,ij}\ \text{otherwise},

    :math:`\Delta^{sheet}` (:func:`stripcoef.hull.finsheet.fins_added_mass`, about the origin)
    moved to ``center`` [m] (:func:`stripcoef.conventions.transform_matrix`).  The sheet is
    thin, so the fins' share of surge (their chordwise sections moving edgewise) keeps the strip
    treatment, and their roll is already the sheet's in ``bare`` (the roll factor of
    :func:`stripcoef.hull.corrections.hull_corrections`).  [assumption] ``center`` is on the
    hull's axis (the centre of buoyancy of a hull of revolution with symmetric fins), so that
    moving the share there couples no roll.  ``bare``, the bare hull's corrected matrix about
    ``center`` [kg, kg m, kg m^2]; ``fin_parts`` from :func:`fin_share_corrections`."""
    bare = np.asarray(bare, dtype=float)
    out = bare + sum(k * sp for sp, k, *_ in fin_parts)
    moved = transform_matrix(np.asarray(sheet, dtype=float), from_point=(0.0, 0.0, 0.0),
                             to_point=center)
    idx = np.ix_(_SHEET_MODES, _SHEET_MODES)
    out[idx] = bare[idx] + moved[idx]
    return out


def fin_share_corrections(strips: Strips, mats: list, shares: list, center) -> list:
    r"""Each fin pair's share of the strip matrix and its 3D factor.

    The fins' share of a finned section normal to a pair (:func:`_combine_fins`) is, with the
    exposed span s = a - R,

    .. math:: m_n - \rho\pi R^2 = \rho\pi\frac{(a^2 - R^2)^2}{a^2}
              = \Big(1 + \frac{R}{a}\Big)^2 \rho\pi s^2,

    the 2D added mass of the exposed pair joined at its roots (a plate of span 2s) times the
    slender-body fin-hull interference factor :math:`(1 + R/a)^2`.  Summed along the chord it
    is strip theory of that plate, which is right only for a chord much longer than the span;
    its 3D value is the rectangular plate's, :math:`\kappa(2\bar s, c)` times the strip sum
    (:func:`stripcoef.sections.added_mass.plate_chordwise_factor`, DNV-RP-H103 table A-2),
    keeping the interference factor of slender-body theory, as Pitts, Nielsen & Kaattari (1957)
    keep theirs on the 3D wing-alone lift.  Per pair (``shares`` grouped by their fins and
    direction), with chord :math:`c = \sum_i c_i\,dx_i` [m] and mean exposed span
    :math:`\bar s = \sum_i c_i\,dx_i\,s_i / c` [m] (c_i the coverage, dx_i the strip width):

    .. math:: M_{fins} = \sum_{pairs} \kappa(2\bar s, c)\, S_{pair},

    :math:`S_{pair}` the strip matrix about ``center`` [m] of the pair's increments alone
    [kg, kg m, kg m^2].  [assumption] the interference factor and the hull's own 3D correction
    are unchanged by the fins' finite chord (the hull keeps the equivalent body of revolution of
    its bare sections).  Returns a list of (S_pair, kappa [-], chord [m], mean exposed span [m]).

    References
    ----------
    DNV-RP-H103 (2011) table A-2; Pitts, W. C., Nielsen, J. N. & Kaattari, G. E. (1957) NACA
    Report 1307 (slender-body interference factors on 3D wing lift); Newman (1977) sec. 4.13
    (finned circle).
    """
    from stripcoef.sections.added_mass import plate_chordwise_factor

    groups: dict = {}
    for f in shares:
        groups.setdefault((f.pair, f.n), []).append(f)
    out = []
    for (_, n), rows in groups.items():
        inc = [np.zeros_like(m) for m in mats]
        chord = span_area = 0.0
        for f in rows:
            inc[f.hull][f.row, n, n] += f.increment
            w = f.coverage * strips.dx[f.strip]
            chord += w
            span_area += w * f.exposed_span
        if chord <= 0 or span_area <= 0:
            continue
        span = span_area / chord
        out.append((strip_added_mass(strips, inc, center),
                    plate_chordwise_factor(2.0 * span, chord), chord, span))
    return out


_GAUSS3 = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 18.0)


def entrained_water(strips: Strips, rho: float, about) -> np.ndarray:
    r"""Added inertia of the water carried in through-holes and duct interiors [SI].

    .. math:: M = \rho\sum_{strips}\sum_g w_g\, c\, d\, dx\ [I,\ -S(r_g)]^T (I - aa^T) [I,\ -S(r_g)]

    with 3 Gauss points :math:`r_g` along the hole's axis (exact for the quadratic moments).
    ``rho`` [kg/m^3], chord c, depth d, dx and ``about`` [m]; returns [kg, kg m, kg m^2].

    References
    ----------
    See module docstring (:math:`M_{hole}`; Ferreira et al. 2009, sec. IV.C and eq. 40).
    """
    about = np.asarray(about, float)
    total = np.zeros((6, 6))
    axes = {"x": np.array([1.0, 0, 0]), "y": np.array([0, 1.0, 0]), "z": np.array([0, 0, 1.0])}
    for h in strips.holes:
        a = axes[h.axis]
        proj = np.eye(3) - np.outer(a, a)
        dm = rho * h.chord * h.depth * strips.dx[h.index]
        for xi, w in zip(*_GAUSS3):
            for k, i in enumerate(h.index):
                r = np.array([strips.x[i], h.y[k], h.z[k]]) - about + a * xi * 0.5 * h.depth[k]
                G = np.hstack([np.eye(3), -skew(r)])
                total += w * dm[k] * G.T @ proj @ G
    return total


def _panel_count(value, default, key: str):
    """A panel count (``key``: correction_panels or section_panels): ``None`` -> ``default``,
    else an int >= 8."""
    if value is None:
        return None if default is None else int(default)
    try:
        n = int(value)
    except (TypeError, ValueError):
        n = None
    if n is None or n != value or n < 8:
        raise InputError(f"invalid number of {key.replace('_', ' ')}", key=key,
                         value=value, expected="an integer >= 8")
    return n


def added_mass(strips: Strips, rho: float, *, about, volume: float, center,
               corrections: bool = True, correction_panels: int | None = None,
               section_panels: int | None = None):
    r"""Full 6x6 M_A about ``about``: strips (+ 3D corrections) + axial + entrained water.

    With ``corrections`` (the default) the strip matrix about the centre of buoyancy gets
    the axisymmetric-BEM corrections of :mod:`stripcoef.hull.corrections` (per-direction
    equivalent bodies of revolution: end effects, sway-yaw / heave-pitch couplings and the
    axial added mass); fin pairs on a circular hull are taken out of the hull's equivalent body,
    and their share of sway, heave, pitch and yaw is the 3D thin-sheet solution where it applies
    (radial rectangular fins in cruciforms or opposite pairs on a hull of revolution:
    :func:`sheet_fin_shares`), else the strip share scaled by the exposed pair's
    rectangular-plate factor (:func:`fin_share_corrections`).  Without them it is pure strip theory plus the axial term
    :math:`k_1\rho V` of the equal-length, equal-volume spheroid (Lamb; Ferreira et al. 2009 eq. 36).

    .. math:: M_A = H^T\big(M_A^{strip}(+\text{corr.}) + k_1\rho V\,e_1e_1^T\big)H + M_{hole}

    (H moves the matrix from ``center`` to ``about``; :func:`stripcoef.conventions.transform_matrix`;
    the k_1 term only without corrections). ``rho`` [kg/m^3], ``volume`` [m^3], ``about``
    and ``center`` [m]. ``correction_panels``: meridian panels of the corrections'
    axisymmetric solves (default :data:`stripcoef.hull.corrections.DEFAULT_PANELS`);
    ``section_panels``: panels per polygon section of the 2D panel method (default adaptive,
    :func:`stripcoef.sections.panel.discretise`).

    Returns (M_A [kg, kg m, kg m^2], info) where info lists the factors used.

    References
    ----------
    See module docstring; Lamb (1932), sec. 373 (k_1); Fossen (2011), sec. 7.5.3 (transform).
    """
    from stripcoef.hull.corrections import (DEFAULT_PANELS, apply_corrections, fin_sheet_3d,
                                            hull_corrections)
    from stripcoef.hull.members import member_added_mass

    panels = _panel_count(correction_panels, DEFAULT_PANELS, "correction_panels")
    section_panels = _panel_count(section_panels, None, "section_panels")
    center = np.asarray(center, float)
    mats, shares = _sections_and_fin_shares(strips, rho, section_panels)
    strip = strip_added_mass(strips, mats, center)
    _, _, k1, ld = end_correction_factors(strips.length, volume)
    info = {"equivalent_spheroid_L_over_D": float(ld)}
    if section_panels is not None:
        info["section_panels"] = section_panels
    if corrections:
        per_strip = np.zeros((strips.n, 3, 3))
        for p, m in zip(strips.parts, mats):
            np.add.at(per_strip, p.index, m * p.coverage[:, None, None])
        per_member = member_added_mass(strips, rho, center, panels=panels,
                                       section_panels=section_panels,
                                       joint=mats[0] if len(mats) == 1 else None)
        if per_member is None:
            # fin pairs on a circular hull: the hull by its bare sections' equivalent body, the
            # fins' shares by the 3D thin sheet where it applies (hull.corrections.fin_sheet_3d),
            # else by the rectangular plate's 3D factor (fin_share_corrections)
            fin_parts = fin_share_corrections(strips, mats, shares, center)
            sheet = fin_sheet_3d(strips, rho) if fin_parts else None
            folded = None
            if fin_parts and sheet is None:   # the finned equivalent body: the shares' 3D
                folded = apply_corrections(strip, hull_corrections(        # distribution
                    strips, rho=rho, center=center, section_added_mass=per_strip, panels=panels,
                    axial=False))
            for f in shares:
                per_strip[f.strip, f.n, f.n] -= f.increment
            corr = hull_corrections(strips, rho=rho, center=center, section_added_mass=per_strip,
                                    panels=panels)
            bare = apply_corrections(strip - sum(sp for sp, *_ in fin_parts), corr)
            scale, axial, method = corr.scale, corr.axial_added_mass, corr.method
            if sheet is not None:
                strip = sheet_fin_shares(bare, sheet, fin_parts, center)
                method += ("; fins' shares of sway, heave, pitch and yaw by the 3D thin-sheet "
                           "panel method (stripcoef.hull.finsheet.fins_added_mass)")
            else:
                strip = distribute_fin_shares(bare, folded, fin_parts)
                if fin_parts:
                    method += ("; fin pairs' shares by the rectangular plate's 3D factor "
                               "(DNV-RP-H103 table A-2, stripcoef.assembly.added_mass."
                               "fin_share_corrections)")
        else:                           # several members / junctions: corrected one by one
            corrected, parts_info = per_member
            info["members"] = sum(1 for e in parts_info if e["kind"] == "member")
            info["junction_pieces"] = sum(1 for e in parts_info if e["kind"] == "junction")
            diag = np.diag(strip)
            scale = np.where(diag > 0, np.diag(corrected) / np.where(diag > 0, diag, 1.0), 1.0)
            axial = float(corrected[0, 0])
            method = ("per-member axisymmetric BEM of the added-mass-equivalent bodies "
                      "of revolution (stripcoef.hull.members); end_correction_* are the "
                      "effective ratios corrected/strip")
            strip = corrected
        info.update({"end_correction_sway": float(scale[1]), "end_correction_heave": float(scale[2]),
                     "end_correction_pitch": float(scale[4]), "end_correction_yaw": float(scale[5]),
                     "axial_added_mass": float(axial),
                     "correction_method": method, "correction_panels": panels})
    else:
        strip[0, 0] += k1 * rho * volume
        info.update({"k1": float(k1), "axial_added_mass": float(k1 * rho * volume),
                     "correction_method": "none (pure strip theory); axial k1 rho V of the "
                                          "equivalent spheroid"})
    total = transform_matrix(strip, from_point=center, to_point=about)
    total = total + entrained_water(strips, rho, about)
    return 0.5 * (total + total.T), info


#: ``auto`` keeps strip theory for a body at least this slender, L / max(B, H) [-].
#: [assumption] strip theory is the slender-body limit (Newman 1977, sec. 7.4): each section's
#: flow is two-dimensional except within about one cross dimension of the ends, so at L / B = 5
#: the 3D ends are at most 40 % of the length, and the 3D corrections (built on equivalent
#: bodies of revolution, stripcoef.hull.corrections) account for them.  Not fitted to any
#: benchmark shape.
SLENDER_RATIO = 5.0


def _mesh_of(vehicle):
    """The one closed mesh of a vehicle made of a mesh alone (Vehicle.from_mesh), else None."""
    from stripcoef.geometry.mesh import MeshBody

    bodies = getattr(vehicle, "bodies", [])
    if (getattr(vehicle, "hull", None) is None and len(bodies) == 1
            and isinstance(bodies[0], MeshBody) and not getattr(vehicle, "holes", [])):
        return bodies[0]
    return None


def panel_surface(vehicle, panels: int):
    r"""The closed surface the panel method solves on with ``panels`` panels (N): a mesh
    vehicle's body (:class:`~stripcoef.geometry.mesh.MeshBody`, its bodies united by the
    panel method), else the vehicle file's parts united
    (:func:`stripcoef.geometry.surface.vehicle_surface`) at the finest tessellation that
    :func:`stripcoef.hull.panels.panel_levels` refines instead of coarsening: at most N/4
    faces with at least 16 sides a circle (its two levels then one family: N/4 panels by
    longest-edge bisection and that split in four), else at most
    :data:`~stripcoef.hull.panels.MAX_PANELS` / 2.5 faces (both levels refine the surface
    itself).  Coarsening a surface of thin members (frame plates,
    duct walls) by vertex clustering collapses them; refining keeps the geometry exactly."""
    body = _mesh_of(vehicle)
    if body is not None:
        return body
    from stripcoef.geometry.surface import coarsest_within, vehicle_surface
    from stripcoef.hull.panels import MAX_PANELS

    if not 50 <= int(panels) <= MAX_PANELS:     # refused by the panel method: build no ladder
        return vehicle_surface(vehicle)
    return coarsest_within(vehicle, ((int(panels) // 4, 16), (int(MAX_PANELS / 2.5), 12)))


def panel_vehicle_added_mass(vehicle, rho: float, about, panels=None, symmetrise=None,
                             mirrors=()):
    r"""M_A [kg, kg m, kg m^2] of a vehicle (a mesh, or a vehicle file's united surface:
    :func:`panel_surface`) by the 3D panel method about ``about`` [m]
    (:func:`stripcoef.hull.panels.panel_added_mass`: the unbounded-fluid Neumann problem,
    :math:`A_{ij} = -\rho\iint_S \phi_j n_i\,dS`, Newman 1977 eq. 4.148), its info and the
    estimated error of each term [kg, kg m, kg m^2] (a :class:`ModelWarning` when a term's
    estimate, the extrapolation's step plus its last change, exceeds
    :data:`stripcoef.hull.panels.ERROR_TOLERANCE` of the diagonal scale, naming the panel
    count that resolves it; with four levels or more the error returned is the wider band
    of Eça & Hoekstra's least squares, :func:`stripcoef.hull.panel_error.least_squares_error`).  ``symmetrise``: a function applied to M_A and its error before
    the check (the body's mirror planes, :func:`stripcoef.assembly.symmetry.enforce_symmetry`);
    ``mirrors``: those planes (``x``, ``y``, ``z`` through ``about``), which shrink the solve
    to half, a quarter or an eighth of the body with image panels (the ``mirrors`` of
    :func:`~stripcoef.hull.panels.panel_added_mass`)."""
    from stripcoef.hull.panels import (DEFAULT_PANELS, ERROR_TOLERANCE, MAX_PANELS,
                                       panel_added_mass, relative_error)

    n = _panel_count(panels, DEFAULT_PANELS, "added_mass_panels")
    body = panel_surface(vehicle, n)
    source = getattr(vehicle, "source", "") or ""
    try:
        m_a, info = panel_added_mass(body, rho=rho, about=about, panels=n, source=source,
                                     mirrors=mirrors)
    except InputError as exc:
        raise (exc.with_key("added_mass_panels") if exc.key == "panels" else exc) from None
    error = info["error"]
    estimate = info.get("estimate")
    estimate = error if estimate is None else estimate
    if symmetrise is not None:
        m_a, error, estimate = symmetrise(m_a), symmetrise(error), symmetrise(estimate)
    rel = relative_error(m_a, error, info.get("length"))
    # the warning reads the estimate (the step plus the last change), the band shown the
    # error (four levels or more: Eça & Hoekstra's uncertainty; stripcoef.hull.panel_error)
    warn = relative_error(m_a, estimate, info.get("length"))
    counts = "/".join(str(c) for c in info["panels"])
    if warn.max() > ERROR_TOLERANCE:
        warnings.warn(f"{source or vehicle.name}: " + unconverged_message(
            warn, info, n, ERROR_TOLERANCE, MAX_PANELS), ModelWarning, stacklevel=3)
    levels = len(info["panels"])
    how = ("error: Eça & Hoekstra's least-squares uncertainty of the levels; warned where "
           "the extrapolation's step plus its last change exceeds "
           f"{100 * ERROR_TOLERANCE:.0f} %)" if levels >= 4
           else "error: the extrapolation's step plus its last change)" if levels == 3
           else "error: grid convergence index)")
    return m_a, {"added_mass_method": "3D panel method (stripcoef.hull.panels, "
                                      f"{info['family']}, Richardson from {counts} panels, "
                                      + how,
                 "added_mass_panels": int(info["panels"][-1]),
                 "added_mass_panel_levels": tuple(int(c) for c in info["panels"]),
                 "added_mass_converged": bool(warn.max() <= ERROR_TOLERANCE),
                 "added_mass_error_max": float(rel.max())}, error


#: Most terms a not-converged warning names (the worst first; the rest counted) [-].
WARNED_TERMS = 6


def unconverged_message(rel, info, panels: int, tolerance: float, max_panels: int) -> str:
    """The not-converged warning of the panel method (:func:`panel_vehicle_added_mass`): every
    upper-triangle term whose estimated error ``rel`` (6x6, over the diagonal scale; three
    levels or more: the extrapolation's step plus its last change,
    :func:`stripcoef.hull.panels.relative_error`) exceeds ``tolerance`` [-], the worst first
    (at most :data:`WARNED_TERMS` named), the levels solved, and the option or command that
    resolves it: more panels (twice those asked, or four times once the refinement went on to
    about twice; at most ``max_panels``), else a look at the mesh or a BEM cross-check; the
    remesher where the input's two levels were used."""
    from stripcoef.conventions import DOF

    iu = np.triu_indices(6)
    over = [(float(rel[i, j]), int(i), int(j)) for i, j in zip(*iu) if rel[i, j] > tolerance]
    over.sort(reverse=True)
    named = ", ".join(f"M_A[{DOF[i]}, {DOF[j]}] {100 * r:.1f} %" for r, i, j in
                      over[:WARNED_TERMS])
    if len(over) > WARNED_TERMS:
        named += f" and {len(over) - WARNED_TERMS} more"
    counts = "/".join(str(c) for c in info["panels"])
    finest = int(info["panels"][-1])
    more = min((2 if finest < 1.5 * panels else 4) * panels, max_panels)
    fix = (f"raise added_mass_panels to {more} (--added-mass-panels {more})" if more > panels
           else "check the mesh (stripcoef mesh FILE) or cross-check with the BEM "
                "(stripcoef compare FILE)")
    # (not where the input's coarsened levels are kept in every install: fine_smooth_input)
    if info["family"].startswith("refined") and not info.get("fine_smooth"):
        fix += ("; install the remesher for three uniform levels (pip install "
                "'stripcoef[remesh]')")
    what = ("the extrapolation's step plus its last change" if len(info["panels"]) >= 3
            else "estimated error")
    return (f"the 3D panel method has not converged: {what} over the diagonal scale "
            f"of {named} (tolerance {100 * tolerance:.0f} %; panels {counts}); {fix}")
