r"""Isotropic remeshing of a closed surface to a target edge length, for the panel method.

The panel method's error depends on the panels' size and shape; a CAD export's tessellation
(caps fan-triangulated from one corner, slivers, one long triangle per flat face) is neither
uniform nor a family that refines consistently.  The panellings of
:func:`stripcoef.hull.panels.panel_added_mass` are therefore, when the optional ``remesh``
extra (pymeshlab) is installed, isotropic remeshes of the input at edge lengths

.. math:: h = \sqrt{\frac{4 A}{\sqrt3\, N}} \quad [\mathrm{m}]

(the side of N equilateral triangles covering the area A [m^2]), by the explicit isotropic
remeshing of Botsch & Kobbelt (2004, "A remeshing approach to multiresolution modeling",
Symp. Geometry Processing: edge split above 4/3 h, collapse below 4/5 h, valence-improving
flips, tangential smoothing, reprojection onto the input), as implemented in MeshLab
(Cignoni et al. 2008, "MeshLab: an open-source mesh processing tool", Eurographics Italian
Chapter; pymeshlab filter ``meshing_isotropic_explicit_remeshing``), with the edges sharper
than :data:`FEATURE_ANGLE` kept as creases, so that a box stays a box.

Why pymeshlab (docs/performance.md, "Remeshing for the panel method"): of the remeshers that
install from PyPI as wheels (pymeshlab, gmsh, pyacvd with pyvista/VTK), it reached the asked
panel count within about 10 % (gmsh's count depends on the geometry's curves: 1.2 to 2x the
target), in 0.03 to 0.3 s, and needs only ``libGL.so.1`` of the system (Debian ``libgl1``;
gmsh's wheel needs the GLU, Xft, Xcursor and Xinerama libraries too).

Thin members (issue 32), as measured: a plate's rims and a thruster duct's walls thinner than
the edge are followed (creases kept; a 0.3 x 0.6 m plate 3 mm thick: normal added mass 0.822,
0.792, 0.785, 0.777 of rho pi/4 a^2 b at 612 to 4048 panels, against 0.772 at t/a = 0.01 of
docs/validation.md's plate table; a duct of 5.6 mm walls converges as smoothly).  What the
remesher cannot follow with its defaults is a knife edge: where a wing section (a NACA
trailing edge, the ECA A9's fins) is thinner than the edge, edge flips join the two faces of
the thin wedge, the collapses then cut it off, and the remesh loses planform area (the seeded
wings of benchmarks/thin_members.py, NACA 00xx of t/c 0.017 to 0.046: 12 to 16 % at 400
panels, 5 % at 3200) more than volume.  Hence (:class:`Mode`, :data:`MODES`): a remesh is
refused when its area changes by more than :data:`AREA_TOLERANCE` (or its volume by more
than :data:`VOLUME_TOLERANCE`); the family is tried with creases above :data:`FEATURE_ANGLE`
and then :data:`FACET_ANGLE` with flips, then at both angles without flips and with the
remesh kept within :data:`KNIFE_DISTANCE` of the input (the thin-member modes: at 1600
and 3200 panels the same wings keep their area within 0.3 to 1.4 % and the aft tenth of the
chord within 0.8 to 7.4 % of its area, where the remeshes with flips lost 5.0 to 8.1 % of the
whole area; ``python -m benchmarks.remesh_choice --knife``, benchmarks/data/
remesh_knife_edges.md); and where no remesh keeps the area (the ECA A9's fins), the levels are the
input's faces bisected (:func:`stripcoef.hull.bisection.refine`, the surface exactly), said in a
:class:`~stripcoef.errors.ModelWarning`: never a silent loss of area.  Measured
(benchmarks/remesh_choice.py, benchmarks/public_meshes.py, benchmarks/thin_members.py;
docs/validation.md): pymeshlab's adaptive flag changed nothing on these wings and a tighter
surface-distance bound with flips did not keep the trailing edge.  A
faceted body (a 30-sided cylinder) is followed at :data:`FACET_ANGLE`, where the facets' creases
hold the face count: :func:`remesh_family` then shortens a level's edge until it refines.

Panels graded towards sharp edges (:func:`graded_for_panels`, an option the panel levels do not
use): the remesh bisected to the algebraic grading of :func:`edge_graded_size`.  Measured on
two thin plates, a box with a pod and a low-polygon ellipsoid of the CAD-shape seed
(``python -m benchmarks.edge_grading``, benchmarks/data/edge_grading.md), by Capytaine and by
this project's panel method (which agree within 0.25 % on every mesh there): at about 6000
faces the graded plates' slow terms (in-plane sway, yaw, surge) lie where the uniform remesh
lies at about 12,000, but the observed order stays 0.4 to 1.1 (beta 2 and 3) and the grid
convergence index of the graded levels is not smaller; the box with a pod gains nothing on
its yaw, and the ellipsoid's graded levels (a coarser remesh bisected) lose 0.7 to 1.0 % of
its volume.  Hence not the default.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

import numpy as np

from stripcoef.errors import ModelWarning
from stripcoef.hull.bisection import bisect_graded, enclosed_volume, refine, surface_area

#: Dihedral angle above which an edge is kept as a crease by the remesher [deg] (MeshLab's
#: default of the filter).
FEATURE_ANGLE = 30.0
#: The crease angle of the second try when the first changed the volume by more than
#: :data:`VOLUME_TOLERANCE` [deg]: a coarse faceted body (a 12-sided cylinder, a low-polygon
#: hull) has facet edges below 30 degrees that the remesher would cut across; kept as creases,
#: the remesh follows the polyhedron exactly (more panels on it).
FACET_ANGLE = 10.0
#: Remeshing passes (MeshLab's default) [-].
ITERATIONS = 10
#: Largest relative change of the enclosed volume a remesh may make [-] before it is refused
#: (the surface was not followed: members thinner than the edge collapsed).
VOLUME_TOLERANCE = 0.02
#: Largest relative change of the surface area a remesh may make [-] before it is refused.
#: A knife edge cut off loses more area than volume (a NACA 0017 wing's trailing edge: 7.3 %
#: of the area, 4.3 % of the volume at 1600 panels), and a thin member's added mass goes
#: with its planform, not its volume: the volume check alone does not see it.  The loss of
#: a small member is a small part of the whole surface: the ECA A9's remeshes lost 1.0 to
#: 1.9 % of its area, nearly all of it on the fins, and its roll (the fins' term) came out
#: 0.208 to 0.215 kg m^2 on them against 0.261 and 0.263 on its faces bisected to 3000 and
#: 6000 (Capytaine: 0.262); hence 1 %, not the volume's 2 %.
AREA_TOLERANCE = 0.01
#: Largest distance of the remesh from the input, a fraction of the bounding box's diagonal
#: [-] (MeshLab's default of the filter, passed explicitly: :func:`_remesh_checked`).
SURFACE_DISTANCE = 0.01
#: The same in the thin-member modes (no flips) [-]: a NACA 0030 wing (chord 0.15 m, span
#: 0.3 m) at 1600 panels keeps its aft tenth of chord within 3.6 % of its area (the whole
#: surface within 0.7 %) at 0.002, against 12.6 % (1.5 %) at 0.01 and 7.7 % (0.9 %) at 0.0005
#: (with flips, at 0.01: the family refused, area -5.9 %).
KNIFE_DISTANCE = 0.002
#: Factor by which :func:`remesh_family` shortens a level's edge while the level does not
#: refine the one before (2^(1/4): a quarter of a panel-count doubling) [-].
EDGE_STEP = 2.0 ** 0.25
#: Most shortenings of one level's edge (4 halve it: four times the panels) [-].
GROWTH_TRIES = 4
#: Most faces of a remesh of a family [-] (the panel method's MAX_PANELS).
MAX_FACES = 6000
#: Refinement ratio of every level the refinement adds over the finest where it fits within
#: :data:`MAX_FACES` (:func:`added_level`; before, only where the remesh at the doubled target
#: did not refine by :data:`LEAST_FACE_RATIO`), :math:`r = h_{coarse}/h_{fine}`
#: [-] (:func:`stripcoef.hull.panels.panel_added_mass`, :func:`grown_level`): Celik et al.
#: 2008 ("Procedure for estimation and reporting of uncertainty due to discretization in CFD
#: applications", J. Fluids Eng. 130(7) 078001, step 2: "it is desirable that the grid
#: refinement factor r be greater than 1.3").  The Richardson step multiplies the difference
#: of the two finest levels by :math:`1/(r^2 - 1)` (error ~ 1/N): 4 at 1.25 times the faces
#: (r = 1.12), 1.45 at 1.3.  Where the creases of thin members hold a level's face count, a
#: level of 1.25 times the faces gave the shipped BlueROV2 Heavy an estimated error of 56-61 %
#: and its vehicle file and mesh (the same surface, 2.6 micrometres apart) 2.6 % apart: two
#: remeshes of one surface differ by 0.1-0.4 % per level, and the step multiplied that by 4
#: (python -m benchmarks.vehicle_file_mesh).  The panel method's remeshed families refine by it
#: too wherever some mode fits it (:func:`stripcoef.hull.panels.remeshed_levels`; the BlueROV2
#: Heavy's no-flip levels at r = 1.19 and 1.25 were extrapolated to surge -22.8 %, yaw -34.4 %).
MIN_REFINEMENT = 1.3
#: :data:`MIN_REFINEMENT` in faces, :math:`N_{fine}/N_{coarse} = r^2` (h ~ N^-1/2) [-].
MIN_FACE_RATIO = MIN_REFINEMENT ** 2
#: The least refinement in faces a family accepts where no level of :data:`MIN_FACE_RATIO`
#: fits within its face limit [-] (the input's faces bisected on a large CAD mesh, the ECA
#: A9's 2,690: its levels 2690/4346/6158 would need 12,400 faces at r = 1.3): a family that
#: refines, at the larger step the level's estimated error then says.
LEAST_FACE_RATIO = 1.25


@dataclass(frozen=True)
class Mode:
    """How a family is remeshed: the crease angle [deg] and whether the remesher flips edges
    (valence-improving flips; off: the feature-preserving mode of thin members, module
    docstring)."""

    feature_angle: float
    flips: bool = True
    #: largest distance of the remesh from the input [-], a fraction of the bounding box's
    #: diagonal (MeshLab's default of the filter 0.01, :data:`SURFACE_DISTANCE`; the
    #: thin-member modes :data:`KNIFE_DISTANCE`)
    surface_distance: float = SURFACE_DISTANCE
    #: not a remesh: the input's faces bisected along their longest edges
    #: (:func:`stripcoef.hull.bisection.refine`) to the edge's panel count -- the surface exactly,
    #: the last resort of :func:`remesh_family`
    bisect: bool = False


#: The modes :func:`remesh_family` tries, in order: creases above :data:`FEATURE_ANGLE`, then
#: above :data:`FACET_ANGLE`, each first with flips (the isotropic remesh of Botsch & Kobbelt)
#: and then without (thin members: the knife edge kept).
MODES = (Mode(FEATURE_ANGLE), Mode(FACET_ANGLE),
         Mode(FEATURE_ANGLE, flips=False, surface_distance=KNIFE_DISTANCE),
         Mode(FACET_ANGLE, flips=False, surface_distance=KNIFE_DISTANCE),
         Mode(180.0, flips=False, bisect=True))


def available() -> bool:
    """Whether the optional remesher (pymeshlab, the ``remesh`` extra) can be imported."""
    try:
        import pymeshlab  # noqa: F401
    except Exception:            # ImportError, or a missing system library (libGL) at import
        return False
    return True


def edge_for_panels(area: float, panels: int) -> float:
    r"""Edge [m] of ``panels`` equilateral triangles covering ``area`` [m^2]:
    :math:`h = \sqrt{4A/(\sqrt3 N)}`."""
    return float(np.sqrt(4.0 * area / (np.sqrt(3.0) * panels)))


def panels_for_edge(area: float, edge: float) -> float:
    r"""Equilateral triangles of side ``edge`` [m] covering ``area`` [m^2]:
    :math:`N = 4A/(\sqrt3 h^2)` (the inverse of :func:`edge_for_panels`)."""
    return float(4.0 * area / (np.sqrt(3.0) * edge * edge))


def remesh_isotropic(vertices, faces, edge: float, *, feature_angle=FEATURE_ANGLE,
                     iterations: int = ITERATIONS):
    """The closed mesh (vertices [m], faces) remeshed to triangles of about ``edge`` [m]
    (module docstring), creases above ``feature_angle`` [deg] kept (then above
    :data:`FACET_ANGLE` if the volume or area changed); ``feature_angle`` may be a
    :class:`Mode` (a family's, :func:`remesh_family`: that mode alone).  Returns (vertices,
    faces) with the input's orientation (outward normals), or ``None`` when the result is not
    a closed, consistently wound surface of the input's volume within
    :data:`VOLUME_TOLERANCE` and area within :data:`AREA_TOLERANCE`."""
    if isinstance(feature_angle, Mode):
        modes = (feature_angle,)
    else:
        modes = tuple(Mode(a) for a in dict.fromkeys((float(feature_angle),
                                                      min(float(feature_angle), FACET_ANGLE))))
    for mode in modes:
        out = _remesh_once(vertices, faces, edge, mode, iterations)
        if out is not None:
            return out
    return None


def remesh_family(vertices, faces, edges, *, min_ratio: float = LEAST_FACE_RATIO,
                  max_faces: int | None = None, modes=MODES):
    r"""Remeshes at each of ``edges`` [m] (longest first) in one :class:`Mode` for all (the
    first of ``modes`` that gives every level), each with at least ``min_ratio`` times the
    faces of the one before.  Returns (list of (vertices, faces), the mode) or ``None``.

    A level whose remesh does not reach ``min_ratio`` times the faces of the one before (the
    creases of a faceted body -- a 30-sided cylinder kept as a polyhedron at
    :data:`FACET_ANGLE` -- hold the face count near the creases' own until the edge is shorter
    than the facets), or changes the area or volume beyond :data:`AREA_TOLERANCE` and
    :data:`VOLUME_TOLERANCE` (a member thinner than the edge), is remeshed at edges shorter
    by :data:`EDGE_STEP` until it does, at most :data:`GROWTH_TRIES` times and within
    ``max_faces``: the family refines, each level an isotropic remesh of the same surface, at
    more faces than asked (issue 32: the Slocum glider's 124-face cylinder and the WHOI
    glider's 208-face hull, whose families 1068/1932/2190 and 1192/2054/2518 were refused and
    the panel method fell back to the refined CAD faces, 11 and 16 % off).  A family refused
    in every mode because a remesh lost area or volume is said in a :class:`ModelWarning`
    (never silent: the caller falls back to a family that follows the surface)."""
    cap = MAX_FACES if max_faces is None else max_faces
    worst = None                              # the smallest area/volume change of a refusal
    for mode in modes:
        levels = []
        for h in edges:
            lv, change = grown_level(vertices, faces, h, mode,
                                min_ratio * len(levels[-1][1]) if levels else 0, cap)
            if lv is None:
                if change is not None and (worst is None or abs(change[0]) < abs(worst[0])):
                    worst = change
                break
            levels.append(lv)
        else:
            if mode.bisect and worst is not None:
                warnings.warn(_refused(worst) + "; the panel levels are the input's faces "
                              "bisected (" + "/".join(str(len(lv[1])) for lv in levels)
                              + " faces): the surface exactly, at the input's panel shapes",
                              ModelWarning, stacklevel=2)
            return levels, mode
    if worst is not None:
        warnings.warn(_refused(worst) + "; the panel levels are then a remesh of the whole "
                      "body or the input's faces refined", ModelWarning, stacklevel=2)
    return None


def _refused(change) -> str:
    """The warning's first part: the smallest (area, volume) change of a refused remesh."""
    return (f"the isotropic remesh was refused: it changed the surface area by "
            f"{100 * change[0]:+.1f} % and the volume by {100 * change[1]:+.1f} % at best "
            f"(limits {100 * AREA_TOLERANCE:.0f} and {100 * VOLUME_TOLERANCE:.0f} %: members "
            "thinner than the edge, such as a fin's trailing edge, cut off)")


