r"""3D potential-flow panel method: the added mass of any closed body in unbounded fluid.

Strip theory is the slender-body limit; a short, wide or open body (box ROVs, frames) needs the
3D flow.  The added mass of a deeply submerged body is the unbounded-fluid Neumann problem

.. math::
    \nabla^2\phi_j = 0 \text{ in the fluid},\qquad
    \partial\phi_j/\partial n = n_j \text{ on } S,\qquad \phi_j \to 0 \text{ at infinity},

    A_{ij} = -\rho \iint_S \phi_j\, n_i\, dS \quad [\mathrm{kg},\ \mathrm{kg\,m},\
    \mathrm{kg\,m^2}]

with n the unit normal out of the body (into the fluid), :math:`(n_1, n_2, n_3) = n` and
:math:`(n_4, n_5, n_6) = (x - x_{ref}) \times n`, body axes FRD about the reference point
(Newman 1977, "Marine Hydrodynamics", sec. 4.13-4.15, eqs. 4.148; the sign convention of
:func:`stripcoef.bem.bem_added_mass`, so that M_A is positive definite).

It is solved by the direct (Green's identity) method with constant-strength flat triangular
panels collocated at their centroids (Hess & Smith 1967, "Calculation of potential flow about
arbitrary bodies", Prog. Aero. Sci. 8; Newman 1977 eq. 4.97; Katz & Plotkin 2001, "Low-Speed
Aerodynamics", 2nd ed., sec. 9.2-9.6 and 10.4): with :math:`G = 1/(4\pi r)`, for x on S

.. math::
    \tfrac12\phi(x) - \iint_S \phi\,\frac{\partial G}{\partial n_\xi}\,dS_\xi
        = -\iint_S G\,\frac{\partial\phi}{\partial n_\xi}\,dS_\xi,
    \qquad \Big(\tfrac12 I - D\Big)\,\Phi = -S\,N,

:math:`S_{kl} = \iint_{T_l} G(x_k, \xi)\,dS` [m], :math:`D_{kl} = \iint_{T_l}
\partial G/\partial n_\xi\,dS` [-] (minus the solid angle of T_l seen from x_k over 4 pi),
N the (n, 6) generalised normals; one LU solves the six modes.  Near pairs (centroid distance
below :data:`NEAR_FACTOR` panel diameters) use the exact flat-triangle integrals (source:
Wilton et al. 1984, IEEE Trans. Antennas Propag. 32(3), eq. for :math:`\int 1/R\,dS`; dipole:
van Oosterom & Strackee 1983, IEEE Trans. Biomed. Eng. 30(2), the solid angle of a triangle);
pairs within :data:`MID_FACTOR` diameters a three-point rule, farther ones the one-point rule.  The self term is analytic (the same formulas, D = 0).

A body with mirror planes through the reference point (``mirrors``) and the remesher is solved
on the part on the planes' positive side (cut, capped, remeshed, its caps dropped) with image
panels (:mod:`stripcoef.hull.mirror_panels`): 2^k solves of N/2^k unknowns for k planes, the
couplings the planes forbid exactly zero.

Constant panels on a smooth body converge as 1/N (error ~ h^2, N panels).
:func:`panel_added_mass` solves several resolutions and Richardson-extrapolates the two finest,
N_1 < N_2, at the body's formal order p (:func:`edge_order`; on a smooth body p = 2, i.e.
:math:`A = (N_2 A_2 - N_1 A_1)/(N_2 - N_1)`; Richardson 1911, Roache 1998 eq. 5.4.1), then
takes the symmetric part (the exact A is symmetric, Newman 1977 eq. 4.150; the discrete one is
not, and its asymmetry is returned as a measure of the discretisation error).

A box or a plate (a parallelepiped) is panelled as its Capytaine references are, tensor grids
graded towards every edge (:mod:`stripcoef.hull.graded_panels`): the isotropic remesh put one
panel across a plate's rim and its in-plane terms came out up to 7.6 % high.  So is a right
prism within the level cap (a coarse cylinder: its rotation about the axis, which only the
facet edges make, wandered by up to 20 % between remeshed levels; ``graded_panels``).

Thin members (frame plates 12.7 mm, duct walls 5.6 mm, issue 32): on the same mesh this
method and Capytaine agree within 0.09 % on every diagonal term of the BlueROV2 Heavy's
united surface (2780 and 3914 faces) and within 0.03 % on the VideoRay Pro III's
(benchmarks/panels_vehicles.py), so the near-field integrals and the self terms of facing
panels are not where the slow convergence comes from.  It comes from the panellings: a
refined CAD or union tessellation keeps its slivers and, at the coarse level, panels as long
as the body (the VideoRay's 24-sided hull at 396 panels: pitch about the origin 39 % below
the remeshed solution, 2 % once those panels are split in four; the input is now refined to
at least twice its faces, :func:`panel_levels`), and an isotropic remesh cannot follow
members thinner than its edge (the BlueROV2 Heavy's collapse below about 2800 faces), so the
levels are not yet in the asymptotic range and their observed order wanders: the estimated
error of the extrapolated value is its step plus its last change (:func:`extrapolation_error`),
not a grid convergence index whose safety factor 3 assumes an order it cannot observe.

Edges: at a convex edge the flow is singular and the added mass converges at the order
:func:`edge_order` gives (4/3 in the panel size at a right-angled edge, 1 at a plate's rim),
not the smooth body's 2; the grid convergence index takes it as its formal order (on the
CAD-style shapes its estimate then covers 272 of 281 terms against Capytaine refined to
12,000-24,000 faces, 250 with the order 2: benchmarks/data/estimate_coverage.md), and the
value is extrapolated at it: against Capytaine on panels graded towards the edges (references
that assume no order, Eça & Hoekstra's least squares over four or five levels: the bluff
set's boxes and chamfered box, the CAD benchmark's plates and extruded polygons), the value
at the edge's order is closer than the value at order 2 on 134 of 155 terms, within 5 % on
153 (133 at order 2), median error 0.46 % (1.23 %), the estimate covering 154
(benchmarks/data/graded_value_order.md).  The edges
are read independently of the input's tessellation (:func:`edge_features`): a crease whose
normals turn by no more than the feature angle of mesh processing (30 degrees) is a facet of
a smooth surface, a fold (two faces in one plane, one folded back) a double sheet whose rim
is a knife edge only where it is a panel wide, and the members' thickness is measured with
or without the remesher.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from stripcoef.conventions import transform_matrix
from stripcoef.errors import InputError
from stripcoef.hull.bisection import (  # noqa: F401  (bisect_longest, refine, split_in_four re-exported)
    bisect_longest, enclosed_volume, refine, split_in_four, surface_area)
from stripcoef.hull.graded_panels import Prism, box_faces, box_level, prism_faces
from stripcoef.hull.graded_panels import thickness as box_thickness
from stripcoef.hull.memo import array_memo
from stripcoef.hull.mirror_panels import capped_part, drop_caps, solve_mirrored
from stripcoef.hull.input_ladder import (  # noqa: F401  (the coarsening, re-exported)
    CLUSTER_CELL, _cluster, coarsen, ladder_levels, vertex_quadrics)
from stripcoef.hull.panel_error import (  # noqa: F401  (the error rule, re-exported)
    ERROR_TOLERANCE, NEGLIGIBLE, estimated_error, extrapolation_error, ladder_extrapolation,
    finest_pair_under_refined, least_squares_error, relative_error, richardson_error)
from stripcoef.hull.remesh import AREA_TOLERANCE, FOLD_ANGLE, edge_for_panels, fold_mask
from stripcoef.hull.panel_kernels import (  # noqa: F401  (the kernels, re-exported)
    _FOUR_PI, DENSE_MID_FRACTION, MID_FACTOR, NEAR_FACTOR, _frames, _three_point_dense,
    generalised_normals, influence_matrices, solve_added_mass, triangle_integrals)

#: Default panels of the finer of the two resolutions [-] (the coarser has half as many).
DEFAULT_PANELS = 1600
#: Most panels one solve accepts (dense memory ~ 24 N^2 bytes, time ~ N^3) [-].
MAX_PANELS = 6000


#: Largest input mesh [faces]: beyond it the clustering alone exceeds the time budget.
MAX_INPUT_FACES = 2_000_000


#: Largest change of the enclosed volume by the coarsening [-]: beyond it the mesh has members
#: thinner than the panels (tubes, plates) that the clustering collapsed.
VOLUME_TOLERANCE = 0.02


def panel_levels(vertices, faces, panels: int, where=None):
    r"""The two panellings (coarse, fine) of the Richardson extrapolation.

    - A mesh of at most N/4 faces (N = ``panels``; boxes, coarse CAD, a vehicle file's
      surface): refined by longest-edge bisection to about :math:`N_1 = \max(N/4, 2F)`
      panels (F faces; :func:`refine`), and that split in four (:func:`split_in_four`):
      N_2 = 4 N_1, h halved on the same polyhedron.  At least twice the faces, so that the
      bisection splits the input's long faces rather than keeping them (it splits the
      longest first): a tessellation of F close to N/4 refined to N/4 keeps its slivers,
      and a level with panels as long as the body is not in the asymptotic range (the
      VideoRay Pro III's 24-sided surface, 360 faces: 396 panels, pitch 40 % below the
      reference, the two levels' extrapolation +24 %; at 640/2560 panels within 4 %,
      benchmarks/data/panel_estimate_rule.md).
    - A mesh of more than N faces: coarsened to N/2 and N panels independently
      (:func:`coarsen`: two approximations of the same surface, their geometric error ~h^2
      like the panel error); if that changes its volume by more than
      :data:`VOLUME_TOLERANCE` (members thinner than the panels collapsed), N is doubled
      while it stays within :data:`MAX_PANELS`.
    - Otherwise (and for thin members) both levels refine the mesh itself (its slivers are
      split too): to :math:`N_1 = \max(N/2, 1.25 F)` (F faces) and :math:`2 N_1` panels; when
      that exceeds :data:`MAX_PANELS`, a mesh of at most MAX_PANELS / 1.5 faces is solved as
      it is and refined to :math:`\max(N, 2 F)` (at most MAX_PANELS, at least 1.5 F) panels, so that
      ``panels`` may exceed the mesh's face count; a larger mesh is an error naming
      ``panels``.
    """
    v, f = np.asarray(vertices, float), np.asarray(faces, np.int64)
    dv = 0.0
    if 4 * len(f) <= panels:
        coarse = refine(v, f, max(panels // 4, 2 * len(f)))
        return [coarse, split_in_four(*coarse)]
    n = panels
    quadrics = vertex_quadrics(v, f) if len(f) > n else None
    vol = enclosed_volume(v, f)
    while len(f) > n:           # coarsen, with twice the panels while thin members collapse
        levels = [coarsen(v, f, k, quadrics) for k in (n // 2, n)]
        dv = max(abs(enclosed_volume(*lv) / vol - 1.0) for lv in levels)
        if dv <= VOLUME_TOLERANCE:
            return levels
        if 2 * n > MAX_PANELS:
            break
        n *= 2
    n1 = max(panels // 2, int(np.ceil(1.25 * len(f))))
    if 2 * n1 > MAX_PANELS and len(f) <= MAX_PANELS / 1.5:
        # a mesh of more than MAX_PANELS / 2.5 faces: the first level is the mesh itself (the
        # first member of the bisection family) and the second refines it to the panels asked
        # for or twice the mesh's faces (at least 1.5 times as many; the Richardson error
        # reports what that is worth)
        levels = [refine(v, f, max(panels // 2, len(f))),
                  refine(v, f, min(max(panels, 2 * len(f)), MAX_PANELS))]
        if len(levels[1][1]) >= 1.5 * len(levels[0][1]):
            return levels
    if 2 * n1 > MAX_PANELS:
        why = (f"the mesh has members thinner than {n} panels resolve (coarsening changes "
               f"its volume by {100 * dv:.1f} %) and " if dv > VOLUME_TOLERANCE else "")
        raise InputError(f"{why}its {len(f)} faces are too many to refine within "
                         f"{MAX_PANELS} panels", file=where,
                         key="panels", value=panels,
                         expected=f"a mesh of at most {MAX_PANELS / 2.5:.0f} faces (decimated "
                                  "in CAD, thin members kept)")
    return [refine(v, f, n1), refine(v, f, 2 * n1)]


def _check_closed(faces, where):
    from stripcoef.geometry.mesh import EdgeTopology

    topo = EdgeTopology(faces)
    if not topo.consistent:
        raise InputError("the panel method needs a closed surface with consistent winding",
                         file=where, key="mesh", value=f"{topo.open_edges} open or "
                         "non-manifold edges" if not topo.watertight else "inconsistent winding",
                         expected="a watertight mesh (load it with stripcoef.geometry.mesh."
                                  "load_mesh, which repairs what it can)")


def remeshed_levels(vertices, faces, panels: int, count: int = 3, area: float | None = None):
    """The family of :func:`_remeshed_levels` ((levels, mode) or ``None``)."""
    return _remeshed_levels(vertices, faces, panels, count, area)[0]


def _remeshed_levels(vertices, faces, panels: int, count: int = 3, area: float | None = None):
    r"""``count`` isotropic remeshes of the mesh (:func:`stripcoef.hull.remesh.remesh_family`)
    at :math:`N_k = N/2^{count-1-k}` panels (N = ``panels``, coarse to fine: the edge shrinks by
    :math:`\sqrt2` a level) and the :class:`~stripcoef.hull.remesh.Mode` that made them, or
    ``None`` when the remesher is not
    installed or refuses one.  One family of uniform panellings of the same surface, whatever
    the input's tessellation.  ``area``: the surface [m^2] whose N panels set the edges
    (default the mesh's own; a :func:`~stripcoef.hull.mirror_panels.capped_part` is
    remeshed at the whole body's edges).

    Thin members (issue 32): where the finest edge exceeds :data:`THIN_EDGE_RATIO` times the
    body's :func:`member_thickness` t, the family is remeshed in the thin-member modes of
    :mod:`stripcoef.hull.remesh` first (no edge flips, creases kept, the remesh within
    ``KNIFE_DISTANCE`` of the input).  Basis: a constant-panel solution approximates the
    potential by one value per flat panel (Hess & Smith 1967), so a member narrower than a
    panel -- the two faces of a plate closer than the edge -- is not represented by panels
    of its own, and Richardson extrapolation and the grid convergence index hold only once
    the levels are in the asymptotic range, whose precondition is that the grids resolve the
    geometry's smallest length scale (Roache 1998 ch. 5; Oberkampf & Roy 2010 ch. 8); the
    rule taken is the plain one, edge no longer than the thickness (argued, not a published
    constant).  Below that edge
    the remesh with flips, whose area and volume stay within the remesher's tolerances, joins
    the two faces of a plate and the levels converge to another surface: the frames of the
    seed 1375923287 of benchmarks/cad_shapes.py (plates 17-27 mm, edges 22-36 mm) came out
    +2.3 to +4.7 % in surge against the Capytaine references at 12,000-17,000 faces
    (reference_tables/bem/cad_shapes_fine_levels.csv) with estimates of 0.2-2.1 %; frame 21
    (17-mm plates) in one y-mirrored level at 7232 panels: surge 3.528 with flips, 3.471
    without (reference 3.467).  In the thin-member modes: -0.5 to +0.8 %
    (docs/performance.md, "Thin members and the panel family").

    Each level refines the one before by Celik et al. 2008's r >= 1.3 (``MIN_FACE_RATIO``
    in faces) where some mode fits it within the face limit, else by ``LEAST_FACE_RATIO``
    (:func:`_family`): the creases of thin members hold the coarse levels' counts, and the
    Richardson step multiplies the last change by :math:`1/(r^p - 1)`, 4 at r = 1.25 in
    faces and the knife edge's p = 1.  The BlueROV2 Heavy's no-flip levels 1942/2760/4306
    (r = 1.19, 1.25; one-level surge +23, +13, +6 % of its Capytaine reference, pre-asymptotic
    at 5.6-mm duct walls) were extrapolated to surge -22.8 %, yaw -34.4 %; with r >= 1.3 no
    remesh mode refines so and its levels are the input's faces bisected, 1712/3966/9120:
    every diagonal term within -8.5 to -1.7 % (python -m benchmarks.frame_remesh_trace,
    docs/performance.md, "The remesh family on the BlueROV2 Heavy: traced")."""
    from stripcoef.hull import remesh

    if not remesh.available():
        return None, float("inf")
    area = surface_area(vertices, faces) if area is None else float(area)
    edges = [remesh.edge_for_panels(area, max(50, int(round(panels / 2 ** (count - 1 - k)))))
             for k in range(count)]
    out = _family(vertices, faces, edges, remesh.MODES)
    if out is None or out[1].bisect:
        return out, float("inf")
    thickness = member_thickness(*out[0][0])
    if edges[-1] <= THIN_EDGE_RATIO * thickness or not out[1].flips:
        return out, thickness
    # a member thinner than the finest edge: the remeshes with flips join its faces (module
    # docstring, "Thin members"); the family in the feature-preserving modes first
    thin = _family(vertices, faces, edges, _thin_modes())
    return (out if thin is None or thin[1].bisect else thin), thickness


def _family(vertices, faces, edges, modes):
    """The first of ``modes`` whose levels each refine the one before by Celik et al.'s
    r >= 1.3 (:data:`~stripcoef.hull.remesh.MIN_FACE_RATIO` in faces), else by
    :data:`~stripcoef.hull.remesh.LEAST_FACE_RATIO` (:func:`stripcoef.hull.remesh.
    remesh_family`; (levels, mode) or ``None``)."""
    from stripcoef.hull import remesh

    with warnings.catch_warnings(record=True) as first:
        warnings.simplefilter("always")
        out = remesh.remesh_family(vertices, faces, edges, min_ratio=remesh.MIN_FACE_RATIO,
                                   modes=modes)
    if out is None:
        return remesh.remesh_family(vertices, faces, edges, modes=modes)
    for w in first:
        warnings.warn_explicit(w.message, w.category, w.filename, w.lineno)
    return out


#: Area fraction [-] below which the thinner members of a body are not counted in
#: :func:`member_thickness` (the area-weighted percentile: a member with less than this
#: share of the surface does not set the panel size).
THICKNESS_PERCENTILE = 0.05
#: Largest finest-level edge over the member thickness [-] before the thin-member family is
#: used (the edge no longer than the thickness: panels resolve the member).
THIN_EDGE_RATIO = 1.0


def _thin_modes():
    from stripcoef.hull.remesh import MODES

    return tuple(m for m in MODES if not m.flips and not m.bisect) + tuple(
        m for m in MODES if m.flips) + tuple(m for m in MODES if m.bisect)


def member_thickness(vertices, faces, rays: int = 256) -> float:
    r"""Thickness of the body's thinnest members that matter [m]: the distance from a face's
    centroid along its inward normal to the first face hit (the shape diameter of Shapira
    et al. 2008, "Consistent mesh partitioning and skeletonisation using the shape diameter
    function", Visual Computer 24, with one ray on the normal), its area-weighted
    :data:`THICKNESS_PERCENTILE` quantile over at most ``rays`` faces (every k-th face of a
    uniform panelling); the ray-triangle test of Moeller & Trumbore 1997 ("Fast, minimum
    storage ray-triangle intersection", J. Graphics Tools 2(1)), vectorised (trimesh's
    ray casting needs rtree or embree, neither in the base install).  ``inf`` when no ray
    hits (an open surface)."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    tri = v[f]
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    cr = np.cross(e1, e2)
    dbl = np.linalg.norm(cr, axis=1)
    ok_face = dbl > 0
    scale = float(np.ptp(v, axis=0).max())
    src = np.flatnonzero(ok_face)[::max(1, int(np.ceil(ok_face.sum() / rays)))]
    orig = tri[src].mean(axis=1)
    d = -cr[src] / dbl[src, None]
    depth = np.full(len(src), np.inf)
    chunk = max(1, 2_000_000 // len(f))
    for s in range(0, len(src), chunk):
        o, dd = orig[s:s + chunk], d[s:s + chunk]
        p = np.cross(dd[:, None, :], e2[None])                   # (rays, faces, 3)
        det = np.einsum("mk,rmk->rm", e1, p)
        ok = np.abs(det) > 1e-12 * scale ** 2
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        tv = o[:, None, :] - tri[None, :, 0]
        u = np.einsum("rmk,rmk->rm", tv, p) * inv
        q = np.cross(tv, e1[None])
        w = np.einsum("rk,rmk->rm", dd, q) * inv
        t = np.einsum("mk,rmk->rm", e2, q) * inv
        hit = ok & (u >= 0) & (w >= 0) & (u + w <= 1) & (t > 1e-9 * scale)
        hit[np.arange(len(o)), src[s:s + chunk]] = False          # not the face itself
        depth[s:s + chunk] = np.where(hit, t, np.inf).min(axis=1)
    good = np.isfinite(depth)
    if not good.any():
        return float("inf")
    x, w = depth[good], dbl[src][good]
    o = np.argsort(x)
    cw = np.cumsum(w[o])
    return float(x[o][min(len(x) - 1, np.searchsorted(cw, THICKNESS_PERCENTILE * cw[-1]))])


def fine_smooth_input(vertices, faces, panels: int, features) -> bool:
    r"""Whether the closed mesh (vertices [m], faces) is panelled by the input family's
    coarsened levels in every install, the remesher installed or not (:func:`panel_added_mass`,
    ``auto``; remesh32h): a rule about the mesh, not about what is installed.

    - More faces than the ``panels`` [-] of the finest level (:func:`panel_levels` coarsens);
    - every edge shorter, in each coordinate, than that level's clustering cell
      :math:`0.75\,h_N` [m] (:data:`~stripcoef.hull.input_ladder.CLUSTER_CELL`, :math:`h_N`
      from :func:`~stripcoef.hull.remesh.edge_for_panels`): its two ends then fall in the same
      or neighbouring cells wherever the grid lies, each panel vertex is the quadric-optimal
      point of a cluster of input vertices and each panel edge joins neighbouring cells, so
      the panels are set by the grid and not by the tessellation, which is what the isotropic
      remesh is for (Rossignac & Borrel 1993; Lindstrom 2000).  A longer face spans cells and
      survives as a sliver (the VideoRay Pro III's 64-sided surface coarsened: pitch -63 %,
      docs/performance.md);
    - no convex edge sharper than :data:`FEATURE_ANGLE` and no fold (``features``, the mesh's
      :class:`EdgeFeatures`): the remesher keeps sharp edges as creases;
    - on the finest coarsened level, the input's area within the remesher's
      :data:`~stripcoef.hull.remesh.AREA_TOLERANCE` and its volume within
      :data:`VOLUME_TOLERANCE` (a member thinner than the cell collapses), and no member
      thinner than :math:`h_N` (:func:`member_thickness`, :data:`THIN_EDGE_RATIO`: the
      remeshed family's own test for its thin-member modes).

    No new constant.  Measured (``python -m benchmarks.remesh32h_paths``,
    benchmarks/data/remesh32h_trace.md): on 7 meshes it keeps, the two families' worst
    diagonal terms agree within 0.15 % on six (a near-sphere's tiny roll 3.4 % coarsened, warned,
    against 1.3 % remeshed) at 0.3-0.4 s of CPU against 2.8-13.6 s; on the 8 fine smooth
    meshes it declines, the remesh is the more accurate on every one (0.29-0.52 % against
    0.47-1.86 %)."""
    v, f = np.asarray(vertices, float), np.asarray(faces, np.int64)
    if len(f) <= panels or features.turning > 0.0 or features.folds:
        return False
    h = edge_for_panels(surface_area(v, f), panels)
    # every edge within one cell in each coordinate: its two ends fall in the same or
    # neighbouring cells wherever the grid lies, so every panel edge joins neighbours
    tri = v[f]
    if not float(np.abs(tri - np.roll(tri, 1, axis=1)).max()) < CLUSTER_CELL * h:
        return False
    # the thickness on the finest coarsened level (the rays of member_thickness cost ~ faces:
    # on a 19,200-face input 0.5-1 s, on the level 0.04 s), where the clustering kept the
    # surface: a member thinner than the cell collapses and takes its area and volume with it
    # (the remesher's and the coarsening's own tolerances)
    cv, cf = coarsen(v, f, panels)
    if not (abs(surface_area(cv, cf) / surface_area(v, f) - 1.0) <= AREA_TOLERANCE
            and abs(enclosed_volume(cv, cf) / enclosed_volume(v, f) - 1.0) <= VOLUME_TOLERANCE):
        return False
    return bool(h <= THIN_EDGE_RATIO * member_thickness(cv, cf))


#: Panel families of :func:`panel_added_mass` ("auto": the isotropic remesh when the remesher
#: is installed but on a fine smooth input, else the refined or coarsened input).
FAMILIES = ("auto", "remesh", "input")


def _solve_level(pv, pf, scale, rho, about, near_factor, mirrors=()):
    r"""(panels, 6x6 added mass about ``about``) of one level; with ``mirrors`` the level is a
    remeshed :func:`~stripcoef.hull.mirror_panels.capped_part`, solved without its caps with
    image panels (:mod:`stripcoef.hull.mirror_panels`; panels: those of the whole mirrored
    panelling).  Solved once per process for the same panels and settings
    (:func:`_solved_level`: a vehicle file's surface is estimated by many commands and tests,
    the BlueROV2 Heavy's two levels about 8 s each time).

    Without mirrors the level is solved about the origin of its own coordinates and moved to
    ``about`` (:math:`p`) by the rigid-body transfer of the matrix,

    .. math:: A_p = H(-p)^T A_0\, H(-p),\qquad
              H(-p) = \begin{bmatrix} I & S(p) \\ 0 & I \end{bmatrix}

    (:func:`stripcoef.conventions.transform_matrix`; Fossen 2011 sec. 7.5.3, eq. 7.248), exact
    for each level's unsymmetrised matrix: the generalised normals (Newman 1977 eq. 4.104)
    about p are those about the origin times :math:`H(-p)`, row by row
    :math:`(n^T, ((x - p)\times n)^T) = (n^T, (x\times n)^T)\, H(-p)` since
    :math:`n^T S(p) = -(p\times n)^T`; the potentials are linear in them, so
    :math:`A = -\rho \sum a\, N^T \Phi` (eq. 4.148) takes the congruence.  Files of one
    surface that differ only by their reference point or centre of gravity share one solve
    [kg, kg m, kg m^2].  A mirrored level's planes pass through ``about``: solved there."""
    pv = np.ascontiguousarray(pv, dtype=float)
    pf = np.ascontiguousarray(pf, dtype=np.int64)
    about = tuple(float(x) for x in np.ravel(about))
    if mirrors:
        return _solved_level(pv, pf, float(scale), float(rho), about, float(near_factor),
                             tuple(mirrors))
    n, a = _solved_level(pv, pf, float(scale), float(rho), (0.0, 0.0, 0.0), float(near_factor),
                         ())
    if any(about):
        a = transform_matrix(a, to_point=about)
    return n, a


def _solved_panels(level, mirrors, about) -> int:
    """Panels of the whole panelling :func:`_solve_level` solves for ``level`` (vertices
    [m], faces): with ``mirrors`` the part's faces without its caps
    (:func:`~stripcoef.hull.mirror_panels.drop_caps`) times 2^k, else its faces [-]."""
    if not mirrors:
        return len(level[1])
    part = drop_caps(*level, mirrors, about)
    return 0 if part is None else (2 ** len(mirrors)) * len(part[1])


@array_memo(maxsize=32)
def _solved_level(pv, pf, scale: float, rho: float, about: tuple, near_factor: float,
                  mirrors: tuple):
    """:func:`_solve_level` of float64 vertices, int64 faces and plain numbers (the memo's
    key, :func:`stripcoef.hull.memo.array_memo`)."""
    n, a = _solve_level_now(pv, pf, scale, rho, np.array(about), near_factor, mirrors)
    return n, np.array(a, dtype=float)


def _solve_level_now(pv, pf, scale, rho, about, near_factor, mirrors=()):
    """:func:`_solve_level`, computed."""
    if mirrors:
        pv, pf = drop_caps(pv, pf, mirrors, about)
    ptri = pv[pf]
    # zero-area panels (a collinear triangle of a remesh without flips) carry no area and
    # would make the influence matrices singular (NaN)
    keep = np.linalg.norm(np.cross(ptri[:, 1] - ptri[:, 0], ptri[:, 2] - ptri[:, 0]),
                          axis=1) > 1e-12 * scale ** 2
    if mirrors:
        return (2 ** len(mirrors)) * int(keep.sum()), solve_mirrored(
            ptri[keep], mirrors, rho=rho, about=about, near_factor=near_factor)
    return int(keep.sum()), solve_added_mass(ptri[keep], rho=rho, about=about,
                                             near_factor=near_factor)


def panel_added_mass(mesh, *, rho: float, about=(0.0, 0.0, 0.0), panels: int = DEFAULT_PANELS,
                     extrapolate: bool = True, near_factor: float = NEAR_FACTOR,
                     source: str = "", family: str = "auto", tolerance: float | None = None,
                     max_panels: int | None = None, mirrors=(),
                     value_pair: str = "finest") -> tuple[np.ndarray, dict]:
    r"""6x6 added mass of a closed body in unbounded fluid by the 3D panel method.

    .. math:: A = A_1 + \frac{A_1 - A_2}{r_{21}^{p_f} - 1},\qquad
              A_k = -\rho \sum_p a_p\, n(x_p)\, \Phi_k(x_p)^T,\qquad
              r_{21} = \sqrt{N_1/N_2}

    (module docstring; Richardson extrapolation of the two finest levels at the body's formal
    order :math:`p_f` in the panel size, :func:`edge_order`: on a smooth body 2, the error of
    constant panels ~ 1/N, i.e. :math:`(N_1 A_1 - N_2 A_2)/(N_1 - N_2)`; 4/3 at a
    right-angled edge, 1 at a knife edge), symmetric part.
    The levels: a box or a plate (``family`` "auto", a parallelepiped,
    :func:`stripcoef.hull.graded_panels.box_faces`) three tensor grids graded towards its
    edges at about N/4, N/2 and N panels, its thickness crossed by several rows
    (:mod:`stripcoef.hull.graded_panels`; the seed's plates within 2.3 % of their edge-graded
    references where the isotropic remesh was up to 7.6 % off: benchmarks/data/
    plate_panels.md); else with the remesher (``family`` "auto" or "remesh", the ``remesh``
    extra) three isotropic remeshes at N/4, N/2 and N panels (:func:`remeshed_levels`); without it
    ("input"), on an input of at most N/4 faces two nested pairs of its faces bisected and
    split in four (:mod:`stripcoef.hull.input_ladder`, its value the finer pair's
    extrapolation, :func:`ladder_extrapolation`), else the two panellings of
    :func:`panel_levels`.  The estimated error of each term
    of the extrapolated value, with three levels or more, is its step from the finest level
    plus its change since the level before (:func:`extrapolation_error`), with two levels
    Roache's two-grid index (:math:`F_s = 3`) about the finest plus the step
    (:func:`estimated_error`), each no smaller than the finest solve's asymmetry; with four
    levels or more the error returned (the band shown) is Eça & Hoekstra's least-squares
    uncertainty moved to the value (:func:`least_squares_error`) and the estimate above
    decides the refinement and the warning alone; the order
    is that of the body's sharpest convex edge (:func:`edge_order`: 2 on a smooth body, 4/3
    at a right-angled edge, 1 at a knife edge or a member thinner than the panels).
    While some term's error exceeds ``tolerance`` of the diagonal scale (:func:`relative_error`:
    a diagonal term's own value, a coupling's :math:`\sqrt{A_{ii} A_{jj}}`) and a level of
    twice the finest panels fits within ``max_panels``, that level is added and the estimate
    repeated ("refine until converged"; at least four levels where they fit), a remesh of at
    least Celik et al.'s r >= 1.3 over the finest where it fits (:func:`stripcoef.hull.remesh.
    added_level`).  Levels whose finest edge is longer than the body's
    :func:`member_thickness` (thin plates and walls) are remeshed without edge flips
    (:func:`remeshed_levels`).

    Parameters
    ----------
    mesh : trimesh.Trimesh or MeshBody
        Closed body in FRD body axes [m], normals out of the body (a MeshBody's mesh is).
    rho : float
        Fluid density [kg/m^3].
    about : (3,)
        Reference point of the rotations and moments, body axes [m].
    panels : int
        Panels of the finest first resolution (:data:`DEFAULT_PANELS`; at most
        :data:`MAX_PANELS`).
    extrapolate : bool
        Several resolutions, extrapolated (default); ``False``: one solve at ``panels``.
    source : str
        Name of the mesh for error messages.
    family : str
        "auto", "remesh" (an error without the remesher) or "input" (:data:`FAMILIES`).
    tolerance : float
        Relative error [-] the refinement aims at (default :data:`ERROR_TOLERANCE`).
    max_panels : int
        Most panels of an added level (default ``2 * panels`` within :data:`MAX_PANELS`);
        a level solved with k mirror planes (2^k solves of N/2^k unknowns) may have up to
        ``MAX_PANELS * 2^k`` panels.
    mirrors : iterable of str
        Mirror planes of the body through ``about`` (``x``, ``y``, ``z``: the coordinate each
        reverses; :func:`stripcoef.assembly.symmetry.strips_mirror_symmetries`): with the
        remesher the levels are remeshes of the closed part on the planes' positive side
        (:func:`~stripcoef.hull.mirror_panels.capped_part`, at the whole body's edges), solved
        without their caps with image panels (:mod:`stripcoef.hull.mirror_panels`: 2^k
        solves of N/2^k unknowns, the couplings the planes forbid exactly zero); the panel
        counts are the whole mirrored panelling's.  Without the remesher (the input family)
        the whole body is solved.
    value_pair : str
        "finest" (default): the value from the two finest levels; "nested" (an option, not
        adopted: :func:`~stripcoef.hull.panel_error.finest_pair_under_refined`, measured in
        benchmarks/data/frame32d_trace.md) the two nested pairs' where the finest pair refines
        by less than Celik et al.'s r = 1.3.

    Returns
    -------
    (ndarray (6, 6), dict)
        M_A [kg, kg m, kg m^2] and ``{"panels": the levels' panel counts, coarse to fine,
        "asymmetry": max|A - A^T| / max|A| of the finest solve [-], "error": the estimated
        error of each term [kg, kg m, kg m^2] (``None`` without extrapolation; four levels or
        more: the least-squares band), "estimate": the estimate the refinement and
        "converged" read [kg, kg m, kg m^2] (the error itself below four levels), "order":
        the order used per term [-], "safety": the safety factor per term [-] (1 with three
        levels: :func:`extrapolation_error` has none; Eça & Hoekstra's with four or more),
        "family": the panellings' family ("fine_smooth": the input's coarsened levels kept by
        :func:`~stripcoef.hull.panels.fine_smooth_input`), "converged": whether every
        term's estimate (about the volume centroid) is within ``tolerance``,
        "length": the body's largest extent [m] (:func:`relative_error`),
        "formal_order": the index's formal order [-] (:func:`edge_order`), "levels": each
        level's solved matrix, coarse to fine, not symmetrised [kg, kg m, kg m^2]}``.
    """
    from stripcoef.geometry.mesh import volume_centroid
    from stripcoef.hull.convergence import grid_convergence_index, richardson

    # several bodies or overlapping parts: one closed surface (MeshBody.united, a boolean union)
    body = mesh.united() if hasattr(mesh, "united") else getattr(mesh, "mesh", mesh)
    v = np.asarray(body.vertices, float)
    f = np.asarray(body.faces, np.int64)
    named = getattr(mesh, "source", "")        # a MeshBody's file (a Trimesh's is no str)
    where = source or (named if isinstance(named, str) else "") or None
    if not (isinstance(panels, (int, np.integer)) and 50 <= panels <= MAX_PANELS):
        raise InputError("panel count out of range", key="panels", value=panels,
                         expected=f"an integer from 50 to {MAX_PANELS}")
    if value_pair not in ("finest", "nested"):
        raise InputError("unknown value pair", key="value_pair", value=value_pair,
                         expected="finest or nested")
    if family not in FAMILIES:
        raise InputError("unknown panel family", key="family", value=family,
                         expected=" or ".join(FAMILIES))
    planes = tuple(sorted(set(mirrors)))
    if not set(planes) <= {"x", "y", "z"}:
        raise InputError("unknown mirror plane", key="mirrors", value=",".join(planes),
                         expected="x, y or z (the coordinate the reflection reverses)")
    tol = ERROR_TOLERANCE if tolerance is None else float(tolerance)
    # (the cap on one solve's unknowns, MAX_PANELS, is applied below: with k mirror planes a
    # level of N panels is 2^k solves of N/2^k unknowns)
    cap = min(MAX_PANELS, 2 * panels) if max_panels is None else int(max_panels)
    if len(f) > MAX_INPUT_FACES:
        raise InputError("mesh too large for the panel method's time budget", file=where,
                         key="mesh", value=f"{len(f)} faces",
                         expected=f"at most {MAX_INPUT_FACES} faces (decimate it in CAD)")
    if len(f) == 0 or not np.all(np.isfinite(v)):
        raise InputError("empty mesh or non-finite vertices", file=where, key="mesh",
                         value=f"{len(f)} faces", expected="a closed triangle mesh")
    _check_closed(f, where)
    tri = v[f]
    dbl = np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    scale = np.ptp(v, axis=0).max()
    if np.any(dbl <= 1e-12 * scale ** 2):
        raise InputError("degenerate (zero-area) faces", file=where, key="mesh",
                         value=f"{int(np.sum(dbl <= 1e-12 * scale ** 2))} faces",
                         expected="faces of non-zero area (load_mesh removes them)")
    vol = enclosed_volume(v, f)
    if not vol > 1e-9 * scale ** 3:
        raise InputError("the mesh's normals point into the body or it encloses no volume",
                         file=where, key="mesh", value=f"volume {vol:.3g} m^3",
                         expected="outward normals (load_mesh orients them)")
    if not extrapolate:
        lv = coarsen(v, f, panels) if len(f) > panels else refine(v, f, panels)
        n, a = _solve_level(*lv, scale, rho, about, near_factor)
        asym = float(np.abs(a - a.T).max() / np.abs(a).max())
        return 0.5 * (a + a.T), {"panels": (n,), "asymmetry": asym, "error": None,
                                 "estimate": None, "order": None, "safety": None, "family": "input",
                                 "converged": None, "formal_order": None, "levels": (a,)}
    # with mirror planes: the closed part on their positive side remeshed at the whole body's
    # edges and solved with image panels (mirror_panels); else, or where that fails, the body
    src, solve_planes, area = (v, f), (), surface_area(v, f)
    family_out, thickness = None, float("inf")
    # a box or a plate (a parallelepiped): panels graded towards its edges (graded_panels),
    # with or without the remesher
    box = (box_faces(v, f) or prism_faces(v, f, min(cap, MAX_PANELS * 2 ** len(planes)))
           if family == "auto" else None)
    if box is not None:
        family_out, thickness = (None, None), box_thickness(box)
    # the body's sharpest convex edge, facets of smooth parts and folds left out [rad]
    features = edge_features(v, f)
    # a fine tessellation of a smooth body: its coarsened levels in every install
    # (fine_smooth_input; benchmarks/data/remesh32h_trace.md)
    fine = family == "auto" and box is None and fine_smooth_input(v, f, panels, features)
    if fine:
        family = "input"
    if planes and family in ("auto", "remesh") and box is None:
        part = capped_part(v, f, planes, about)
        family_out, thickness = (_remeshed_levels(*part, panels, area=area)
                                 if part is not None else (None, float("inf")))
        if family_out is not None:
            # (the refinement keeps the whole body's cap: a fifth level of 2^(k/2) cap panels,
            # as cheap with k planes as a full solve of cap, cut the warnings on a fresh seed
            # of benchmarks/cad_shapes.py from 34 to 29 of 38 shapes but its extrapolations
            # covered their error in 91 % of terms instead of 96 %: docs/performance.md)
            src, solve_planes = part, planes
    if family_out is None and family in ("auto", "remesh"):
        family_out, thickness = _remeshed_levels(v, f, panels)
    levels, mode = family_out if family_out is not None else (None, None)
    if box is not None:
        # (each level at least LEAST_FACE_RATIO times the panels of the one before: the
        # graded counts are steps)
        from stripcoef.hull.remesh import LEAST_FACE_RATIO

        levels, whole = [], 0
        for k in range(3):
            want = max(50, round(panels / 2 ** (2 - k)), int(LEAST_FACE_RATIO * whole) + 1)
            pv, pf, solve_planes, row = box_level(box, want, planes, about)
            levels.append((pv, pf))
            whole = len(pf) * 2 ** len(solve_planes)
    if levels is None and family == "remesh":
        raise InputError("the isotropic remesher is not installed or could not follow the "
                         "surface", file=where, key="family", value=family,
                         expected="pip install 'stripcoef[remesh]' (pymeshlab), or the input "
                                  "family")
    if box is not None:
        used = "graded towards the edges (" + ("a prism)" if isinstance(box, Prism) else "a box)")
    elif levels is None:
        used = "refined/coarsened input"
    elif mode.bisect:
        used = "input faces bisected (no remesh family kept the surface and refined)"
    else:
        used = "isotropic remesh (pymeshlab" + ("" if mode.flips else ", no flips: thin members") + ")"
    ladder = False
    if levels is None:
        # the input family: two nested pairs where they fit one solve (input_ladder), else
        # the two levels of panel_levels
        levels = ladder_levels(v, f, panels, MAX_PANELS)
        ladder = levels is not None
        if ladder:
            used = "refined/coarsened input, two nested pairs"
        else:
            levels = panel_levels(v, f, panels, where)
    if not np.isfinite(thickness):
        # the input family (no remesher) or the input's faces bisected: the members'
        # thickness from the finest panelling, by the same ray casts (member_thickness needs
        # neither pymeshlab nor rtree), so the knife-edge rule applies in every install
        thickness = member_thickness(*levels[-1])
    counts, mats, nominal = [], [], panels
    centroid = volume_centroid(v, f)         # where the refinement is judged (below)
    for pv, pf in levels:
        n, a = _solve_level(pv, pf, scale, rho, about, near_factor, solve_planes)
        counts.append(n)
        mats.append(a)
    while True:
        if counts[-1] <= counts[-2]:
            raise InputError("the panel resolutions do not refine", file=where, key="panels",
                             value=counts, expected="a finer last resolution (more panels)")
        # levels whose finest edge exceeds the member thickness cannot be in the asymptotic
        # range (_remeshed_levels): no term takes the safety factor of 1.25; the order the
        # index may use, and the value's extrapolation takes, is that of the body's sharpest
        # edge (edge_order; module docstring: benchmarks/data/graded_value_order.md)
        # (the graded box: its largest row across the thickness, far below it)
        finest_edge = row if box is not None else edge_for_panels(area, counts[-1])
        formal = edge_order(features.turning, finest_edge, thickness,
                            sheet=features.sheet_wider_than(THIN_EDGE_RATIO * finest_edge))
        a = richardson(mats[-2], mats[-1], counts[-2], counts[-1], order=formal)
        if ladder or (value_pair == "nested" and finest_pair_under_refined(counts)):
            # two nested pairs (the input ladder; or, an option, the finest pair under Celik
            # et al.'s r = 1.3): the finer pair's extrapolation, its step plus its change
            # since the coarser pair's (ladder_extrapolation)
            a, error = ladder_extrapolation(mats[-4:], counts[-4:], formal)
            order, safety = np.full((6, 6), formal), np.ones((6, 6))
            at_c = [transform_matrix(m, from_point=about, to_point=centroid) for m in mats[-4:]]
            converged = bool(relative_error(*ladder_extrapolation(at_c, counts[-4:], formal),
                                            scale).max() <= tol)
        elif len(mats) >= 3:
            # the extrapolated value's own error: its step from the finest level plus its
            # change since the level before (extrapolation_error; benchmarks/data/
            # panel_estimate_rule.md)
            error = extrapolation_error(mats, counts, formal)
            order, safety = np.full((6, 6), formal), np.ones((6, 6))
            # whether to refine, judged about the volume centroid, so that the levels do not
            # depend on the reference point (each level moves there exactly, _solve_level)
            at_c = [transform_matrix(m, from_point=about, to_point=centroid) for m in mats]
            converged = bool(relative_error(
                richardson(at_c[-2], at_c[-1], counts[-2], counts[-1], order=formal),
                extrapolation_error(at_c, counts, formal), scale).max() <= tol)
        else:
            # two levels: Roache's two-grid index about the finest (F_s = 3) plus the step
            gci, order, safety = grid_convergence_index(mats, counts, formal_order=formal)
            error = estimated_error(mats[-1], a, gci)
            converged = bool(relative_error(a, error, scale).max() <= tol)
        nxt = 2 * nominal
        # at least four levels: three levels' estimate exceeds 5 % on 35 of the 38 shapes of
        # benchmarks/data/panel_estimate_rule.md; the box of tests/test_hull_panels.py 2.4 % off at three
        if (converged and len(mats) >= 4) or nxt > min(cap, MAX_PANELS * 2 ** len(solve_planes)) \
                or used.startswith("refined"):
            break
        from stripcoef.hull import remesh

        if box is not None:
            pv, pf, _, row = box_level(box, max(nxt, int(remesh.LEAST_FACE_RATIO * counts[-1])
                                                + 1), solve_planes, about)
            lv = (pv, pf)
        else:
            # Celik et al.'s r >= 1.3 over the finest, grown where creases hold the count
            # (remesh.added_level), judged in the panels solved, the counts the extrapolation
            # reads (a mirrored level's caps are not solved: benchmarks/data/slocum32s_trace.md)
            lv = remesh.added_level(*src, remesh.edge_for_panels(area, nxt), mode, counts[-1],
                                    lambda x: _solved_panels(x, solve_planes, about))
            if lv is None:
                break
        levels.append(lv)
        n, m = _solve_level(*lv, scale, rho, about, near_factor, solve_planes)
        counts.append(n)
        mats.append(m)
        nominal = nxt
    asym = float(np.abs(mats[-1] - mats[-1].T).max() / np.abs(mats[-1]).max())
    # four levels or more: the band shown is Eça & Hoekstra's least-squares uncertainty; the
    # refinement and the warning read the step plus the change (panel_error's docstring)
    estimate = error
    if len(mats) >= 4:
        error, safety = least_squares_error(mats, counts, a)
    return 0.5 * (a + a.T), {"panels": tuple(counts), "asymmetry": asym, "error": error,
                             "estimate": estimate,
                             "order": order, "safety": safety, "family": used,
                             "converged": converged, "formal_order": formal,
                             "fine_smooth": fine,
                             "length": float(scale),
                             "levels": tuple(np.array(m) for m in mats)}


#: Formal order in the panel size of constant panels on a smooth closed body [-] (their error
#: goes as 1/N, Hess & Smith 1967; :mod:`stripcoef.hull.convergence`).
SMOOTH_ORDER = 2.0


#: Turning of the normal [deg] up to which a convex crease of the input mesh is read as the
#: tessellation of a smooth surface, not an edge of the body: the feature (crease) angle of
#: mesh processing, 30 degrees in VTK's vtkFeatureEdges and vtkPolyDataNormals (Schroeder,
#: Martin & Lorensen 2006, "The Visualization Toolkit", 4th ed., Kitware, ch. 9, feature
#: edges) and in MeshLab's remesher (:data:`stripcoef.hull.remesh.FEATURE_ANGLE`, the crease
#: angle the remeshed levels keep).  A cylinder exported with 12 or more facets (CAD tools'
#: coarsest angular tolerance, 30 degrees) is smooth; a box's, a chamfer's (45 degrees) or a
#: plate's rim is an edge.
FEATURE_ANGLE = 30.0
# FOLD_ANGLE (imported from stripcoef.hull.remesh): the largest departure from 180 degrees
# of the turning at a fold, two faces in one plane, one folded back onto the other
#: Most folds :meth:`EdgeFeatures.sheet_wider_than` probes (every k-th beyond) [-]: a bound
#: on its time (one pass over the faces per fold), not a tolerance.
MAX_FOLD_PROBES = 64


@dataclass(frozen=True)
class EdgeFeatures:
    """The convex edges of a closed surface that set the panel method's formal order
    (:func:`edge_features`)."""

    #: the largest turning of the normal at a convex edge [rad], creases up to
    #: :data:`FEATURE_ANGLE` and folds left out (0: no edge)
    turning: float
    #: per fold (:data:`FOLD_ANGLE`): the midpoint of its edge [m] (k, 3)
    fold_points: np.ndarray
    #: per fold: the unit vector in the folded faces' plane, normal to the edge, towards them
    fold_inward: np.ndarray
    #: per fold: the unit normal of one of its two faces
    fold_normal: np.ndarray
    #: the surface's triangles (m, 3, 3) [m], for :meth:`sheet_wider_than`
    triangles: np.ndarray

    @property
    def folds(self) -> int:
        """Number of fold edges [-]."""
        return len(self.fold_points)

    def sheet_wider_than(self, width: float) -> bool:
        r"""Whether some fold closes a double sheet at least ``width`` [m] wide: the point
        ``width`` into the fold from its edge's midpoint lies on two faces of opposite
        normals in the fold's plane (within :math:`10^{-6}` of the body's size).  A sheet
        narrower than a panel is not resolved by the panels (a tessellation artefact such as
        eROV's slivers); a wider one is a member of zero thickness, whose rim is a knife
        edge (:func:`edge_order`)."""
        if not self.folds or not width > 0.0:
            return False
        tri = self.triangles
        scale = float(np.ptp(tri.reshape(-1, 3), axis=0).max())
        e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        cr = np.cross(e1, e2)
        dbl = np.linalg.norm(cr, axis=1)
        n = cr / np.where(dbl > 0, dbl, 1.0)[:, None]
        d00, d01, d11 = (np.einsum("ij,ij->i", e1, e1), np.einsum("ij,ij->i", e1, e2),
                         np.einsum("ij,ij->i", e2, e2))
        den = d00 * d11 - d01 * d01
        ok = den > 0
        den = np.where(ok, den, 1.0)
        step = max(1, int(np.ceil(self.folds / MAX_FOLD_PROBES)))
        probes = (self.fold_points + width * self.fold_inward)[::step]
        for p, nf in zip(probes, self.fold_normal[::step]):
            d = p - tri[:, 0]
            # in the fold's plane, to round-off and the fold's own tilt over the width
            on_plane = np.abs(np.einsum("ij,ij->i", d, n)) <= (
                1e-6 * scale + width * np.sin(np.radians(FOLD_ANGLE)))
            aligned = np.abs(n @ nf) >= np.cos(np.radians(FOLD_ANGLE))
            # barycentric coordinates of p in each triangle's plane
            d20, d21 = np.einsum("ij,ij->i", d, e1), np.einsum("ij,ij->i", d, e2)
            b1 = (d11 * d20 - d01 * d21) / den
            b2 = (d00 * d21 - d01 * d20) / den
            tol = 1e-9
            inside = ok & (b1 >= -tol) & (b2 >= -tol) & (b1 + b2 <= 1 + tol)
            hit = on_plane & aligned & inside
            sides = np.sign(n[hit] @ nf)
            if (sides > 0).any() and (sides < 0).any():
                return True
        return False


def edge_features(vertices, faces) -> EdgeFeatures:
    r"""The convex edges of a closed surface (vertices [m], faces) that the formal order of
    the panel method reads (:func:`edge_order`), independent of how a smooth part of it was
    tessellated:

    - **edges**: convex creases whose normals turn by more than :data:`FEATURE_ANGLE` (the
      feature angle of mesh processing); a crease up to it is a facet edge of a smooth
      surface (a 12- to 24-sided cylinder, a CAD export's curved face), which the panels'
      own remeshed creases follow with the same 1/N error as a smooth body's;
    - **folds**: creases turning within :data:`FOLD_ANGLE` of 180 degrees, the two faces
      in one plane, one folded back onto the other: no wedge of fluid but a double sheet of
      zero thickness, whose rim is a knife edge only where the sheet is at least a panel
      wide (:meth:`EdgeFeatures.sheet_wider_than`; the panel size is known only to the
      caller).

    The turning :math:`\theta = \pi - \alpha` for an interior dihedral angle :math:`\alpha`,
    from trimesh's face adjacency (``face_adjacency_angles``, ``face_adjacency_convex``).

    Limits: a real edge turning by no more than the feature angle (a shallow chine) is read
    as smooth, order 2 instead of at least 1.71 (the index at most 1.23 times smaller at
    r = sqrt 2); a smooth surface faceted coarser than it (an 8-sided cylinder) is read as
    the polyhedron it is, which is what the panels and the references solve.

    Measured (issue 32): eROV's visual mesh (DAVE, erov.dae) has 24 folds, each a sliver
    1.8 mm wide (3.5e-5 m^2) folded onto a larger face, in two mirror-image rings of 12 of
    radius about 0.09 m: an export artefact, not a fin; its sharpest edge is then 99 degrees
    (order 1.29 where its members are thicker than the panels, not the fold's 1).  On the shipped vehicle files, the CAD draw of seed
    1375923287 and the other public meshes every order is set by real edges (90 degrees and
    more) or thin members, as before."""
    import trimesh

    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    mesh = trimesh.Trimesh(v, f, process=False)
    ang = np.asarray(mesh.face_adjacency_angles, float)
    convex = np.asarray(mesh.face_adjacency_convex, bool)
    fold = fold_mask(ang)
    edge = convex & ~fold & (ang > np.radians(FEATURE_ANGLE) * (1.0 + 1e-9))
    turning = float(ang[edge].max()) if edge.any() else 0.0
    pairs = mesh.face_adjacency[fold]
    ends = mesh.face_adjacency_edges[fold]
    mid = v[ends].mean(axis=1) if len(ends) else np.zeros((0, 3))
    nrm = np.asarray(mesh.face_normals, float)[pairs[:, 0]] if len(pairs) else np.zeros((0, 3))
    if len(pairs):
        # towards the folded faces: from the edge to the first face's third vertex, in plane
        third = np.asarray(mesh.face_adjacency_unshared, np.int64)[fold][:, 0]
        d = v[third] - mid
        along = v[ends[:, 1]] - v[ends[:, 0]]
        along /= np.linalg.norm(along, axis=1, keepdims=True)
        d -= np.einsum("ij,ij->i", d, along)[:, None] * along
        d -= np.einsum("ij,ij->i", d, nrm)[:, None] * nrm
        inward = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-300)
    else:
        inward = np.zeros((0, 3))
    return EdgeFeatures(turning, mid, inward, nrm, v[f])


def max_convex_turning(vertices, faces) -> float:
    r"""The largest turning [rad] between the outward normals of two faces that meet at a
    convex edge of the closed surface that is an edge of the body: :math:`\theta = \pi -
    \alpha` for an interior dihedral angle :math:`\alpha` (a box's edge :math:`\pi/2`; 0 for
    a surface without convex edges or one faceted no coarser than :data:`FEATURE_ANGLE`),
    folds left out (:func:`edge_features`)."""
    return edge_features(vertices, faces).turning


def edge_order(turning: float, edge: float = 0.0, thickness: float = float("inf"),
               sheet: bool = False) -> float:
    r"""Formal order in the panel size h [-] of an added-mass term of a body whose sharpest
    convex edge turns the normal by ``turning`` [rad] (:func:`max_convex_turning`; creases up
    to the feature angle are a smooth surface's facets, :func:`edge_features`).

    .. math:: p_f = \min(2,\ 2\lambda),\qquad \lambda = \pi/\omega,\qquad
              \omega = \pi + \theta \quad [-]

    In a wedge of fluid of angle :math:`\omega` about a convex edge the potential goes as
    :math:`r^{\lambda}` and the velocity as :math:`r^{\lambda - 1}`, singular for
    :math:`\omega > \pi` (the edge singularities of Laplace's equation and of its boundary
    integral equations: von Petersdorff & Stephan 1990, Math. Methods Appl. Sci. 12,
    229-249, docs/bibliography.md).  A boundary-element solution on panels
    of uniform size then converges in the energy norm as :math:`h^{\lambda}` and a smooth linear
    functional of it, as an added-mass term is, as :math:`h^{2\lambda}` (ibid.; the duality
    argument): 4/3 at a right-angled edge (:math:`\theta = \pi/2`), 1 at a knife edge or a
    plate's rim (:math:`\omega = 2\pi`), 2 (the smooth body's 1/N, :data:`SMOOTH_ORDER`) where no
    edge turns the flow.  A member thinner than the panel edge (``thickness`` <
    ``edge`` [m], :func:`member_thickness`) is a knife edge at the panels' scale: its two rims
    lie within one panel, the normal turns by :math:`\pi` across it, so :math:`\omega = 2\pi`.
    So is the rim of a double sheet of zero thickness at least a panel wide (``sheet``: a
    fold, :meth:`EdgeFeatures.sheet_wider_than`); a narrower fold is below the panels'
    resolution and sets no order.

    This is the formal order of the grid convergence index (the largest order it may use,
    Oberkampf & Roy 2010, sec. 8.6.3.2: :math:`p = \min(\max(0.5, \hat p), p_f)`), not a
    fitted constant.  Measured on the CAD shapes against Capytaine refined to 12,000-24,000
    faces by Eça & Hoekstra's procedure (docs/validation.md): the references' fitted orders
    are 0.5-1.3 on the bodies with edges and about 1 on the plates, where the panel levels'
    own observed order (at 400-3,000 panels) is 2.4 to 22 on the terms the smooth order's
    index missed."""
    knife = bool(sheet) or float(edge) > float(thickness)
    theta = float(np.pi) if knife else min(float(turning), np.pi)
    if not theta > 0.0:
        return SMOOTH_ORDER
    return float(min(SMOOTH_ORDER, 2.0 * np.pi / (np.pi + theta)))
