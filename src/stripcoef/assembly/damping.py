r"""Linear and quadratic damping: cross-flow drag per strip, friction and form drag of the hull.

The cross-flow principle (Hoerner 1965, ch. 3; Newman 1977, sec. 7.4) integrates each
section's drag coefficient along the body; axial drag of a slender closed hull is skin friction
from the ITTC-1957 or Blasius line at the hull Reynolds number with a form factor; the power-law split of
:func:`stripcoef.hull.lamb.power_law_split` gives the linear and quadratic parts about the
reference speed. The axial drag of short and blunt hulls is measured whole-body drag (Hoerner 1965,
ch. 3; :mod:`stripcoef.sections.drag`), the form factor only inside its range. Every equation is
in :func:`damping_matrices`' docstring.
"""

from __future__ import annotations
import warnings
import numpy as np
from stripcoef.hull.lamb import power_law_split
from stripcoef.sections import drag as sdrag
from stripcoef.sections import get_shape, section_drag
from stripcoef.sections.panel import part_rings
from stripcoef.strips import Strips
from stripcoef.conventions import clean_roundoff
from stripcoef.strips import hole_widths
from stripcoef.errors import ModelWarning


#: relative excess of L/D over the measured short bodies' end (L/D 2) that the model still
#: calls measured, without a warning: a meshed 2:1 spheroid's inscribed polygon sections make
#: its L/D a few parts per thousand above 2 (the bridge moves C_D by 2 % at most there)
BRIDGE_QUIET = 0.02

#: an end section larger than this fraction of the largest section is a flat (truncated) end
FLAT_END = 0.25

#: ratio of the vehicle's surge drag going astern to going ahead (or its inverse) above which
#: the model warns that its one |u|u term (Fossen 2011, eq. 6.62: D_Q symmetric in the sign
#: of u) misrepresents one direction: 1.5 is a factor the method's band (sd(ln) about 0.25 at
#: its target) does not cover
ASTERN_RATIO_WARN = 1.5


def local_exponent(fn, *re):
    """n_k = 2 + d ln C_D,k / d ln Re_k (power-law exponent of the drag force in speed).

    ``fn(Re_1, Re_2, ...)`` -> (C_D,1, C_D,2, ...) [-], each C_D,k depending on Re_k only
    (so one call at Re*1.1 and one at Re/1.1 serve every k); ``re``: the Re_k [-]; returns
    the n_k [-] (a tuple) by a central difference over Re*1.1^+-1.
    From F = 1/2 rho C_D(Re) A V^2 with Re proportional to V (Hoerner 1965, ch. 3);
    the split is :func:`stripcoef.hull.lamb.power_law_split`.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hi = fn(*(np.asarray(r) * 1.1 for r in re))
        lo = fn(*(np.asarray(r) / 1.1 for r in re))
    return tuple(2.0 + (np.log(np.asarray(h, float)) - np.log(np.asarray(l, float)))
                 / (2.0 * np.log(1.1)) for h, l in zip(hi, lo))


def wetted_perimeter(part):
    r"""Wetted perimeter of each strip's section of a part [m].

    The shape's ``wetted_perimeter`` (:data:`stripcoef.sections.SHAPES`): ellipse, Ramanujan's
    approximation (:func:`stripcoef.sections.drag.ellipse_perimeter`); polygon, the sum of
    edge lengths :math:`P = \sum_{rings}\sum_i |p_{i+1} - p_i|` (outer rings and holes: a
    duct's inner wall is wetted too; wetted area for friction drag as in Hoerner 1965,
    ch. 2), taken from the part's ring set :func:`stripcoef.sections.panel.part_rings`,
    which the section solvers share (repeated points, closer than 1e-12 of the ring's size,
    are dropped there); rectangle: P = 4 (b + h), half sizes b, h [m].
    """
    return get_shape(part.shape).wetted_perimeter(part)


#: a vertex within this fraction of a part's extent along the flow of its extreme lies on the
#: face there (a faceted circle of 96 sides puts 2 vertices within 1e-3 of its diameter, a
#: flat face all of its own)
FACE_TOL = 1e-3


#: vertices of a curved outline (ellipse) when its section is drawn for :func:`_outline_points`
OUTLINE_POINTS = 96


def _outline_points(part):
    """Per strip of ``part``: the vertices (m, 2) [m] of its section's outline, (y, z), as the
    shape draws it (:data:`stripcoef.sections.SHAPES`; a curved outline with
    :data:`OUTLINE_POINTS` vertices). Drawn once per part for both flow directions; a shape
    with ``outlines`` draws every strip's at once, as a (k, m, 2) array."""
    shape = get_shape(part.shape)
    if shape.outlines is not None:
        return shape.outlines(part, OUTLINE_POINTS)
    outline = shape.outline
    pts = []
    for i in range(part.index.size):
        rings = outline(part, i, OUTLINE_POINTS)
        pts.append(np.concatenate([np.asarray(r, float) for r in rings]) if len(rings)
                   else np.zeros((0, 2)))
    return pts