def grown_level(vertices, faces, edge, mode, at_least, max_faces, counted=None):
    """(the remesh at ``edge`` [m], or at edges shorter by EDGE_STEP until it has at least
    ``at_least`` faces (or ``counted(level)`` at least ``at_least``: the panels a mirrored
    solve keeps) and keeps the area and volume; the last (area, volume) change refused,
    or None).  The remesh is ``None`` if no edge gives it within ``max_faces``.  In the
    bisection mode the level is bisected straight to ``at_least`` faces where the edge asks
    fewer (the bisection reaches the count it is asked for; the edge's steps overshoot it:
    the bluff set's open_frame, 1,732 faces, has no level between 4,525 and 6,400 asked panels
    for the 4,947 that r = 1.3 needs, python -m benchmarks.bluff_shapes --method panels)."""
    if mode.bisect and at_least > 0:
        edge = min(edge, edge_for_panels(surface_area(vertices, faces), at_least)
                   * (1.0 - 1e-9))
    change = None
    for _ in range(GROWTH_TRIES + 1):
        lv = _remesh_checked(vertices, faces, edge, mode, ITERATIONS)
        if lv[0] is None:
            if lv[1] is None:                 # not closed: a shorter edge will not mend it
                return None, change
            change = lv[1]
        else:
            if len(lv[0][1]) > max_faces:
                return None, change
            if (len(lv[0][1]) if counted is None else counted(lv[0])) >= at_least:
                return lv[0], change
        edge /= EDGE_STEP
    return None, change


