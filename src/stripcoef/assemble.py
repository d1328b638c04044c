r"""Assembly: strips + sections + hull-level formulas -> :class:`~stripcoef.model.HydroModel`.

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
Then the 3D end correction (:func:`stripcoef.hull.end_correction_factors`), the axial
added mass :math:`k_1\rho V` of the equivalent spheroid (seed 002, eq. 36), and the water
carried in through-holes and ducts

.. math:: M_{hole} = \rho \int [I,\ -S(r)]^T (I - a a^T) [I,\ -S(r)]\, dV

(the water's velocity component across the hole axis ``a`` moves with the body; along
the axis it passes freely: seed 002, sec. IV.C).

Damping: see :func:`_damping` (cross-flow principle, friction lines, power-law split).
"""

from __future__ import annotations

import warnings

import numpy as np

from stripcoef.conventions import skew, transform_matrix
from stripcoef.errors import InputError, ModelWarning
from stripcoef.hull import end_correction_factors, power_law_split
from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.sections import drag as sdrag
from stripcoef.sections import section_added_mass, section_drag
from stripcoef.strips import Strips


# ---------------------------------------------------------------------------
# Volumes and mass properties
# ---------------------------------------------------------------------------

def _hole_water(strips: Strips):
    """Per hole-cut: water volume per strip [m^3] (only holes cut through displaced parts).

    dV = c d dx, chord c [m], depth d [m], strip width dx [m]; [assumption] prismatic
    hole per strip (seed 002, sec. IV.C approximates holes by cylinders).
    """
    return [(h, h.chord * h.depth * strips.dx[h.index]) for h in strips.holes]


def displaced_volume(strips: Strips):
    r"""Displaced volume and centre of buoyancy from the strips.

    .. math:: V = \sum_{parts} A\,dx - \sum_{holes} c\,d\,dx,\qquad
              r_B = \frac{1}{V}\Big(\sum A\,dx\,(x, y_c, z_c) - \sum c\,d\,dx\,(x, y_h, z_h)\Big)

    Part areas A [m^2], hole chord c and depth d [m], strip widths dx [m]; centroids [m].

    Returns
    -------
    (float, ndarray)
        V [m^3], r_B [m] in body axes

    References
    ----------
    Midpoint-rule volume and first moment of the strips (Newman 1977, sec. 7.4 strip
    slicing); Fossen (2011), sec. 4.1 (B and r_B).
    """
    vol = 0.0
    mom = np.zeros(3)
    for p in strips.parts:
        dv = p.area * strips.width(p)
        vol += dv.sum()
        mom += np.array([(dv * strips.x[p.index]).sum(), (dv * p.y).sum(), (dv * p.z).sum()])
    for h, dv in _hole_water(strips):
        if not h.in_hull:
            continue
        vol -= dv.sum()
        mom -= np.array([(dv * strips.x[h.index]).sum(), (dv * h.y).sum(), (dv * h.z).sum()])
    if vol <= 0:
        raise InputError("the body has no displaced volume", key="geometry", value=vol,
                         expected="a volume > 0")
    return float(vol), mom / vol


def _density_of(part, x, vehicle, rho_default):
    """Density per strip of a part from the vehicle's zones (last matching zone wins)."""
    dens = np.full(x.size, rho_default)
    for z in vehicle.mass.zones:
        if z.bodies is not None and part.name not in z.bodies:
            continue
        inside = (x >= z.x_aft) & (x <= z.x_fwd)
        dens[inside] = z.density
    return dens