def _extremes(pts, axis):
    """Per strip (``pts``: :func:`_outline_points`): the lowest and highest coordinate along
    ``axis`` (0: y, 1: z) [m], and the width across the flow [m] of the section's face at the
    highest: the spread across the flow of the outline's vertices within :data:`FACE_TOL` of
    the part's extent of that extreme (0 for a rounded contour or a vertex, the side for a
    flat face)."""
    if isinstance(pts, np.ndarray):
        # every strip's outline in one (k, m, 2) array: the same values row by row
        along, across = pts[..., axis], pts[..., 1 - axis]
        lo, hi = along.min(axis=1), along.max(axis=1)
        tol = FACE_TOL * max(float(np.max(hi) - np.min(lo)), 1e-300)
        on = along >= (hi - tol)[:, None]
        w_hi = (np.where(on, across, -np.inf).max(axis=1)
                - np.where(on, across, np.inf).min(axis=1))
        return lo, hi, w_hi
    k = len(pts)
    lo, hi = np.full(k, np.inf), np.full(k, -np.inf)
    for i, p in enumerate(pts):
        if p.size:
            lo[i], hi[i] = p[:, axis].min(), p[:, axis].max()
    tol = FACE_TOL * max(float(np.max(hi) - np.min(lo)), 1e-300)
    w_hi = np.zeros(k)
    for i, p in enumerate(pts):
        if p.size:
            w_hi[i] = np.ptp(p[p[:, axis] >= hi[i] - tol, 1 - axis])
    return lo, hi, w_hi


def _single_solid(part):
    """Whether every section of ``part`` is one solid part (no frame of several members)."""
    if not get_shape(part.shape).contoured:
        return True
    return int(np.count_nonzero(part_rings(part).area > 0)) == part.index.size


def short_body_crossflow(part, dx, heights, coeffs, rho, speed, nu):
    r"""The cross-flow drag of a part that is short across the flow: the strips' coefficients
    ``coeffs`` = (c_y, c_z) [kg/m per strip] scaled to the bridged whole-body drag.

    For flow along k (y or z) with the part's length L, its largest extent across the flow
    h (``heights``: per strip, the heights across y- and z-flow [m]) and its extent along the
    flow :math:`\ell`, the slenderness :math:`L/h = L/\max(h, \ell)` (the strips' 2D flow
    needs the part long against its section's size both across and along the flow: Hoerner
    1965, ch. 3, the cross-flow principle; Newman 1977, sec. 7.4, slender bodies) sets the share
    :math:`w = w(L/h)` (:func:`stripcoef.sections.drag.short_body_crossflow_weight`: 1 at
    L/h <= 1, 0 from L/h = 2) of the force that is the whole-body drag of the part seen along
    the flow (:func:`stripcoef.sections.drag.short_body_crossflow_cd`):

    .. math:: \sum_e c_{k,e}' = (1 - w)\sum_e c_{k,e} + w\,\tfrac12\rho\,C_{D}(\ell/D,
              \ldots)\,A,\qquad A = \sum_e h_{k,e}\,\Delta x_e,\ D = \sqrt{4A/\pi}

    a flat class when its face at the
    +k extreme (the face that meets the flow going +k, as the bow going ahead) covers more than
    :data:`FLAT_END` of A. Every strip is scaled by the same factor, so the moments of the
    cross-flow (yaw, pitch, roll) keep the strips' distribution. Parts whose sections have
    several members (a frame) or holes keep the strips (interference, not a short body).
    A closed part thinner along the flow than the measured closed bodies
    (:func:`stripcoef.sections.drag.closed_body_depth_range`: \ell/D below 0.75) keeps its strips
    (weight 0) rather than extrapolate their curve [a step: a circular cylinder across goes
    from the bridge to the strips at L/D 1.4].
    Returns ((c_y', c_z'), info) with info per direction: ``weight``, ``cd`` (the whole-body
    C_D on A), ``class`` (``flat``/``closed``), ``factor`` (c'/c), ``length_over_height``,
    ``depth_over_diameter`` [-].
    """
    out, info = [], {}
    pts = _outline_points(part)
    for axis, key in ((0, "y"), (1, "z")):
        c, h = coeffs[axis], heights[axis]
        lo, hi, w_hi = _extremes(pts, axis)
        depth = float(np.max(hi) - np.min(lo))
        lh = max(part.length, 1e-12) / max(float(np.max(h)), depth, 1e-12)
        w = float(sdrag.short_body_crossflow_weight(lh))
        if w <= 0.0 or not np.any(c > 0):
            out.append(c)
            continue
        area = float((h * dx).sum())
        tol = FACE_TOL * max(depth, 1e-300)
        face = float((np.where(hi >= np.max(hi) - tol, np.minimum(w_hi, h), 0.0) * dx).sum())
        flat = face > FLAT_END * area
        d_eq = np.sqrt(4.0 * area / np.pi)
        aspect = max(part.length, 1e-12) / max(float(np.max(h)), 1e-12)
        if not flat and depth / d_eq < sdrag.closed_body_depth_range()[0]:
            # no measured closed body this thin along the flow: the strips alone (no
            # extrapolation of the ellipsoids' curve)
            out.append(c)
            info[key] = {"weight": 0.0, "class": "closed", "factor": 1.0,
                         "length_over_height": lh, "depth_over_diameter": depth / d_eq}
            continue
        cd = sdrag.short_body_crossflow_cd(depth / d_eq, flat, aspect, speed * d_eq / nu)
        strip_total = float(c.sum())
        factor = ((1.0 - w) * strip_total + w * 0.5 * rho * cd * area) / strip_total
        out.append(c * factor)
        info[key] = {"weight": w, "cd": cd, "class": "flat" if flat else "closed",
                     "factor": factor, "length_over_height": lh,
                     "depth_over_diameter": depth / d_eq}
    return tuple(out), info