def added_level(vertices, faces, edge, mode, finest: float, counted=None, *,
                ratio: float = MIN_FACE_RATIO):
    r"""The level the panel method's refinement adds to a family of ``mode`` whose finest
    level has ``finest`` panels (:func:`stripcoef.hull.panels.panel_added_mass`), or ``None``:
    the remesh at ``edge`` [m] (the doubled panel count's) where it refines the finest by
    ``ratio`` in panels (``counted(level)``, default its faces: the panels solved); else a
    level grown from it to :data:`MIN_FACE_RATIO` (:func:`grown_level`, within
    :data:`MAX_FACES`); else, where that does not fit, the remesh at ``edge`` if it refines
    by :data:`LEAST_FACE_RATIO` at least (the family's fallback step).

    The default ``ratio`` is Celik et al. 2008's r >= 1.3 (:data:`MIN_REFINEMENT`, "Procedure
    for estimation and reporting of uncertainty due to discretization in CFD applications",
    J. Fluids Eng. 130(7) 078001, step 2), the ratio the families' own levels take
    (:func:`remesh_family`).  Before (``ratio`` = :data:`LEAST_FACE_RATIO`, which reproduces
    it) a remesh of 1.25 times the finest's faces was taken: where the creases of a frame's
    thin plates made the family's finest level overshoot its target (the no-flip remesh's
    1,600-panel target at 3,084 panels), the doubled target's remesh refined it by r = 1.14
    to 1.20, and the Richardson step multiplied that pair's change by 5 to 7
    (benchmarks/data/fresh32f_trace.md, frame 8 of seed 1795939009 and frame 25 of seed
    1795948662: heave -6.3 and -5.8 % where the finest level was within 1.7 %); grown to
    r >= 1.3, -1.1 and +0.4 % (benchmarks/data/frame32g_trace.md)."""
    count = (lambda lv: len(lv[1])) if counted is None else counted
    lv = _remesh_once(vertices, faces, edge, mode, ITERATIONS)
    if lv is not None and count(lv) >= ratio * finest:
        return lv
    # (a shorter edge than the remesh that fell short: grown_level would remesh it again)
    grown = grown_level(vertices, faces, edge if lv is None else edge / EDGE_STEP, mode,
                        MIN_FACE_RATIO * finest, MAX_FACES, counted)[0]
    if grown is not None:
        return grown
    return lv if lv is not None and count(lv) >= LEAST_FACE_RATIO * finest else None