def mass_properties(strips: Strips, vehicle, rho_fluid: float, volume: float, cb):
    r"""Mass [kg], centre of gravity [m] and inertia tensor about the CG [kg m^2].

    Directly from the vehicle file when given; otherwise from density zones (seed 002,
    Table I and eq. 34) or, without either, a uniform body of the fluid's density
    (neutrally buoyant). The inertia of the strips is

    .. math:: I = \sum \rho_i A_i\,dx\,(|r_i|^2 I - r_i r_i^T) +
              \rho_i\,dx\,\mathrm{diag}(i_{yy}+i_{zz},\ i_{zz} + A\,dx^2/12,\
              i_{yy} + A\,dx^2/12)

    with :math:`r_i` from the CG (parallel-axis theorem, Fossen 2011 eq. 3.37).
    """
    spec = vehicle.mass if vehicle is not None else None
    have_mass = spec is not None and spec.mass is not None
    zones = spec is not None and bool(spec.zones)
    rho_default = rho_fluid
    if spec is not None and spec.default_density is not None:
        rho_default = spec.default_density
    if have_mass and spec.center_of_gravity is not None and spec.inertia is not None:
        return spec.mass, np.asarray(spec.center_of_gravity, float), np.asarray(spec.inertia)
    # distribute mass over the strips
    elems = []  # (dm, r, second-moment diag contribution)
    for p in strips.parts:
        xs = strips.x[p.index]
        dx = strips.width(p)
        dens = _density_of(p, xs, vehicle, rho_default) if zones else np.full(xs.size, 1.0)
        dm = dens * p.area * dx
        elems.append((dm, np.column_stack([xs, p.y, p.z]),
                      np.column_stack([dens * dx * (p.iyy + p.izz),
                                       dens * dx * p.izz + dm * dx**2 / 12.0,
                                       dens * dx * p.iyy + dm * dx**2 / 12.0])))
    for h, dv in _hole_water(strips):
        if not h.in_hull:
            continue
        xs = strips.x[h.index]
        if zones:
            hull = next((p for p in strips.parts if p.role == "hull"), None)
            dens = _density_of(hull, xs, vehicle, rho_default) if hull is not None \
                else np.full(xs.size, rho_default)
        else:
            dens = np.ones(xs.size)
        elems.append((-dens * dv, np.column_stack([xs, h.y, h.z]), np.zeros((xs.size, 3))))
    dm = np.concatenate([e[0] for e in elems])
    r = np.concatenate([e[1] for e in elems])
    sec = np.concatenate([e[2] for e in elems])
    total = dm.sum()
    if total <= 0:
        raise InputError("density zones give no mass", key="mass.zones", value=float(total),
                         expected="zones with positive density over the body")
    scale = 1.0
    if have_mass:
        scale = spec.mass / total           # uniform distribution scaled to the given mass
    elif not zones:
        scale = rho_fluid                   # neutrally buoyant, uniform
    dm = dm * scale
    sec = sec * scale
    mass = float(dm.sum())
    cg = (dm[:, None] * r).sum(axis=0) / mass
    if have_mass and spec.center_of_gravity is not None:
        cg = np.asarray(spec.center_of_gravity, float)
    d = r - cg
    inertia = np.zeros((3, 3))
    inertia += np.einsum("i,ij,ik->jk", dm, d, d) * -1.0
    inertia += np.eye(3) * (dm * (d**2).sum(axis=1)).sum()
    inertia += np.diag(sec.sum(axis=0))
    if have_mass and spec.inertia is not None:
        inertia = spec.inertia
    return mass, cg, inertia


# ---------------------------------------------------------------------------
# Added mass
# ---------------------------------------------------------------------------

def _strip_operator(xrel):
    """L(X) for an array of X: (n, 3, 6).

    [v + X r, w - X q, p] = L(X) nu, X = x - x_0 [m]; L is [-] in its 1 entries and [m]
    in the X entries. See module docstring (Newman 1977, sec. 7.4).
    """
    n = xrel.size
    L = np.zeros((n, 3, 6))
    L[:, 0, 1] = 1.0
    L[:, 0, 5] = xrel
    L[:, 1, 2] = 1.0
    L[:, 1, 4] = -xrel
    L[:, 2, 3] = 1.0
    return L


def _hole_width_reduction(strips: Strips, part):
    """Per strip of a hull part: open width of holes along z (c_z) and along y (c_y) [m].

    c_z = sum of the chords [m] of the in-hull holes with axis z in the strip (same for y).
    [assumption] widths add (holes do not overlap); used by seed 002, eq. 40 style
    reductions in :func:`section_matrices` and :func:`_damping`.
    """
    cz = np.zeros(part.index.size)
    cy = np.zeros(part.index.size)
    if part.role != "hull":
        return cy, cz
    pos = {int(i): k for k, i in enumerate(part.index)}
    for h in strips.holes:
        if not h.in_hull:
            continue
        for i, c in zip(h.index, h.chord):
            k = pos.get(int(i))
            if k is None:
                continue
            if h.axis == "z":
                cz[k] += c
            elif h.axis == "y":
                cy[k] += c
    return cy, cz


