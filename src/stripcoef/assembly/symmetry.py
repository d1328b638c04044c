r"""Which added-mass couplings a body's mirror symmetries force to zero, from its geometry.

A reflection :math:`S` of space that maps the body onto itself maps the fluid's kinetic energy
:math:`T = \tfrac12 \nu^T M_A \nu` onto itself, so :math:`M_A = P M_A P` with :math:`P` the
action of the reflection on :math:`\nu = [u, v, w, p, q, r]`: velocities are vectors
(:math:`v' = S v`), angular velocities pseudovectors (:math:`\omega' = \det(S)\, S\,\omega =
-S\omega`). Hence :math:`M_{ij} = P_i P_j M_{ij}`, and a coupling between a DOF that keeps
its sign and one that changes it is zero (Newman 1977, *Marine Hydrodynamics*, sec. 4.15;
Imlay 1961, DTMB 1528). The parities :math:`P_i` (:data:`PARITY`), for the reflection
planes through the point the matrix is expressed about:

==========================  =====================  ======================
reflection                  even (P = +1)          odd (P = -1)
==========================  =====================  ======================
``y``: y -> -y (port-stbd)  u, w, q                v, p, r
``z``: z -> -z (top-bottom) u, v, r                w, p, q
``x``: x -> -x (fore-aft)   v, w, p                u, q, r
==========================  =====================  ======================

So port-starboard symmetry forbids X_vdot, X_pdot, X_rdot, Z_vdot, Z_pdot, Z_rdot, M_vdot,
M_pdot, M_rdot (and their transposes); top-bottom symmetry the couplings between {u, v, r}
and {w, p, q}; fore-aft symmetry those between {v, w, p} and {u, q, r}. A body with all
three (a box, an ellipsoid, about its centre) has no coupling; one with y and z (a finned
torpedo, about a point on its axis) only Y_rdot and Z_qdot; one with y only (a box ROV with a
skid, a VideoRay) X_wdot, X_qdot, Z_qdot, Y_pdot, Y_rdot and K_rdot.

:func:`mirror_symmetries` reads the symmetries off the strips the model is made of
(:meth:`stripcoef.geometry.vehicle.Vehicle.cut`): each strip's section is the union of its
parts' outlines (a mesh's polygon contours, or the ellipse / rectangle of a part's
half-extents), and a reflection R through the reference point is a symmetry when the body
and its image differ by at most :data:`MIRROR_TOL` of the body's volume,

.. math:: \sum_i |S_i \,\triangle\, R(S_{i'})|\,\Delta x_i \le \tau \sum_i |S_i|\,\Delta x_i,

with :math:`S_i` the section of strip i [m^2], :math:`\triangle` the symmetric difference,
:math:`i' = i` for the reflections of y and z and :math:`i' = n - 1 - i` for x -> -x (the
strips are uniform over the body's extent, whose middle must then be the reflection plane
within :math:`\tau L`), :math:`\Delta x_i` the strip width [m] and :math:`\tau` =
:data:`MIRROR_TOL` [-]. For x -> -x the strips' covered areas (parts ending mid-strip) must
also match within :math:`\tau` of the volume. Holes are not looked at.
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.shapes import GEOMETRY, has_rings
from stripcoef.hull.mirror_panels import PARITY as MODE_PARITY
from stripcoef.sections import get_shape

#: the reflections, by the axis they reverse
MIRRORS = ("x", "y", "z")
#: parity of (u, v, w, p, q, r) under each reflection (module docstring: the table; kept
#: beside the panel method's solve with image panels, which needs it too)
PARITY = MODE_PARITY
#: a reflection is a symmetry when the body and its image differ by at most this fraction of
#: its volume [-] (a tessellated circle's facets differ by far less; a skid, a camera pod, a
#: tether mount or a fore-aft asymmetric hull of the reference shapes by more)
MIRROR_TOL = 0.01
_RING = 48      # points on an ellipse's outline (symmetric about both axes)



def allowed_couplings(mirrors) -> np.ndarray:
    r"""(6, 6) bool: True where the reflections ``mirrors`` (a subset of ``x``, ``y``, ``z``)
    allow :math:`M_{ij} \ne 0`, i.e. :math:`P_i P_j = +1` for each; the diagonal is True."""
    ok = np.ones((6, 6), dtype=bool)
    for m in mirrors:
        if m not in PARITY:

            raise InputError("unknown reflection", key="mirrors", value=m,
                             expected="x, y or z (the axis it reverses)")
        p = PARITY[m]
        ok &= np.outer(p, p) > 0
    return ok


def _section(part, k: int):
    """The k-th section of ``part`` as a shapely geometry (y, z) [m]: the shape's outline
    (:data:`stripcoef.sections.SHAPES`), its rings combined for a contoured shape."""
    from shapely.geometry import Polygon

    rings = get_shape(part.shape).outline(part, k, _RING)
    if not has_rings(part):
        return Polygon(rings[0])
    out = None
    for ring in rings:
        r = np.asarray(ring, dtype=float)
        poly = Polygon(r).buffer(0)
        # outer rings counter-clockwise, holes clockwise (stripcoef.strips.Part)
        hole = np.sum(r[:, 0] * np.roll(r[:, 1], -1) - np.roll(r[:, 0], -1) * r[:, 1]) < 0
        out = poly if out is None else (out.difference(poly) if hole else out.union(poly))
    if out is not None:
        return out
    return Polygon(GEOMETRY["ellipse"].outline(part, k, _RING)[0])


def strip_sections(strips):
    """Per strip: (the union of its parts' sections as a shapely geometry (y, z) [m], or None;
    covered area [m^2]), the input of :func:`strips_mirror_symmetries`."""
    from shapely.ops import unary_union

    geo = [[] for _ in range(strips.n)]
    area = np.zeros(strips.n)
    for p in strips.parts:
        for k, i in enumerate(np.asarray(p.index, dtype=int)):
            geo[i].append(_section(p, k))
            area[i] += float(p.area[k]) * float(p.coverage[k])
    return [unary_union(g) if g else None for g in geo], area


def _difference(a, b) -> float:
    """Area of the symmetric difference of two sections [m^2] (None: empty)."""
    if a is None or b is None:
        return (a.area if a is not None else 0.0) + (b.area if b is not None else 0.0)
    return float(a.symmetric_difference(b).area)


def mirror_symmetries(vehicle, point=(0.0, 0.0, 0.0), strips: int | None = None,
                      tol: float = MIRROR_TOL) -> frozenset:
    """The reflections (``x``, ``y``, ``z``) through ``point`` [m] (the point the model is
    expressed about, :attr:`stripcoef.model.HydroModel.reference_point`) that map the
    vehicle's strips (``strips`` of them; default its own count) onto themselves within
    ``tol`` of its volume (module docstring: the test)."""
    return strips_mirror_symmetries(vehicle.cut(strips), point, tol)


def strips_mirror_symmetries(st, point=(0.0, 0.0, 0.0), tol: float = MIRROR_TOL,
                             sections=None) -> frozenset:
    """:func:`mirror_symmetries` of strips already cut (:class:`stripcoef.strips.Strips`);
    ``sections``: their :func:`strip_sections` when already drawn (the test about several
    points draws them once)."""
    from shapely.affinity import scale

    secs, area = strip_sections(st) if sections is None else sections
    x0, y0, z0 = (float(v) for v in point)
    dx = np.asarray(st.dx, dtype=float)
    volume = float(np.sum(area * dx))
    limit = tol * volume
    out = set()
    for axis, (fy, fz) in (("y", (-1.0, 1.0)), ("z", (1.0, -1.0))):
        diff = sum(_difference(s, scale(s, fy, fz, origin=(y0, z0)) if s is not None else None)
                   * w for s, w in zip(secs, dx))
        if diff <= limit:
            out.add(axis)
    if abs(st.x_min + st.x_max - 2.0 * x0) <= tol * st.length and \
            float(np.sum(np.abs(area - area[::-1]) * dx)) <= limit and \
            sum(_difference(a, b) * w for a, b, w in zip(secs, secs[::-1], dx)) <= limit:
        out.add("x")
    return frozenset(out)


#: Tolerance of the mirror test when the forbidden couplings of a computed matrix are set to
#: exactly zero (:func:`enforce_symmetry`) [-]: 0.1 % of the volume, so that a coupling is
#: only removed where the asymmetry it could come from is below the 3D panel method's own
#: estimated error (at least 0.1 % of the diagonal scale on the shapes measured, docs/meshes.md).
ZERO_TOL = 1e-3


def enforce_symmetry(matrix, mirrors):
    """``matrix`` (6x6) with the couplings that the reflections ``mirrors`` forbid
    (:func:`allowed_couplings`) set to exactly zero; a new array."""
    out = np.array(matrix, dtype=float)
    out[~allowed_couplings(mirrors)] = 0.0
    return out


def enforce_symmetry_about(matrix, mirrors, centre, about):
    r"""``matrix`` (6x6, about the point ``about`` [m]) with the couplings forbidden by the
    reflections ``mirrors`` through another point ``centre`` [m] (the body's own mirror
    planes, which need not pass through the reference point: a body symmetric top-bottom
    with its centre of gravity below the plane) set to zero *about ``centre``*, and the
    result moved back to ``about``; a new array.

    .. math:: A_C = H(-r)^T A_P H(-r),\quad A_C \to P A_C P\ \text{(forbidden terms
              zero)},\quad A_P = H(r)^T A_C H(r), \quad r = C - P

    (:func:`stripcoef.conventions.transform_matrix`, Fossen 2011 sec. 7.5.3; the parities of
    the module docstring, Newman 1977 sec. 4.15).  The translational block does not depend on
    the point, so its forbidden couplings (X_wdot of a top-bottom symmetric body) are exactly
    zero about any point; the others are the exact congruence of the symmetric matrix (X_qdot
    about a point z below the plane: z X_udot, not zero)."""
    from stripcoef.conventions import transform_matrix

    if not mirrors:
        return np.array(matrix, dtype=float)
    at_centre = enforce_symmetry(transform_matrix(matrix, from_point=about, to_point=centre),
                                 mirrors)
    out = transform_matrix(at_centre, from_point=centre, to_point=about)
    # the translational block is the same about every point (exact zeros kept)
    out[:3, :3] = at_centre[:3, :3]
    return out