def _remesh_once(vertices, faces, edge, mode, iterations):
    """The remesh, or ``None`` (:func:`_remesh_checked`)."""
    return _remesh_checked(vertices, faces, edge, mode, iterations)[0]


def _remesh_checked(vertices, faces, edge, mode, iterations):
    """((vertices, faces) or None, (relative area change, relative volume change) of a
    refused remesh or None).  Every parameter of the filter is passed: pymeshlab keeps the
    values of the previous call for those left out (pymeshlab 2025.7: a call with
    ``collapseflag=False`` made the next plain call's remesh 5x finer)."""
    import pymeshlab

    if not isinstance(mode, Mode):
        mode = Mode(float(mode))
    if mode.bisect:
        rv, rf = refine(np.asarray(vertices, float), np.asarray(faces, np.int64),
                        int(np.ceil(panels_for_edge(surface_area(vertices, faces), edge))))
        return (np.asarray(rv, float), np.asarray(rf, np.int64)), None
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int32)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f))
    diag = float(np.linalg.norm(np.ptp(v, axis=0)))
    ms.meshing_isotropic_explicit_remeshing(
        iterations=iterations, adaptive=False, selectedonly=False,
        targetlen=pymeshlab.PureValue(float(edge)), featuredeg=float(mode.feature_angle),
        checksurfdist=True, maxsurfdist=pymeshlab.PureValue(mode.surface_distance * diag),
        splitflag=True, collapseflag=True, swapflag=bool(mode.flips), smoothflag=True,
        reprojectflag=True)
    m = ms.current_mesh()
    rv = np.asarray(m.vertex_matrix(), float)
    rf = np.asarray(m.face_matrix(), np.int64)
    if len(rf) < 4:
        return None, None
    from stripcoef.geometry.mesh import EdgeTopology

    if not EdgeTopology(rf).consistent or _degenerate(rv, rf) or _new_folds(v, faces, rv, rf):
        return None, None
    vol0, vol = enclosed_volume(v, np.asarray(faces)), enclosed_volume(rv, rf)
    if vol < 0:                  # the remesher kept the winding; guard against a flip anyway
        rf, vol = rf[:, ::-1], -vol
    change = (surface_area(rv, rf) / surface_area(v, np.asarray(faces)) - 1.0, vol / vol0 - 1.0)
    if abs(change[0]) > AREA_TOLERANCE or abs(change[1]) > VOLUME_TOLERANCE:
        return None, change
    return (rv, rf), None