def _combine_fins(strips: Strips, mats: list, rho: float) -> None:
    r"""Replace hull + fin-pair sums by the finned-circle section where it applies (in place).

    Where a circular hull section carries a symmetric pair of fins (both spanning along z,
    mirrored about the hull axis, or both along y) whose roots touch the hull, the section
    normal to the fins is the circle with fins of tip radius a:

    .. math:: m_n = \rho\pi(a^2 - R^2 + R^4/a^2),\qquad m_{44} = \tfrac{2}{\pi}\rho a^4

    (Blevins 1979 table 14-2; Prestero 2001 sec. 3.4) instead of the circle plus two
    isolated plates, which ignores their interaction.  A cruciform section gets both pairs'
    normal terms; its roll term is then the sum of the two pairs' (an approximation).

    Hull radius R and tip radius a [m], rho [kg/m^3]; m_n [kg/m], m_44 [kg m] per unit
    length, written into ``mats`` (per part, (k, 3, 3) [kg/m, kg, kg m]).
    """
    from stripcoef.sections.added_mass import circle_with_fins

    hulls = [(k, p) for k, p in enumerate(strips.parts) if p.role == "hull" and p.shape == "ellipse"]
    fins = [(k, p) for k, p in enumerate(strips.parts) if p.role == "fin"]
    if not hulls or len(fins) < 2:
        return
    for kh, hull in hulls:
        pos_h = {int(i): j for j, i in enumerate(hull.index)}
        for a_i in range(len(fins)):
            for b_i in range(a_i + 1, len(fins)):
                (ka, fa), (kb, fb) = fins[a_i], fins[b_i]
                common = np.intersect1d(np.intersect1d(fa.index, fb.index), hull.index)
                for s_idx in common:
                    ia = int(np.nonzero(fa.index == s_idx)[0][0])
                    ib = int(np.nonzero(fb.index == s_idx)[0][0])
                    ih = pos_h[int(s_idx)]
                    b, h = hull.half_breadth[ih], hull.half_height[ih]
                    if not np.isclose(b, h, rtol=1e-6):
                        continue
                    vertical = fa.half_height[ia] > fa.half_breadth[ia]
                    if vertical != (fb.half_height[ib] > fb.half_breadth[ib]):
                        continue
                    if vertical:
                        off_a, off_b = fa.z[ia] - hull.z[ih], fb.z[ib] - hull.z[ih]
                        lat_ok = np.isclose(fa.y[ia], hull.y[ih]) and np.isclose(fb.y[ib], hull.y[ih])
                        half_a, half_b = fa.half_height[ia], fb.half_height[ib]
                        n = 0          # sway is normal to vertical fins
                    else:
                        off_a, off_b = fa.y[ia] - hull.y[ih], fb.y[ib] - hull.y[ih]
                        lat_ok = np.isclose(fa.z[ia], hull.z[ih]) and np.isclose(fb.z[ib], hull.z[ih])
                        half_a, half_b = fa.half_breadth[ia], fb.half_breadth[ib]
                        n = 1          # heave is normal to horizontal fins
                    tip_a, tip_b = abs(off_a) + half_a, abs(off_b) + half_b
                    touching = (abs(off_a) - half_a <= b * (1 + 1e-6)
                                and abs(off_b) - half_b <= b * (1 + 1e-6))
                    if not (lat_ok and off_a * off_b < 0 and np.isclose(tip_a, tip_b, rtol=1e-6)
                            and touching and tip_a > b):
                        continue
                    m_n, m44 = circle_with_fins(b, tip_a, rho=rho)
                    mats[kh][ih, n, n] = m_n
                    for k, i in ((ka, ia), (kb, ib)):
                        mats[k][i, n, n] = 0.0
                        mats[k][i, 2, 2] = 0.5 * m44


def section_matrices(strips: Strips, rho: float, panels: int | None = None) -> list:
    r"""Per part, the (k, 3, 3) 2D added mass about the part's centre [kg/m, kg, kg m], with
    fin pairs combined (:func:`_combine_fins`) and the open width of holes removed.

    .. math:: m_{33} \leftarrow m_{33}\,(1 - c_z/2b)^2,\qquad m_{22} \leftarrow m_{22}\,(1 - c_y/2h)^2

    with open hole widths c_z, c_y [m] (:func:`_hole_width_reduction`), half-breadth b and
    half-height h [m]; ``rho`` [kg/m^3]. Sections: :func:`stripcoef.sections.section_added_mass`
    (``panels``: panels per polygon section, default adaptive).

    References
    ----------
    Holes pass heave (sway) flow: seed 002, eq. 40; the squared open-width factor is an
    [assumption] (added mass ~ width^2, as for a plate, DNV-RP-C205 table A-1).
    """
    mats = [section_added_mass(p, rho, panels).copy() for p in strips.parts]
    _combine_fins(strips, mats, rho)
    for p, m in zip(strips.parts, mats):
        cy, cz = _hole_width_reduction(strips, p)
        if np.any(cz > 0):   # heave passes through vertical holes (seed 002, eq. 40)
            m[:, 1, 1] *= np.clip(1.0 - cz / (2 * p.half_breadth), 0.0, 1.0) ** 2
        if np.any(cy > 0):   # sway passes through horizontal holes
            m[:, 0, 0] *= np.clip(1.0 - cy / (2 * p.half_height), 0.0, 1.0) ** 2
    return mats


def shift_section_matrices(m, dy, dz) -> np.ndarray:
    r"""2D section matrices (sway, heave, roll) moved to a reference point offset by
    (dy, dz) [m] from their own:

    .. math:: m' = H_2^T m H_2,\qquad
              H_2 = \begin{bmatrix}1&0&-\Delta z\\0&1&\Delta y\\0&0&1\end{bmatrix}

    (a rigid roll p about the new point moves the section's own point by
    :math:`(-\Delta z\,p, \Delta y\,p)`; Fossen 2011, sec. 7.5.3, in 2D).  ``m`` (..., 3, 3)
    [kg/m, kg, kg m], ``dy``, ``dz`` broadcasting over its leading axes; returns the same
    shape.
    """
    dy, dz = np.broadcast_arrays(np.asarray(dy, dtype=float), np.asarray(dz, dtype=float))
    h2 = np.zeros(dy.shape + (3, 3))
    h2[..., 0, 0] = h2[..., 1, 1] = h2[..., 2, 2] = 1.0
    h2[..., 0, 2] = -dz
    h2[..., 1, 2] = dy
    return np.einsum("...ji,...jl,...lm->...im", h2, m, h2)


