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
remesher cannot follow is a knife edge: where a wing section (a NACA trailing edge, the ECA
A9's fins) is thinner than the edge, the collapses cut it off, and the remesh loses planform
area (NACA 00xx wings of t/c 0.012 to 0.036: 14 % at 400 panels, 4.5 % at 3200) more than
volume; the family is then refused and the panel method falls back to the refined input.  A
faceted body (a 30-sided cylinder) is followed at :data:`FACET_ANGLE`, where the facets' creases
hold the face count: :func:`remesh_family` then shortens a level's edge until it refines.
"""

from __future__ import annotations

import numpy as np

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
#: Factor by which :func:`remesh_family` shortens a level's edge while the level does not
#: refine the one before (2^(1/4): a quarter of a panel-count doubling) [-].
EDGE_STEP = 2.0 ** 0.25
#: Most shortenings of one level's edge (4 halve it: four times the panels) [-].
GROWTH_TRIES = 4
#: Most faces of a remesh of a family [-] (the panel method's MAX_PANELS).
MAX_FACES = 6000


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


def remesh_isotropic(vertices, faces, edge: float, *, feature_angle: float = FEATURE_ANGLE,
                     iterations: int = ITERATIONS):
    """The closed mesh (vertices [m], faces) remeshed to triangles of about ``edge`` [m]
    (module docstring), creases above ``feature_angle`` [deg] kept (then above
    :data:`FACET_ANGLE` if the volume changed).  Returns (vertices, faces) with the input's orientation (outward
    normals), or ``None`` when the result is not a closed, consistently wound surface of the
    input's volume within :data:`VOLUME_TOLERANCE`."""
    for angle in dict.fromkeys((feature_angle, min(feature_angle, FACET_ANGLE))):
        out = _remesh_once(vertices, faces, edge, angle, iterations)
        if out is not None:
            return out
    return None


def remesh_family(vertices, faces, edges, *, min_ratio: float = 1.25,
                  max_faces: int | None = None):
    r"""Remeshes at each of ``edges`` [m] (longest first) with one crease angle for all
    (:data:`FEATURE_ANGLE`, else :data:`FACET_ANGLE`), each with at least ``min_ratio`` times
    the faces of the one before.  Returns (list of (vertices, faces), the angle [deg]) or
    ``None``.

    A level whose remesh does not reach ``min_ratio`` times the faces of the one before (the
    creases of a faceted body -- a 30-sided cylinder kept as a polyhedron at
    :data:`FACET_ANGLE` -- hold the face count near the creases' own until the edge is shorter
    than the facets) is remeshed at edges shorter by :data:`EDGE_STEP` until it does, at most
    :data:`GROWTH_TRIES` times and within ``max_faces``: the family refines, each level an
    isotropic remesh of the same surface, at more faces than asked (issue 32: the Slocum
    glider's 124-face cylinder and the WHOI glider's 208-face hull, whose families
    1068/1932/2190 and 1192/2054/2518 were refused and the panel method fell back to the
    refined CAD faces, 11 and 16 % off)."""
    cap = MAX_FACES if max_faces is None else max_faces
    for angle in (FEATURE_ANGLE, FACET_ANGLE):
        levels = []
        for h in edges:
            lv = _grown(vertices, faces, h, angle,
                        min_ratio * len(levels[-1][1]) if levels else 0, cap)
            if lv is None:
                break
            levels.append(lv)
        else:
            return levels, angle
    return None


def _grown(vertices, faces, edge, angle, at_least, max_faces):
    """The remesh at ``edge`` [m], or at edges shorter by EDGE_STEP until it has at least
    ``at_least`` faces; ``None`` if the volume changes, or it exceeds ``max_faces``."""
    for _ in range(GROWTH_TRIES + 1):
        lv = _remesh_once(vertices, faces, edge, angle, ITERATIONS)
        if lv is None or len(lv[1]) > max_faces:
            return None
        if len(lv[1]) >= at_least:
            return lv
        edge /= EDGE_STEP
    return None


def _remesh_once(vertices, faces, edge, feature_angle, iterations):
    import pymeshlab

    v = np.asarray(vertices, float)
    f = np.asarray(faces, np.int32)
    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f))
    ms.meshing_isotropic_explicit_remeshing(iterations=iterations,
                                            targetlen=pymeshlab.PureValue(float(edge)),
                                            featuredeg=float(feature_angle))
    m = ms.current_mesh()
    rv = np.asarray(m.vertex_matrix(), float)
    rf = np.asarray(m.face_matrix(), np.int64)
    if len(rf) < 4:
        return None
    from stripcoef.geometry.mesh import EdgeTopology

    if not EdgeTopology(rf).consistent:
        return None
    vol0, vol = _volume(v, np.asarray(faces)), _volume(rv, rf)
    if vol < 0:                  # the remesher kept the winding; guard against a flip anyway
        rf, vol = rf[:, ::-1], -vol
    if abs(vol / vol0 - 1.0) > VOLUME_TOLERANCE:
        return None
    return rv, rf


def _volume(vertices, faces) -> float:
    """Enclosed volume [m^3] (sum of signed tetrahedra, divergence theorem)."""
    t = np.asarray(vertices, float)[np.asarray(faces)]
    return float(np.einsum("ij,ij->i", t[:, 0], np.cross(t[:, 1], t[:, 2])).sum() / 6.0)