#: Smallest triangle quality q = 4 sqrt(3) A / (a^2 + b^2 + c^2) [-] (1 for an equilateral
#: triangle, 0 for three collinear vertices; Bank 1998's shape measure) a remesh may leave.
#: MeshLab's remesher can leave triangles of three collinear vertices along a crease (the
#: bluff set's box_pod_top_aft at 780-3,192 faces: two to 26 of them, q = 0): a constant-panel
#: triangle of zero area makes the panel method's matrix singular (rcond 1e-23, pitch +380 %),
#: so such a remesh is refused like an open one and the next mode is tried.  Only triangles
#: degenerate to round-off are refused: at 1e-3 the rule also refused the public meshes' usable
#: remeshes (slivers of the WHOI glider's and the LAUV's families), and the WHOI glider's sway
#: went from -2.7 to +13.6 % on the fallback family (benchmarks.public_meshes).
LEAST_QUALITY = 1e-9


def _degenerate(vertices, faces) -> bool:
    """Whether any triangle's quality is below :data:`LEAST_QUALITY`."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    area2 = np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)
    edges2 = (np.diff(t, axis=1, append=t[:, :1]) ** 2).sum(axis=(1, 2))
    return bool(np.any(2.0 * np.sqrt(3.0) * area2 < LEAST_QUALITY * edges2))


#: Largest departure from 180 degrees [deg] of the turning at a fold: the two faces lie in one
#: plane, one folded back onto the other (a double sheet of zero thickness; eROV's visual
#: mesh has 24 such slivers, 1.8 mm wide, turning 179.985-179.997 degrees;
#: :func:`stripcoef.hull.panels.edge_features` reads them as such).
FOLD_ANGLE = 0.1


def fold_mask(turning) -> np.ndarray:
    """Which adjacent face pairs are folds, from their turning angles [rad] (trimesh's
    ``face_adjacency_angles``): the normals turn by at least 180 - :data:`FOLD_ANGLE`
    degrees, one face folded back onto the other.  The one fold rule, read by :func:`folds`
    and :func:`stripcoef.hull.panels.edge_features`."""
    return np.asarray(turning, float) >= np.pi - np.radians(FOLD_ANGLE)


def folds(vertices, faces) -> int:
    """The number of fold edges of a closed mesh (:func:`fold_mask`)."""
    import trimesh

    ang = trimesh.Trimesh(np.asarray(vertices, float), np.asarray(faces, np.int64),
                          process=False).face_adjacency_angles
    return int(np.count_nonzero(fold_mask(ang)))


def _new_folds(vertices, faces, rv, rf) -> bool:
    r"""Whether the remesh (``rv``, ``rf``) has more folds (:func:`folds`) than its input: a
    triangle the remesher folded back onto its neighbour.  MeshLab's remesh without flips
    folds triangles along the concave crease where the bluff set's box_pod_top_aft's pod
    meets the box (7, 8, 16 and 19 folds at 490, 884, 1804 and 3268 faces, none in the
    input): a folded panel is a double sheet the flow does not see as the body, and the
    levels' heave went 38.0, 38.0, 34.6, 39.6 kg (pitch +63 % after the extrapolation).
    Refused like a degenerate remesh; the next mode is tried.  The input's own folds (eROV's
    export slivers) are not the remesher's and are not counted against it."""
    n = folds(rv, rf)
    return n > 0 and n > folds(vertices, faces)