def damping_matrices(strips: Strips, vehicle, rho, nu, speed, about, regime):
    r"""Linear and quadratic damping about ``about`` from the viscous force model.

    Force model (all per element e at r_e, directions k = x, y, z):

    - cross-flow (Hoerner 1965 ch. 3; Fossen 2011 sec. 6.4.3, MSS crossFlowDrag.m):
      :math:`f_k = -\tfrac12\rho\,C_{D,k}(Re)\,\kappa\,h_k\,|V_k|V_k` per unit length, with
      :math:`h_y = 2h`, :math:`h_z = 2b` the part's extent across the flow and
      :math:`Re = U h_k/\nu` at the reference speed U;
    - hull axial drag, by the hull's ends and fineness ratio L/D (D of the largest section's
      equal circle, :math:`A_f = \pi D^2/4`):
      a closed hull with :math:`L/D \ge 3`: friction with Hoerner's streamlined-body form
      factor, :math:`X = -\tfrac12\rho C_f(Re_L)\,FF\,S_{wet}u|u|`; a shorter closed hull:
      the measured whole-body drag of ellipsoids of its L/D,
      :math:`X = -\tfrac12\rho C_D(L/D, Re_D) A_f u|u|`, bridged to the form factor between
      L/D 2 and 3 (:func:`stripcoef.sections.drag.closed_body_axial_cd`, with a warning there);
      a hull with a flat bow (its +x end, which meets the flow going ahead): the measured
      whole-body drag of flat-ended bodies end-on by L/D and frontal aspect ratio
      (:func:`stripcoef.sections.drag.blunt_cylinder_axial_cd`: a thin plate normal to the
      flow at L/D -> 0); a closed bow and a flat stern only: the measured drag of closed
      bodies whose flow separates, the ellipsoids of its L/D
      (:func:`stripcoef.sections.drag.ellipsoid_axial_cd`) [assumption: the base separates
      the flow as a laminar separation does; the |u|u term then holds going ahead, and
      underestimates the drag going astern, flat face first]; both plus plain friction
      (no form factor);
      appendages: the blunt-body curve on their frontal area (fins: friction on both faces);
    - roll: skin friction on the hull's perimeter and the cross-flow of off-axis parts.

    For each DOF j the element's local velocity is :math:`V = [I,\ -S(r)]e_j`; the
    generalized force is :math:`[F;\ r\times F]`.  Each element's force at the reference
    DOF speed, with its power-law exponent n (from the Reynolds dependence of its C_D or
    C_f), is split into linear and quadratic parts by :func:`stripcoef.hull.lamb.power_law_split`.
    Reference speeds: U for translations, :math:`\Omega = U/(L/2)` for rotations.

    Rotation of a bluff body (neither a body of revolution about x nor slender,
    :func:`bluff_surface`): K_pp, M_qq and N_rr are the pressure drag of its closed surface's
    elements moving into the water, :func:`rotational_pressure_drag`, with the element
    coefficients that give the translational terms above
    (:func:`face_drag_coefficients`); the strips' own values are in
    ``cond["rotational_drag"]["strips"]``.  Their cross-flow at a lever arm misses the faces
    a turning bluff body pushes along its length (a box about its long axis: all of them).
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
    (n_f,) = local_exponent(lambda r: (sdrag.friction_coefficient(r, regime=regime)[0],), re_l)
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
        per = wetted_perimeter(p)
        s_wet += float((per * dx).sum())
        area = p.area
        max_d = max(max_d, float(2.0 * np.sqrt(np.max(area) / np.pi)))
        w = area * dx
        hull_volume += float(w.sum())
        hull_moment += np.array([(w * strips.x[p.index]).sum(), (w * p.y).sum(), (w * p.z).sum()])
        # roll friction on the hull perimeter: dK = 1/2 rho Cf per R_eff^3 p|p| dx
        r_eff = np.sqrt(p.half_breadth * p.half_height)
        c_roll = 0.5 * rho * cf * float((per * r_eff**3 * dx).sum())
        elems.append(("roll friction", c_roll, n_f))
    hull_body = getattr(vehicle, "hull", None)
    if hull_parts:
        x_h, y_h, z_h = hull_moment / hull_volume
        r_h = np.array([x_h, y_h, z_h])
        ld_hull = L / max_d
        a_frontal = np.pi * max_d**2 / 4
        # flat ends: a hull that does not close gets the measured whole-body drag of its
        # class on the frontal area, by the end that meets the flow going ahead (+x, FRD):
        # a flat bow, the flat-ended bodies end-on; a closed bow with a flat stern only, the
        # closed bodies whose flow separates (ellipsoids: a base separates the flow as a
        # laminar separation does); its friction is the plain friction line, the
        # streamlined-body form factor being outside its source
        blunt = False
        astern_delta = 0.0   # D_Q[0, 0] going astern minus going ahead [kg/m]
        blunt_kind = ""
        re_d = speed * max_d / nu
        for p in hull_parts:
            a_max = float(np.max(p.area))
            if hull_body is not None:    # exact end sections of the profile (stern, bow)
                lo, hi = hull_body.x_extent()
                ends = [hull_body.half_breadth(np.array([x]))[0]
                        * hull_body.half_height(np.array([x]))[0] for x in (lo, hi)]
                stern, bow = (float(e) / float(np.max(p.half_breadth * p.half_height))
                              for e in ends)
            else:                        # mesh: end strips (strips run aft to fore)
                stern, bow = float(p.area[0]) / a_max, float(p.area[-1]) / a_max
            if not p.index.size or max(stern, bow) <= FLAT_END:
                continue
            width, height = 2 * float(np.max(p.half_breadth)), 2 * float(np.max(p.half_height))
            aspect = max(width, 1e-12) / max(height, 1e-12)
            cd_flat = float(sdrag.blunt_cylinder_axial_cd(ld_hull, aspect))
            if bow > FLAT_END:           # the flat face meets the flow
                cd_b = cd_flat
                blunt_kind = "blunt"
            else:                        # a closed bow and a flat base
                cd_b = float(sdrag.ellipsoid_axial_cd(ld_hull, re_d))
                blunt_kind = blunt_kind or "blunt_base"
            # going astern the stern meets the flow: the same rule by the stern (reported;
            # the |u|u term holds the drag going ahead)
            cd_astern = cd_flat if stern > FLAT_END else float(
                sdrag.ellipsoid_axial_cd(ld_hull, re_d))
            cond["blunt_hull_cd_astern"] = cd_astern
            astern_delta += 0.5 * rho * (cd_astern - cd_b) * a_max
            elems.append((r_h, np.array([0.5 * rho * cd_b * a_max, 0, 0]),
                          np.array([2.0, 2, 2])))
            cond.update({"blunt_hull_cd": cd_b, "blunt_hull_aspect_ratio": aspect})
            blunt = True
        lo_ff, hi_ff = sdrag.FORM_FACTOR_LD
        if blunt or ld_hull >= hi_ff:
            # friction with the form factor of a streamlined body inside its range; a blunt
            # hull's pressure drag is in its measured curve above, so its friction has none
            ff = 1.0 if blunt else float(sdrag.hoerner_form_factor(max_d / L))
            c_fric = 0.5 * rho * cf * ff * s_wet
            elems.append((r_h, np.array([c_fric, 0, 0]), np.array([n_f, 2, 2])))
            cd_axial = cf * ff * s_wet / a_frontal
            n_axial = n_f
        else:
            # a short closed hull: the measured whole-body drag of ellipsoids of its L/D
            # (the flow separates), bridged to the form factor between L/D 2 and 3
            def axial_cd(s):
                c_f = sdrag.friction_coefficient(re_l * float(s), regime=regime)[0]
                return (sdrag.closed_body_axial_cd(ld_hull, re_d * float(s), c_f,
                                                   s_wet / a_frontal),)
            cd_axial = float(axial_cd(1.0)[0])
            (n_axial,) = local_exponent(axial_cd, 1.0)
            n_axial = float(n_axial)
            ff = float(sdrag.hoerner_form_factor(max_d / L))
            elems.append((r_h, np.array([0.5 * rho * cd_axial * a_frontal, 0, 0]),
                          np.array([n_axial, 2, 2])))
            if ld_hull > lo_ff * (1 + BRIDGE_QUIET):
                warnings.warn(
                    f"{getattr(vehicle, 'name', 'vehicle')}: closed hull of L/D {ld_hull:.3g}, "
                    f"between the measured short bodies (ellipsoids, L/D <= {lo_ff:g}) and the "
                    f"streamlined-body form factor (L/D >= {hi_ff:g}): its axial drag "
                    f"(C_D {cd_axial:.3g} on the frontal area) is a bridge between the two, "
                    f"not a measured value", ModelWarning, stacklevel=3)
        cond.update({"wetted_area": s_wet, "form_factor": ff,
                     "axial_drag_coefficient_wetted": cd_axial * a_frontal / s_wet,
                     "axial_drag_coefficient_frontal": cd_axial,
                     "axial_drag_method": blunt_kind if blunt else (
                         "form_factor" if ld_hull >= hi_ff else
                         "measured_short_body" if ld_hull <= lo_ff * (1 + BRIDGE_QUIET) else "bridge")})
    # --- appendages: axial pressure drag (blunt) on the frontal area
    for p in strips.parts:
        if p.role == "hull":
            continue
        a_front = float(np.max(get_shape(p.shape).outer_area(p)))
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
    short_info = {}
    for p in strips.parts:
        dx = strips.width(p)
        hy, hz = 2 * p.half_height, 2 * p.half_breadth      # extents across y- and z-flow
        # one Reynolds number per part, on its largest extent across the flow: the regime
        # of a body is set by its main diameter, not by the tapering tips (MSS cylinderDrag.m)
        re_y = np.full(p.index.size, speed * float(np.max(hy)) / nu)
        re_z = np.full(p.index.size, speed * float(np.max(hz)) / nu)
        cd_y, cd_z = section_drag(p, re_y, re_z)
        # cd_y depends on re_y only and cd_z on re_z only (sections.SHAPES: cross_flow_drag)
        n_y, n_z = local_exponent(lambda ry, rz: section_drag(p, ry, rz), re_y, re_z)
        if p.role != "fin":
            ld_y = max(p.length, 1e-9) / np.maximum(hy, 1e-9)
            ld_z = max(p.length, 1e-9) / np.maximum(hz, 1e-9)
            kap_y = sdrag.cylinder_length_factor(np.clip(ld_y, 2, 100), re_y)
            kap_z = sdrag.cylinder_length_factor(np.clip(ld_z, 2, 100), re_z)
            # short parts (L/D < 2) keep the L/D = 2 factor here; below, a part short
            # against its section takes the short-body rule (docs/theory.md)
        else:   # a fin: the 2D plate in flow normal to it, reduced to its aspect ratio
            kap_y = kap_z = np.ones(p.index.size)
            span = 2.0 * float(np.max(np.maximum(p.half_breadth, p.half_height)))
            kappa = sdrag.fin_crossflow_factor(span, max(p.length, 1e-9))
            if np.max(p.half_height) > np.max(p.half_breadth):
                kap_y = np.full(p.index.size, kappa)     # vertical fin: sway is normal to it
            else:
                kap_z = np.full(p.index.size, kappa)
        cy, cz = hole_widths(strips, p)
        c_y = 0.5 * rho * cd_y * kap_y * np.maximum(hy - cy, 0.0) * dx
        c_z = 0.5 * rho * cd_z * kap_z * np.maximum(hz - cz, 0.0) * dx
        if p.role != "fin" and not (np.any(cy > 0) or np.any(cz > 0)) and _single_solid(p):
            # a part short across the flow: the whole-body drag of a short body, bridged
            (c_y, c_z), sb = short_body_crossflow(p, dx, (hy, hz), (c_y, c_z), rho, speed, nu)
            if sb:
                short_info[p.name] = sb
        # one element per strip, appended as one block of rows (r, c, n), each (k, 3)
        k = p.index.size
        elems.append((np.column_stack([strips.x[p.index], p.y, p.z]),
                      np.column_stack([np.zeros(k), c_y, c_z]),
                      np.column_stack([np.full(k, 2.0), n_y, n_z])))
        if get_shape(p.shape).corner_roll:   # roll of a sharp part about its own centre
            f_y, f_z = (kap_y, kap_z) if p.role == "fin" else (1.0, 1.0)   # fins: finite span
            c_self = 0.5 * rho * (f_z * cd_z * p.half_breadth**4
                                  + f_y * cd_y * p.half_height**4) / 2 * dx
            elems.append(("roll", float(c_self.sum()), 2.0))
        if p.role == "hull":
            mid = int(np.argmax(p.area))
            hull_cd = {"hull_reynolds_diameter": float(re_y[mid]),
                       "hull_crossflow_cd_y": float(cd_y[mid]), "hull_crossflow_cd_z": float(cd_z[mid]),
                       "hull_length_factor": float(np.atleast_1d(kap_y)[mid])}
    cond.update(hull_cd)
    if short_info:
        cond["short_body_crossflow"] = short_info
    d_lin = np.zeros((6, 6))
    d_quad = np.zeros((6, 6))
    # point elements: single (3,) rows and (k, 3) blocks, stacked in order
    pts = [tuple(np.reshape(np.asarray(v, float), (-1, 3)) for v in e)
           for e in elems if not isinstance(e[0], str)]
    roll_friction = 0.0     # the skin friction's share of D_Q[3, 3] [kg m^2]
    roll_friction_lin = 0.0  # and of D_L[3, 3] [kg m^2/s]
    for r, c, n in elems:
        if isinstance(r, str):  # roll-only element: c [kg m^2], local speed ~ R * Omega
            a_hat, b_hat = power_law_split(n)
            d_lin[3, 3] += a_hat * c * omega
            d_quad[3, 3] += b_hat * c
            if r == "roll friction":
                roll_friction += float(b_hat * c)
                roll_friction_lin += float(a_hat * c * omega)
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
    if "blunt_hull_cd_astern" in cond:
        ahead, astern = float(d_quad[0, 0]), float(d_quad[0, 0] + astern_delta)
        cond["surge_quadratic_damping_astern"] = astern
        if max(ahead, astern) > ASTERN_RATIO_WARN * min(ahead, astern):
            warnings.warn(
                f"{getattr(vehicle, 'name', 'vehicle')}: its hull's ends differ (bow "
                f"{'flat' if cond['axial_drag_method'] == 'blunt' else 'closed'}): the "
                f"quadratic X_uu holds the surge drag going ahead ({ahead:.4g} kg/m); going "
                f"astern its class gives {astern:.4g} kg/m (conditions "
                f"surge_quadratic_damping_astern); the |u|u form cannot hold both",
                ModelWarning, stacklevel=3)
    # --- rotation of a bluff body: the pressure drag of its surface moving into the water
    surface = bluff_surface(vehicle, strips)
    if surface is not None:
        d_quad, ratio = with_rotational_pressure_drag(d_quad, surface, rho, about, cond,
                                                      roll_friction=roll_friction)
        d_lin[4, 4] += roll_friction_lin * ratio[1]   # friction's linear share, as in roll
        d_lin[5, 5] += roll_friction_lin * ratio[2]
    return clean_roundoff(d_lin), clean_roundoff(d_quad), cond


# --- rotational pressure drag of bluff bodies: the surface integral --------------------------

def positive_cube_integral(s, area):
    r"""Exact :math:`\int_T \max(s, 0)^3\,dA` over each flat triangle T on which s is linear.

    ``s``: (F, 3) the values of s at the triangle's vertices [any unit u]; ``area``: (F,) the
    triangles' areas [m^2]; returns (F,) [u^3 m^2].  On a triangle where s keeps its sign,
    the integral of a linear function's cube is (Hammer & Stroud's monomial rule for the
    barycentric coordinates, :math:`\int_T \lambda_1^a\lambda_2^b\lambda_3^c dA =
    2A\,a!\,b!\,c!/(a+b+c+2)!`)

    .. math:: \int_T s^3\,dA = \frac{A}{10}\,h_3(s_1, s_2, s_3)

    with :math:`h_3` the complete homogeneous symmetric polynomial of degree 3 (the ten
    monomials :math:`s_1^3 + s_1^2 s_2 + \ldots + s_1 s_2 s_3`).  A triangle with one vertex i
    on the positive side keeps the corner triangle cut by the zero line, of area
    :math:`A\,t_j t_k`, :math:`t_j = s_i/(s_i - s_j)`, on which s is :math:`s_i` at its
    apex and 0 at the other two: :math:`\int = A\,t_j t_k\,s_i^3/10`; one with two vertices
    positive is the whole triangle's integral plus the negative corner's,
    :math:`\int s_+^3 = \int s^3 + \int (-s)_+^3`.
    """
    s = np.asarray(s, float)
    area = np.asarray(area, float)
    h3 = ((s ** 3).sum(1) + s[:, 0] ** 2 * (s[:, 1] + s[:, 2]) + s[:, 1] ** 2 * (s[:, 0] + s[:, 2])
          + s[:, 2] ** 2 * (s[:, 0] + s[:, 1]) + s.prod(1))
    whole = area * h3 / 10.0

    def corner(x):       # x with at most one positive vertex: its positive corner
        i = np.argmax(x, axis=1)
        xi = np.take_along_axis(x, i[:, None], 1)[:, 0]
        others = np.stack([np.take_along_axis(x, ((i + d) % 3)[:, None], 1)[:, 0]
                           for d in (1, 2)], axis=1)
        pos = xi > 0
        t = np.where(pos[:, None], xi[:, None] / np.where(pos[:, None], xi[:, None] - others,
                                                           1.0), 0.0)
        return np.where(pos, area * t[:, 0] * t[:, 1] * np.maximum(xi, 0.0) ** 3 / 10.0, 0.0)

    npos = (s > 0).sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):   # rows np.select does not take
        one, two = corner(s), corner(-s)
    return np.select([npos == 3, npos == 2, npos == 1], [whole, whole + two, one],
                     0.0)


def face_drag_coefficients(normals, areas, translational, rho):
    r"""Drag coefficients :math:`C_m` (m = x, y, z) [-] of the surface's elements, from the
    body's own quadratic drag in translation.

    An element of area dA with outward normal n moving with normal velocity
    :math:`v_n = V\cdot n > 0` into the water takes the pressure drag (Morison's drag term on
    the velocity of the structure relative to still water, DNV-RP-C205 (2010), sec. 6.2,
    Morison's load formula, the case of a structure moving in still water; the element-wise form of the ROV simulators Stonefish,
    Cieslak 2019, and MuJoCo's inertia-box model, Todorov et al. 2012, docs "Fluid forces")

    .. math:: dF = -\tfrac12\rho\,C(n)\,v_n^2\,n\,dA,\qquad C(n) = \sum_m n_m^2 C_m

    [assumption: the coefficient of an element between the axes blends those of the axes by
    its direction cosines squared].  The :math:`C_m` are those for which the sum over the
    surface in pure translation along each axis k gives the body's quadratic drag of the
    model, ``translational`` = (X_uu, Y_vv, Z_ww) magnitudes [kg/m] (Hoerner 1965 measured
    whole-body drag and the cross-flow principle, :func:`damping_matrices`):

    .. math:: D_{kk} = \tfrac12\rho\sum_m C_m B_{km},\qquad
              B_{km} = \tfrac12\sum_e dA_e\,n_{e,m}^2\,|n_{e,k}|^3

    (both senses of the motion averaged, as the |u|u term is [m^2]).  For a box the
    :math:`C_m` are the box's whole-body C_D on its faces; the sum holds the body's base
    pressure with its front (a leeward face takes none): for a face that sweeps the water
    symmetrically about the axis, a windward and a leeward share adding up to :math:`C_m`
    give the same moment.  ``normals`` (E, 3), ``areas`` (E,) [m^2], ``rho`` [kg/m^3];
    returns (C (3,), how): ``"per axis"``, or where the 3x3 system has no positive solution
    (a surface without faces along an axis) one coefficient for all,
    :math:`C = \sum_k D_{kk} / (\tfrac12\rho\sum_{k,m} B_{km})`, ``"one for all"``.
    """
    n = np.asarray(normals, float)
    a = np.asarray(areas, float)
    d = np.abs(np.asarray(translational, float))
    b = 0.5 * np.einsum("e,em,ek->km", a, n ** 2, np.abs(n) ** 3)
    with np.errstate(all="ignore"):
        try:
            c = np.linalg.solve(0.5 * rho * b, d)
        except np.linalg.LinAlgError:
            c = np.full(3, np.nan)
    if np.all(np.isfinite(c)) and np.all(c > 0):
        return c, "per axis"
    return np.full(3, d.sum() / max(0.5 * rho * b.sum(), 1e-300)), "one for all"


def _triangles_about(vertices, faces, about):
    """The surface's triangles about ``about`` (F, 3, 3) [m], their unit outward normals
    (F, 3) and areas (F,) [m^2], faces of zero area left out."""
    v = np.asarray(vertices, float) - np.asarray(about, float)
    tri = v[np.asarray(faces)]                                          # (F, 3, 3)
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    twice = np.linalg.norm(cross, axis=1)
    keep = twice > 0
    tri, cross, twice = tri[keep], cross[keep], twice[keep]
    return tri, cross / twice[:, None], 0.5 * twice


def rotational_pressure_drag(vertices, faces, coefficients, about, rho):
    r"""Quadratic damping of rotation about each body axis from the pressure drag of the
    surface elements moving into the water [kg m^2] (K_pp, M_qq, N_rr magnitudes, (3,)).

    For a rotation :math:`\omega e_k` an element at r (about ``about``) with outward normal n
    has the normal velocity :math:`v_n = (\omega e_k \times r)\cdot n = \omega\,s`,
    :math:`s = e_k\cdot(r\times n)` [m], linear in r on a flat face. Each element moving into
    the water (:math:`v_n > 0`) takes :math:`dF = -\tfrac12\rho C(n) v_n^2 n\,dA`
    (:func:`face_drag_coefficients`), whose moment about the axis is
    :math:`e_k\cdot(r\times dF) = -\tfrac12\rho C(n)\,\omega|\omega|\,s^3 dA`, so

    .. math:: D_{Q,kk} = \tfrac12\rho\sum_f C(n_f)\int_f \max(s, 0)^3\,dA

    integrated exactly on each triangle (:func:`positive_cube_integral`).  A sphere about its
    centre and a body of revolution about its axis have s = 0 everywhere (no pressure drag:
    their damping is friction); a box of half sizes :math:`r_x, r_y, r_z` about its centre
    gives :math:`\tfrac12\rho\,r_i(C_j r_k^4 + C_k r_j^4)` about axis i (MuJoCo's
    inertia-box torque with C = 1: Todorov et al. 2012, docs "Fluid forces").
    ``vertices`` (V, 3) [m], ``faces`` (F, 3) int, ``coefficients`` (3,) [-] (the
    :math:`C_m`), ``about`` (3,) [m], ``rho`` [kg/m^3].
    """
    tri, n, area = _triangles_about(vertices, faces, about)
    c = (n ** 2) @ np.asarray(coefficients, float)
    out = np.zeros(3)
    for k in range(3):
        s = np.cross(tri, n[:, None, :])[:, :, k]                       # e_k . (r x n)
        out[k] = 0.5 * rho * float((c * positive_cube_integral(s, area)).sum())
    return out


def rotational_friction_integral(vertices, faces, about):
    r"""The skin friction's lever integral of a closed surface turning about each body axis,
    :math:`I_k = \int |u_{t,k}|^3\,dA` [m^5], (3,).

    A rotation :math:`\omega e_k` moves an element at r (about ``about``) tangentially at
    :math:`\omega u_{t,k}`, :math:`u_{t,k} = w - (w\cdot n)n`, :math:`w = e_k\times r`; its
    shear :math:`dF = -\tfrac12\rho C_f |\omega u_t|\,\omega u_t\,dA` (the flat-plate law
    applied locally, Hoerner 1965, ch. 2) has the moment
    :math:`e_k\cdot(r\times dF) = -\tfrac12\rho C_f\,\omega|\omega|\,|u_t|^3 dA`
    (:math:`e_k\cdot(r\times u_t) = u_t\cdot w = |u_t|^2`). So the friction damping about
    axis k is :math:`\tfrac12\rho C_f I_k`. Integrated on each triangle by the edge-midpoint
    rule (exact for quadratics; Dunavant 1985). A sphere of radius R:
    :math:`I_k = 3\pi^2 R^5/4` about every axis.  ``vertices`` (V, 3) [m], ``faces`` (F, 3).
    """
    tri, n, area = _triangles_about(vertices, faces, about)
    mids = 0.5 * (tri + np.roll(tri, -1, axis=1))                       # (F, 3 points, 3)
    out = np.zeros(3)
    for k in range(3):
        w = np.cross(np.eye(3)[k], mids)                                # e_k x r
        ut = w - np.einsum("fpi,fi->fp", w, n)[:, :, None] * n[:, None, :]
        cube = np.linalg.norm(ut, axis=2) ** 3                          # (F, 3)
        out[k] = float((cube.mean(axis=1) * area).sum())
    return out


def is_slender(strips) -> bool:
    r"""Whether the strips' body is slender, :math:`L \ge` SLENDER_RATIO :math:`\max(B, H)`
    (B, H the largest breadth and height of its sections [m];
    :data:`stripcoef.assembly.added_mass.SLENDER_RATIO` = 5, the bound of the panel method's
    rule): where the cross-flow principle's 2D sections hold along the body (Hoerner 1965,
    ch. 3; Newman 1977, sec. 7.4), its rotational drag their drag at a lever arm."""
    from stripcoef.assembly.added_mass import SLENDER_RATIO

    width = max(max(float(np.max(2 * p.half_breadth)), float(np.max(2 * p.half_height)))
                for p in strips.parts)
    return bool(strips.length >= SLENDER_RATIO * width)


def bluff_surface(vehicle, strips):
    """The closed surface (vertices [m], faces) on which a bluff vehicle's rotational drag is
    integrated, or None for a slender one (:func:`is_slender`: strip theory's domain, where
    the strips' cross-flow at a lever arm is the rotational drag; a short body of revolution,
    a sphere, is bluff: the strips would give it pressure drag turning about its centre).
    A mesh vehicle: its body united (:meth:`stripcoef.geometry.mesh.MeshBody.united`); a
    vehicle file: its parts united (:func:`stripcoef.geometry.surface.vehicle_surface` at
    its default tessellation, the panel method's: the BlueROV2 Heavy's K_pp, M_qq, N_rr
    move by 0.02-0.1 % from there to 128 sides and 48 stations)."""
    from stripcoef.assembly.added_mass import _mesh_of

    if vehicle is None or not strips.parts or is_slender(strips):
        return None
    body = _mesh_of(vehicle)
    if body is not None:
        mesh = body.united()
    else:
        from stripcoef.errors import InputError
        from stripcoef.geometry.surface import vehicle_surface

        try:
            mesh = vehicle_surface(vehicle)
        except InputError as exc:   # no closed union: the strips' rotational drag, said so
            warnings.warn(f"{getattr(vehicle, 'name', 'vehicle')}: its rotational drag stays "
                          f"the strips' cross-flow ({exc})", ModelWarning, stacklevel=3)
            return None
    return np.asarray(mesh.vertices, float), np.asarray(mesh.faces)


def with_rotational_pressure_drag(d_quad, surface, rho, about, cond, *, roll_friction=0.0):
    """``d_quad`` with its rotational diagonal (K_pp, M_qq, N_rr) from the surface integral
    :func:`rotational_pressure_drag` on ``surface`` (:func:`bluff_surface`), the element
    coefficients from ``d_quad``'s own translational diagonal
    (:func:`face_drag_coefficients`), plus the hull's skin friction: ``roll_friction``
    [kg m^2] (its quadratic share in roll, :func:`damping_matrices`: pressure drag leaves a
    body of revolution about its axis undamped) in roll, and in pitch and yaw the same
    friction law on the same surface, ``roll_friction`` I_k / I_x
    (:func:`rotational_friction_integral`: a sphere is damped alike about every axis).  The
    strips' values and the coefficients go to ``cond["rotational_drag"]``; returns
    (D_Q, friction ratios I / I_x (3,)), the ratios for the friction's linear share.  The
    couplings and D_L's other terms stay from the strips."""
    vertices, faces = surface
    tri = vertices[faces]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    twice = np.linalg.norm(cross, axis=1)
    ok = twice > 0
    coeffs, how = face_drag_coefficients(cross[ok] / twice[ok, None], 0.5 * twice[ok],
                                         np.diag(d_quad)[:3], rho)
    rot = rotational_pressure_drag(vertices, faces, coeffs, about, rho)
    out = np.array(d_quad, float)
    strip = np.diag(out)[3:].copy()
    lever = rotational_friction_integral(vertices, faces, about)
    ratio = lever / lever[0]
    out[3, 3], out[4, 4], out[5, 5] = rot + roll_friction * ratio
    cond["rotational_drag"] = {
        "method": "surface pressure drag", "element_cd": [float(v) for v in coeffs],
        "element_cd_rule": how, "strips": [float(v) for v in strip],
        "roll_friction": float(roll_friction),
        "friction": [float(roll_friction * v) for v in ratio],
        "surface_faces": int(len(faces))}
    return out, ratio