def strip_added_mass(strips: Strips, rho: float, about, mats=None) -> np.ndarray:
    r"""Pure strip-theory 6x6 added mass about point ``about`` (no 3D corrections) [SI].

    .. math:: M_A^{strip} = \sum_{parts}\sum_k dx_k\, L(X_k)^T H_2^T m_k H_2\, L(X_k),
              \quad H_2 = \begin{bmatrix}1&0&-\Delta z\\0&1&\Delta y\\0&0&1\end{bmatrix}

    ``mats`` are the parts' section matrices [kg/m, kg, kg m] (:func:`section_matrices`;
    computed if omitted); ``rho`` [kg/m^3]; ``about`` [m]; strip widths dx [m]. Returns M_A
    [kg, kg m, kg m^2].

    References
    ----------
    See module docstring (Newman 1977, sec. 7.4; Fossen 2011, sec. 6.3.3).
    """
    x0, y0, z0 = about
    total = np.zeros((6, 6))
    if mats is None:
        mats = section_matrices(strips, rho)
    for p, m in zip(strips.parts, mats):
        m = shift_section_matrices(m, p.y - y0, p.z - z0)
        L = _strip_operator(strips.x[p.index] - x0)
        total += np.einsum("k,kji,kjl,klm->im", strips.width(p), L, m, L)
    return total


_GAUSS3 = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 18.0)


def entrained_water(strips: Strips, rho: float, about) -> np.ndarray:
    r"""Added inertia of the water carried in through-holes and duct interiors [SI].

    .. math:: M = \rho\sum_{strips}\sum_g w_g\, c\, d\, dx\ [I,\ -S(r_g)]^T (I - aa^T) [I,\ -S(r_g)]

    with 3 Gauss points :math:`r_g` along the hole's axis (exact for the quadratic moments).
    ``rho`` [kg/m^3], chord c, depth d, dx and ``about`` [m]; returns [kg, kg m, kg m^2].

    References
    ----------
    See module docstring (:math:`M_{hole}`; seed 002, sec. IV.C and eq. 40).
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
    the axisymmetric-BEM corrections of :mod:`stripcoef.corrections` (per-direction
    equivalent bodies of revolution: end effects, sway-yaw / heave-pitch couplings and the
    axial added mass).  Without them it is pure strip theory plus the axial term
    :math:`k_1\rho V` of the equal-length, equal-volume spheroid (Lamb; seed 002 eq. 36).

    .. math:: M_A = H^T\big(M_A^{strip}(+\text{corr.}) + k_1\rho V\,e_1e_1^T\big)H + M_{hole}

    (H moves the matrix from ``center`` to ``about``; :func:`stripcoef.conventions.transform_matrix`;
    the k_1 term only without corrections). ``rho`` [kg/m^3], ``volume`` [m^3], ``about``
    and ``center`` [m]. ``correction_panels``: meridian panels of the corrections'
    axisymmetric solves (default :data:`stripcoef.corrections.DEFAULT_PANELS`);
    ``section_panels``: panels per polygon section of the 2D panel method (default adaptive,
    :func:`stripcoef.sections.panel.discretise`).

    Returns (M_A [kg, kg m, kg m^2], info) where info lists the factors used.

    References
    ----------
    See module docstring; Lamb (1932), sec. 373 (k_1); Fossen (2011), sec. 7.5.3 (transform).
    """
    from stripcoef.corrections import DEFAULT_PANELS, apply_corrections, hull_corrections
    from stripcoef.members import member_added_mass

    panels = _panel_count(correction_panels, DEFAULT_PANELS, "correction_panels")
    section_panels = _panel_count(section_panels, None, "section_panels")
    center = np.asarray(center, float)
    mats = section_matrices(strips, rho, section_panels)
    strip = strip_added_mass(strips, rho, center, mats)
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
            corr = hull_corrections(strips, rho=rho, center=center, section_added_mass=per_strip,
                                    panels=panels)
            strip = apply_corrections(strip, corr)
        else:                           # several members / junctions: corrected one by one
            corrected, parts_info = per_member
            info["members"] = sum(1 for e in parts_info if e["kind"] == "member")
            info["junction_pieces"] = sum(1 for e in parts_info if e["kind"] == "junction")
            diag = np.diag(strip)
            eff = np.where(diag > 0, np.diag(corrected) / np.where(diag > 0, diag, 1.0), 1.0)
            corr = {"scale": eff, "axial_added_mass": float(corrected[0, 0]),
                    "method": "per-member axisymmetric BEM of the added-mass-equivalent bodies "
                              "of revolution (stripcoef.members); end_correction_* are the "
                              "effective ratios corrected/strip"}
            strip = corrected
        scale = corr["scale"]
        info.update({"end_correction_sway": float(scale[1]), "end_correction_heave": float(scale[2]),
                     "end_correction_pitch": float(scale[4]), "end_correction_yaw": float(scale[5]),
                     "axial_added_mass": float(corr["axial_added_mass"]),
                     "correction_method": corr["method"], "correction_panels": panels})
    else:
        strip[0, 0] += k1 * rho * volume
        info.update({"k1": float(k1), "axial_added_mass": float(k1 * rho * volume),
                     "correction_method": "none (pure strip theory); axial k1 rho V of the "
                                          "equivalent spheroid"})
    total = transform_matrix(strip, from_point=center, to_point=about)
    total = total + entrained_water(strips, rho, about)
    return 0.5 * (total + total.T), info