# ------------------------------------------------------------------ graded towards edges
#: Dihedral angle above which an edge of the input counts as a sharp edge that the graded
#: panellings refine towards [deg] (a box's 90-degree edges, a plate's rims; a 12-sided
#: cylinder's 30-degree facet edges are not singular enough to count).
SHARP_ANGLE = 60.0
#: Grading exponent beta of :func:`edge_graded_size` [-] (beta = 1: uniform; beta = 2: the
#: isotropic panel count grows only as log(L/h) more than the uniform one's).
GRADING_BETA = 2.0
#: Width L of the graded zone, a fraction of the bounding box's diagonal [-].
GRADING_LENGTH = 0.1


def sharp_edges(vertices, faces, angle: float = SHARP_ANGLE):
    """The edges of a closed mesh (vertices [m], faces) whose dihedral angle (between the two
    faces' normals) exceeds ``angle`` [deg], as an (m, 2, 3) array of segments [m]."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    t = v[f]
    n = np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    a = f.reshape(-1)
    b = np.roll(f, -1, axis=1).reshape(-1)
    key = np.minimum(a, b) * len(v) + np.maximum(a, b)
    order = np.argsort(key, kind="stable")
    ks = key[order]
    pair = np.flatnonzero(ks[1:] == ks[:-1])          # the two half-edges of one edge
    f1, f2 = order[pair] // 3, order[pair + 1] // 3
    cos = np.einsum("ij,ij->i", n[f1], n[f2])
    sharp = cos < np.cos(np.radians(angle))
    e = order[pair][sharp]
    return np.stack([v[a[e]], v[b[e]]], axis=1)


def distance_to_segments(points, segments, chunk: int = 2048):
    """Distance [m] of each of ``points`` (n, 3) [m] to the nearest of ``segments`` (m, 2, 3)
    [m] (the clamped projection onto each segment); infinity when there are none."""
    p = np.asarray(points, float)
    s = np.asarray(segments, float)
    out = np.full(len(p), np.inf)
    if len(s) == 0:
        return out
    a, ab = s[:, 0], s[:, 1] - s[:, 0]
    ab2 = np.maximum(np.einsum("ij,ij->i", ab, ab), 1e-300)
    for i in range(0, len(p), chunk):
        ap = p[i:i + chunk, None, :] - a[None]
        u = np.clip(np.einsum("nmj,mj->nm", ap, ab) / ab2, 0.0, 1.0)
        d = np.linalg.norm(ap - u[..., None] * ab[None], axis=2)
        out[i:i + chunk] = d.min(axis=1)
    return out


def edge_graded_size(points, segments, edge: float, length: float,
                     beta: float = GRADING_BETA):
    r"""Panel edge [m] at ``points`` graded towards the sharp edges ``segments``
    (:func:`sharp_edges`): with d the distance to the nearest [m], h = ``edge`` [m] the edge far
    from them and L = ``length`` [m] the graded zone's width,

    .. math:: h(d) = h\,\Big(\frac{\max(d, d_0)}{L}\Big)^{1 - 1/\beta}\ (d < L),\qquad
              h(d) = h\ (d \ge L),\qquad d_0 = L\,(h/L)^{\beta} \quad [\mathrm{m}]

    the local size of the algebraically graded mesh :math:`x_j = L\,(j/n)^\beta`, h = L/n
    (up to the factor beta; at :math:`d_0`, the first cell, h(d_0) = d_0), that restores the
    optimal convergence rate of a boundary element method where the solution is singular at
    an edge (von Petersdorff & Stephan 1990, "Regularity of mixed boundary value problems in
    R^3 and boundary element methods on graded meshes", Math. Methods Appl. Sci. 12,
    229-249; the finite-element original: Babuska, Kellogg & Pitkaranta 1979, "Direct and
    inverse error estimates for finite elements with mesh refinement", Numer. Math. 33,
    447-471).  beta = 1 is the uniform mesh."""
    d = distance_to_segments(points, segments)
    d0 = length * (edge / length) ** beta
    scaled = (np.maximum(d, d0) / length) ** (1.0 - 1.0 / beta)
    return edge * np.minimum(1.0, scaled)


def graded_remesh(vertices, faces, edge: float, *, beta: float = GRADING_BETA,
                  length: float | None = None, angle: float = SHARP_ANGLE,
                  mode: Mode | None = None, max_faces: int | None = None):
    """The closed mesh remeshed at ``edge`` [m] (:func:`remesh_isotropic` in ``mode``, default
    the first of :data:`MODES`), then its faces bisected along their longest edges
    (:func:`stripcoef.hull.bisection.bisect_graded`) to the sizing field
    :func:`edge_graded_size` towards the input's edges sharper than ``angle`` [deg]; graded
    zone ``length`` [m] (default :data:`GRADING_LENGTH` of the bounding box's diagonal).
    Returns (vertices, faces) or ``None`` when the remesh is refused or the graded mesh would
    exceed ``max_faces``.  Not used by default:
    an option measured by ``python -m benchmarks.edge_grading``."""
    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int64)
    base = remesh_isotropic(v, f, edge, feature_angle=mode or MODES[0])
    if base is None:
        return None
    segments = sharp_edges(v, f, angle)
    if length is None:
        length = GRADING_LENGTH * float(np.linalg.norm(np.ptp(v, axis=0)))
    return bisect_graded(base[0], base[1],
                         lambda c: edge_graded_size(c, segments, edge, length, beta),
                         max_faces=max_faces)


def graded_for_panels(vertices, faces, panels: int, *, beta: float = GRADING_BETA,
                      length: float | None = None, angle: float = SHARP_ANGLE,
                      mode: Mode | None = None, tries: int = 10):
    """:func:`graded_remesh` at the far-field edge that gives about ``panels`` faces (within
    10 %): the far edge searched by the secant on log(faces) against log(edge), kept within
    the bracket of the tries so far (its geometric middle where the secant leaves it; a graded
    mesh beyond 4 x ``panels`` counts as too fine), at most ``tries`` remeshes; the closest
    kept.  Returns (vertices, faces) or ``None``."""
    area = surface_area(vertices, faces)
    edge = edge_for_panels(area, panels)
    best, seen = None, []                    # seen: (log edge, log faces)
    fine, coarse = None, None                # bracket: edges giving too many / too few faces
    for _ in range(tries):
        out = graded_remesh(vertices, faces, edge, beta=beta, length=length, angle=angle,
                            mode=mode, max_faces=4 * panels)
        if out is None:
            if remesh_isotropic(vertices, faces, edge, feature_angle=mode or MODES[0]) is None:
                return best
            fine = edge if fine is None else max(fine, edge)
            edge = 2.0 * edge if coarse is None else float(np.sqrt(edge * coarse))
            continue
        n = len(out[1])
        if best is None or abs(n - panels) < abs(len(best[1]) - panels):
            best = out
        if abs(n / panels - 1.0) <= 0.1:
            break
        if n > panels:
            fine = edge if fine is None else max(fine, edge)
        else:
            coarse = edge if coarse is None else min(coarse, edge)
        seen.append((np.log(edge), np.log(n)))
        if len(seen) >= 2 and seen[-1][1] != seen[-2][1]:
            slope = (seen[-1][1] - seen[-2][1]) / (seen[-1][0] - seen[-2][0])
            new = float(np.exp(seen[-1][0] + (np.log(panels) - seen[-1][1]) / slope))
        else:
            new = edge * float(np.sqrt(n / panels))
        if (fine is not None and new <= fine) or (coarse is not None and new >= coarse):
            new = float(np.sqrt(fine * coarse)) if fine and coarse else \
                (2.0 * edge if n > panels else 0.5 * edge)
        edge = new
    return best