# ---------------------------------------------------------------------------
# Damping
# ---------------------------------------------------------------------------

def _local_exponent(fn, *re):
    """n_k = 2 + d ln C_D,k / d ln Re_k (power-law exponent of the drag force in speed).

    ``fn(Re_1, Re_2, ...)`` -> (C_D,1, C_D,2, ...) [-], each C_D,k depending on Re_k only
    (so one call at Re*1.1 and one at Re/1.1 serve every k); ``re``: the Re_k [-]; returns
    the n_k [-] (a tuple) by a central difference over Re*1.1^+-1.
    From F = 1/2 rho C_D(Re) A V^2 with Re proportional to V (Hoerner 1965, ch. 3);
    the split is :func:`stripcoef.hull.power_law_split`.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hi = fn(*(np.asarray(r) * 1.1 for r in re))
        lo = fn(*(np.asarray(r) / 1.1 for r in re))
    return tuple(2.0 + (np.log(np.asarray(h, float)) - np.log(np.asarray(l, float)))
                 / (2.0 * np.log(1.1)) for h, l in zip(hi, lo))


def _perimeter(part):
    r"""Wetted perimeter of each strip's section of a part [m].

    Ellipse: :func:`_ellipse_perimeter`; polygon: sum of edge lengths
    :math:`P = \sum_{rings}\sum_i |p_{i+1} - p_i|` (outer rings and holes: a duct's inner
    wall is wetted too; wetted area for friction drag as in Hoerner 1965, ch. 2), taken from
    the part's ring set :func:`stripcoef.sections.panel.part_rings`, which the section
    solvers share (repeated points, closer than 1e-12 of the ring's size, are dropped
    there); rectangle: P = 4 (b + h), half sizes b, h [m]. Exact geometry (the ellipse:
    Ramanujan's approximation).
    """
    if part.shape == "ellipse":
        return _ellipse_perimeter(part.half_breadth, part.half_height)
    if part.shape == "polygon":
        from stripcoef.sections.panel import part_rings
        if not part.contours:
            return np.zeros(part.index.size)
        rs = part_rings(part)
        return np.bincount(rs.section, rs.perimeters(), part.index.size)
    return 4.0 * (part.half_breadth + part.half_height)


def _ellipse_perimeter(b, h):
    r"""Ramanujan's approximation of an ellipse's perimeter [m] (exact for circles).

    .. math:: P \approx \pi(b + h)\left(1 + \frac{3\lambda}{10 + \sqrt{4 - 3\lambda}}\right),
              \quad \lambda = \left(\frac{b-h}{b+h}\right)^2

    Half-axes b, h [m]. Ramanujan (1914), Quart. J. Math. 45, the second approximation.
    """
    hh = ((b - h) / (b + h)) ** 2
    return np.pi * (b + h) * (1.0 + 3.0 * hh / (10.0 + np.sqrt(4.0 - 3.0 * hh)))


def _damping(strips: Strips, vehicle, rho, nu, speed, about, regime):
    r"""Linear and quadratic damping about ``about`` from the viscous force model.

    Force model (all per element e at r_e, directions k = x, y, z):

    - cross-flow (Hoerner 1965 ch. 3; Fossen 2011 sec. 6.4.3, MSS crossFlowDrag.m):
      :math:`f_k = -\tfrac12\rho\,C_{D,k}(Re)\,\kappa\,h_k\,|V_k|V_k` per unit length, with
      :math:`h_y = 2h`, :math:`h_z = 2b` the part's extent across the flow and
      :math:`Re = U h_k/\nu` at the reference speed U;
    - hull axial friction + form drag: :math:`X = -\tfrac12\rho C_f(Re_L)\,FF\,S_{wet}u|u|`
      (Hoerner form factor), plus blunt-end pressure drag for blunt hulls and appendages;
    - roll: skin friction on the hull's perimeter and the cross-flow of off-axis parts.

    For each DOF j the element's local velocity is :math:`V = [I,\ -S(r)]e_j`; the
    generalized force is :math:`[F;\ r\times F]`.  Each element's force at the reference
    DOF speed, with its power-law exponent n (from the Reynolds dependence of its C_D or
    C_f), is split into linear and quadratic parts by :func:`stripcoef.hull.power_law_split`.
    Reference speeds: U for translations, :math:`\Omega = U/(L/2)` for rotations.
    """
    about = np.asarray(about, float)
    L = strips.length
    omega = speed / (0.5 * L)
    elems = []  # (r, c [kg/m], n): rows (3,) or blocks (k, 3); or ("roll", c, n)
    cond = {"reference_speed": speed, "reference_rate": omega}

    # --- axial: hull friction and form drag
    re_l = speed * L / nu
    cf, reg = sdrag.friction_coefficient(re_l, regime=regime)
    cf_lam = float(sdrag.blasius_cf(re_l))
    cf_turb = float(sdrag.ittc57_cf(re_l))
    (n_f,) = _local_exponent(lambda r: (sdrag.friction_coefficient(r, regime=regime)[0],), re_l)
    n_f = float(n_f)
    cond.update({"reynolds_length": re_l, "regime": reg, "cf_laminar": cf_lam,
                 "cf_turbulent": cf_turb, "cf_used": cf})
    hull_parts = [p for p in strips.parts if p.role == "hull"]
    s_wet = 0.0
    max_d = 0.0
    hull_moment = np.zeros(3)   # volume-weighted centre of all hull parts (friction acts there)
    hull_volume = 0.0
    for p in hull_parts:
        dx = strips.width(p)
        per = _perimeter(p)
        s_wet += float((per * dx).sum())
        area = p.area
        max_d = max(max_d, float(2.0 * np.sqrt(np.max(area) / np.pi)))
        w = area * dx
        hull_volume += float(w.sum())
        hull_moment += np.array([(w * strips.x[p.index]).sum(), (w * p.y).sum(), (w * p.z).sum()])
        # roll friction on the hull perimeter: dK = 1/2 rho Cf per R_eff^3 p|p| dx
        r_eff = np.sqrt(p.half_breadth * p.half_height)
        c_roll = 0.5 * rho * cf * float((per * r_eff**3 * dx).sum())
        elems.append(("roll", c_roll, n_f))
    if hull_parts:
        ff = float(sdrag.hoerner_form_factor(max_d / L))
        c_fric = 0.5 * rho * cf * ff * s_wet
        x_h, y_h, z_h = hull_moment / hull_volume
        elems.append((np.array([x_h, y_h, z_h]), np.array([c_fric, 0, 0]), np.array([n_f, 2, 2])))
        cond.update({"wetted_area": s_wet, "form_factor": ff,
                     "axial_drag_coefficient_wetted": cf * ff,
                     "axial_drag_coefficient_frontal": cf * ff * s_wet / (np.pi * max_d**2 / 4)})
        # blunt ends: pressure drag on the frontal area of a hull that does not close
        hull_body = getattr(vehicle, "hull", None)
        for p in hull_parts:
            a_max = float(np.max(p.area))
            if hull_body is not None:    # exact end sections of the profile
                lo, hi = hull_body.x_extent()
                ends = [hull_body.half_breadth(np.array([x]))[0]
                        * hull_body.half_height(np.array([x]))[0] for x in (lo, hi)]
                end_ratio = float(max(ends)) / float(np.max(p.half_breadth * p.half_height))
            else:                        # mesh: end strips
                end_ratio = max(float(p.area[0]), float(p.area[-1])) / a_max
            if p.index.size and end_ratio > 0.25:   # flat or truncated end
                cd_b = float(sdrag.blunt_cylinder_axial_cd(L / max_d))
                elems.append((np.array([x_h, y_h, z_h]),
                              np.array([0.5 * rho * cd_b * a_max, 0, 0]), np.array([2.0, 2, 2])))
                cond["blunt_hull_cd"] = cd_b
    # --- appendages: axial pressure drag (blunt) on the frontal area
    for p in strips.parts:
        if p.role == "hull":
            continue
        a_front = float(np.max(p.area + p.entrained_area)) if p.shape != "rectangle" else \
            float(np.max(4 * p.half_breadth * p.half_height))
        ld = max(p.length, 1e-9) / max(2 * np.sqrt(a_front / np.pi), 1e-9)
        if p.role == "fin":
            cd_a = 2.0 * cf * p.length * np.max(2 * np.maximum(p.half_breadth, p.half_height)) \
                / max(a_front, 1e-12)   # friction on both faces, per frontal area
        else:
            cd_a = float(sdrag.blunt_cylinder_axial_cd(ld))
        w = p.area * strips.width(p)
        xc = float((w * strips.x[p.index]).sum() / max(w.sum(), 1e-300))
        elems.append((np.array([xc, float(np.mean(p.y)), float(np.mean(p.z))]),
                      np.array([0.5 * rho * cd_a * a_front, 0, 0]), np.array([2.0, 2, 2])))
    # --- cross-flow per strip element
    hull_cd = {}
    for p in strips.parts:
        dx = strips.width(p)
        hy, hz = 2 * p.half_height, 2 * p.half_breadth      # extents across y- and z-flow
        # one Reynolds number per part, on its largest extent across the flow: the regime
        # of a body is set by its main diameter, not by the tapering tips (MSS cylinderDrag.m)
        re_y = np.full(p.index.size, speed * float(np.max(hy)) / nu)
        re_z = np.full(p.index.size, speed * float(np.max(hz)) / nu)
        cd_y, cd_z = section_drag(p, re_y, re_z)
        # cd_y depends on re_y only and cd_z on re_z only (sections.CROSS_FLOW_DRAG)
        n_y, n_z = _local_exponent(lambda ry, rz: section_drag(p, ry, rz), re_y, re_z)
        if p.role != "fin":
            ld_y = max(p.length, 1e-9) / np.maximum(hy, 1e-9)
            ld_z = max(p.length, 1e-9) / np.maximum(hz, 1e-9)
            kap_y = sdrag.cylinder_length_factor(np.clip(ld_y, 2, 100), re_y)
            kap_z = sdrag.cylinder_length_factor(np.clip(ld_z, 2, 100), re_z)
            # short parts (L/D < 2) keep the L/D = 2 factor: documented in theory.md
        else:
            kap_y = kap_z = np.ones(p.index.size)
        cy, cz = _hole_width_reduction(strips, p)
        c_y = 0.5 * rho * cd_y * kap_y * np.maximum(hy - cy, 0.0) * dx
        c_z = 0.5 * rho * cd_z * kap_z * np.maximum(hz - cz, 0.0) * dx
        # one element per strip, appended as one block of rows (r, c, n), each (k, 3)
        k = p.index.size
        elems.append((np.column_stack([strips.x[p.index], p.y, p.z]),
                      np.column_stack([np.zeros(k), c_y, c_z]),
                      np.column_stack([np.full(k, 2.0), n_y, n_z])))
        if p.shape == "rectangle":   # roll of a sharp part about its own centre
            c_self = 0.5 * rho * (cd_z * p.half_breadth**4 + cd_y * p.half_height**4) / 2 * dx
            elems.append(("roll", float(c_self.sum()), 2.0))
        if p.role == "hull":
            mid = int(np.argmax(p.area))
            hull_cd = {"hull_reynolds_diameter": float(re_y[mid]),
                       "hull_crossflow_cd_y": float(cd_y[mid]), "hull_crossflow_cd_z": float(cd_z[mid]),
                       "hull_length_factor": float(np.atleast_1d(kap_y)[mid])}
    cond.update(hull_cd)
    d_lin = np.zeros((6, 6))
    d_quad = np.zeros((6, 6))
    # point elements: single (3,) rows and (k, 3) blocks, stacked in order
    pts = [tuple(np.reshape(np.asarray(v, float), (-1, 3)) for v in e)
           for e in elems if not isinstance(e[0], str)]
    for r, c, n in elems:
        if isinstance(r, str):  # roll-only element: c [kg m^2], local speed ~ R * Omega
            a_hat, b_hat = power_law_split(n)
            d_lin[3, 3] += a_hat * c * omega
            d_quad[3, 3] += b_hat * c
    rel = np.concatenate([p[0] for p in pts]) - about              # (E, 3)
    c = np.concatenate([p[1] for p in pts])                         # (E, 3) [kg/m]
    a_hat, b_hat = power_law_split(np.concatenate([p[2] for p in pts]))   # (E, 3)
    G = np.zeros((rel.shape[0], 3, 6))                              # local velocity per DOF
    G[:, :, :3] = np.eye(3)
    G[:, 0, 4], G[:, 0, 5] = rel[:, 2], -rel[:, 1]                  # -S(r) = S(r)^T
    G[:, 1, 3], G[:, 1, 5] = -rel[:, 2], rel[:, 0]
    G[:, 2, 3], G[:, 2, 4] = rel[:, 1], -rel[:, 0]
    # linear part: a linear force law -k V on the local velocity, k = a_hat c U, so
    # D_L = sum G^T diag(k) G is a congruence and moves between points exactly
    d_lin += np.einsum("eki,ek,ekj->ij", G, a_hat * c * speed, G)
    # quadratic part: pure-motion columns, force g = b_hat c |V| V and its moment r x g
    g = (b_hat * c)[:, :, None] * np.abs(G) * G                     # (E, 3, 6)
    d_quad[:3] += g.sum(axis=0)
    d_quad[3:] += np.cross(rel[:, :, None], g, axisa=1, axisb=1, axisc=1).sum(axis=0)
    return _clean(d_lin), _clean(d_quad), cond


# ---------------------------------------------------------------------------
# The pipeline
# ---------------------------------------------------------------------------

def _clean(m, rel=1e-12):
    """Set round-off below ``rel`` times the largest entry to exactly zero."""
    m = np.array(m, dtype=float)
    m[np.abs(m) < rel * max(float(np.abs(m).max()), 1e-300)] = 0.0
    return m + 0.0   # no negative zeros


def _reference_point(ref, cb, cg):
    if isinstance(ref, str):
        return {"center_of_buoyancy": cb, "center_of_gravity": cg,
                "origin": np.zeros(3)}[ref]
    return np.asarray(ref, dtype=float)


def estimate(vehicle, *, strips: int | None = None, corrections: bool | None = None,
             speed: float | None = None, reference_point=None, regime: str = "auto",
             fluid=None, correction_panels: int | None = None,
             section_panels: int | None = None) -> HydroModel:
    """Strip theory: a :class:`~stripcoef.geometry.vehicle.Vehicle` in, a HydroModel out.

    Parameters
    ----------
    vehicle : Vehicle
    strips : int, optional
        Number of strips (default: the vehicle file's, else 1000).
    corrections : bool, optional
        3D end corrections (default on; ``False`` = pure strip theory).
    speed : float, optional
        Reference speed for Reynolds numbers and the damping split [m/s].
    reference_point : str or (3,), optional
        center_of_buoyancy, center_of_gravity, origin, or a point [m] (default: file's).
    regime : str
        Friction line: ``auto``, ``laminar`` or ``turbulent``.
    fluid : Fluid, optional
        Override the vehicle file's fluid.
    correction_panels : int, optional
        Meridian panels of each axisymmetric solve of the 3D corrections (default
        :data:`stripcoef.corrections.DEFAULT_PANELS` = 160; cost grows as its square,
        accuracy converges at second order, docs/performance.md "Speed"). Ignored
        without corrections.
    section_panels : int, optional
        Panels per 2D section of a mesh body (default adaptive: 96 for a round section, more
        for slender ones and sharp corners, :func:`stripcoef.sections.panel.discretise`); a
        round section is within 0.01 % of its exact value with 32 (docs/meshes.md).

    Returns the model of :mod:`stripcoef.model` (Fossen 2011, eq. 7.190): M_A from
    :func:`added_mass`, D_L and D_Q from :func:`_damping`, M_RB from
    :func:`mass_properties` (Fossen 2011, eqs. 3.44-3.45). See the module docstring.
    """
    if regime not in ("auto", "laminar", "turbulent"):
        raise InputError("unknown regime", key="regime", value=regime,
                         expected="auto, laminar or turbulent")
    fluid = fluid or vehicle.fluid
    rho, nu = fluid.density, fluid.kinematic_viscosity
    speed = float(speed if speed is not None else vehicle.reference_speed)
    if not np.isfinite(speed) or speed <= 0:
        raise InputError("invalid reference speed", key="speed", value=speed,
                         expected="a speed > 0 m/s")
    corrections = vehicle.corrections if corrections is None else bool(corrections)
    st = vehicle.cut(strips)
    volume, cb = displaced_volume(st)
    mass, cg, inertia = mass_properties(st, vehicle, rho, volume, cb)
    ref = _reference_point(reference_point if reference_point is not None else vehicle.reference,
                           cb, cg)
    m_a, am_info = added_mass(st, rho, about=ref, volume=volume, center=cb,
                              corrections=corrections, correction_panels=correction_panels,
                              section_panels=section_panels)
    d_l, d_q, cond = _damping(st, vehicle, rho, nu, speed, ref, regime)
    m_rb = rigid_body_mass_matrix(mass, cg - ref, inertia)
    m_a, m_rb = _clean(m_a), _clean(m_rb)
    cond.update(am_info)
    cond.update({"strips": st.n, "corrections": corrections, "density": rho,
                 "kinematic_viscosity": nu, "fluid": fluid.source, "length": st.length})
    if abs(mass - rho * volume) > 0.05 * rho * volume:
        warnings.warn(f"{vehicle.name}: weight and buoyancy differ by "
                      f"{100 * (mass - rho * volume) / (rho * volume):+.1f} % "
                      f"(m = {mass:.3g} kg, rho V = {rho * volume:.3g} kg)", ModelWarning,
                      stacklevel=2)
    return HydroModel(
        name=vehicle.name, reference_point=ref, rigid_body_mass=m_rb, added_mass=m_a,
        linear_damping=d_l, quadratic_damping=d_q, mass=mass, volume=volume,
        center_of_gravity=cg, center_of_buoyancy=cb, density=rho, kinematic_viscosity=nu,
        thrusters=list(vehicle.thrusters), conditions=cond,
        provenance={"method": "strip theory", "source": vehicle.source,
                    "corrections": corrections, "strips": st.n},
    )
