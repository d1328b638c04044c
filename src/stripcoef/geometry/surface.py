r"""The closed surface of a vehicle file: its parts united into one watertight mesh.

Strip theory reads a vehicle file part by part (:mod:`stripcoef.geometry.bodies`); the 3D
panel method (:mod:`stripcoef.hull.panels`) needs the wetted surface of the whole body, one
closed surface with outward normals.  :func:`vehicle_surface` builds it from the same parts:

- the hull: its half-breadth b(x) and half-height h(x) lofted along x, each station an
  ellipse :math:`(y_0 + b\cos\theta,\ z_0 + h\sin\theta)` or a rectangle 2b x 2h (the
  ``section`` of the file), a zero end radius a tip;
- boxes, fins (chord x span x thickness boxes), cylinders along x, y or z, ducts
  (cylinders with ``inner_diameter``: rings, their interior open to the water);
- mesh appendages as loaded (their ``length_unit`` and ``transform`` applied by
  :func:`stripcoef.geometry.mesh.load_mesh`; the vehicle file itself is in metres);
- through-holes (``holes``) subtracted from the hull before the union, so that the water in
  them is the panel method's to move.

The union and difference are the exact, guaranteed-manifold mesh booleans of manifold3d
(Lalish et al., "Manifold", https://github.com/elalish/manifold, through
``trimesh.boolean`` with ``engine="manifold"``): a maintained library that returns a
watertight result for overlapping solids, which hand-written clipping does not.

Round parts are polygons of ``sections`` sides whose area is the circle's: their vertices lie
on the radius :math:`r\,k_n`, :math:`k_n = \sqrt{2\pi / (n \sin(2\pi/n))}` (the inscribed
n-gon has :math:`\frac{n}{2\pi}\sin\frac{2\pi}{n}` of the circle's area, -2.6 % at n = 16:
the volume and the strips' section areas of the vehicle file are kept; k_16 = 1.013,
k_64 = 1.0008).
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.mesh import closed_loft
from stripcoef.geometry.mesh_close import manifold_boolean
from stripcoef.geometry.shapes import shape_geometry

#: Default polygon sides of every round section (hull stations, cylinders, ducts) [-].
DEFAULT_SECTIONS = 64
#: Default stations per hull profile segment (cosine-spaced, clustered at its ends) [-].
DEFAULT_STATIONS = 24


def _ring_angles(n: int) -> np.ndarray:
    return 2.0 * np.pi * np.arange(n) / n


def equal_area_factor(n: int) -> float:
    r""":math:`k_n = \sqrt{2\pi / (n \sin(2\pi/n))}` [-]: the radius of the regular n-gon of a
    circle's area over the circle's (module docstring; the n-gon of circumradius R has area
    :math:`\tfrac{n}{2} R^2 \sin(2\pi/n)`)."""
    n = int(n)
    return float(np.sqrt(2.0 * np.pi / (n * np.sin(2.0 * np.pi / n))))


def _section_ring(shape: str, b, h, n: int):
    r"""(n, 2) offsets (y, z) [m] of one hull station, counter-clockwise from +y: the ellipse
    :math:`k_n (b\cos\theta, h\sin\theta)`, :math:`\theta = 2\pi k / n` (of the ellipse's
    area: :func:`equal_area_factor`), or the rectangle
    2b x 2h by its four corners (its sides are straight: ``n`` is ignored)."""
    if not shape_geometry(shape).rounded:    # straight sides: the rectangle's corners
        return np.array([[b, h], [-b, h], [-b, -h], [b, -h]], float)
    th = _ring_angles(n)
    k = equal_area_factor(n)
    return np.column_stack([k * b * np.cos(th), k * h * np.sin(th)])


def hull_stations(hull, stations: int = DEFAULT_STATIONS) -> np.ndarray:
    """The x stations [m] of the lofted hull: the ends of every profile segment of either
    profile and, inside a curved segment (all but ``cylinder`` and ``cone``, whose ruled
    surface between its ends is exact), ``stations`` - 1 more, cosine-spaced (clustered at
    the segment's ends, where noses and tails curve)."""
    xs = []
    t = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, int(stations) + 1)))
    for prof in (hull.half_breadth, hull.half_height):
        for seg in prof.segments:
            u = np.array([0.0, 1.0]) if seg.kind in ("cylinder", "cone") else t
            xs.append(seg.x_aft + (seg.x_fwd - seg.x_aft) * u)
    x = np.unique(np.concatenate(xs))
    # merge stations closer than 1e-9 of the length (segment ends of the two profiles)
    keep = np.concatenate([[True], np.diff(x) > 1e-9 * (x[-1] - x[0])])
    return x[keep]


def hull_mesh(hull, *, sections: int = DEFAULT_SECTIONS, stations: int = DEFAULT_STATIONS):
    r"""The hull of a vehicle file as a closed ``trimesh.Trimesh`` [m, body axes]: stations of
    :func:`hull_stations` lofted with ``sections`` vertices each (:func:`_section_ring`);
    an end station of zero half-breadth or half-height is a tip (one vertex), a non-zero one
    a flat cap.  Volume: :math:`\int A(x)\,dx` of the polygonal sections by the trapezoidal
    rule of the loft (the ruled surface between stations)."""

    n = int(sections) if shape_geometry(hull.section).rounded else 4
    x = hull_stations(hull, stations)
    b = np.asarray(hull.half_breadth(x), float)
    h = np.asarray(hull.half_height(x), float)
    tiny = 1e-9 * max(float(np.max(b)), float(np.max(h)), 1e-300)
    open_ = (b > tiny) & (h > tiny)
    tips = [not open_[0], not open_[-1]]
    inner = slice(1 if tips[0] else 0, len(x) - 1 if tips[1] else len(x))
    if not np.all(open_[inner]):
        k = int(np.nonzero(~open_[inner])[0][0]) + (1 if tips[0] else 0)
        raise InputError("hull radius is zero inside the body", key="hull",
                         value=f"x = {x[k]:.6g} m",
                         expected="a half-breadth and half-height > 0 except at the two ends")
    xr, br, hr = x[inner], b[inner], h[inner]
    rings = np.stack([np.column_stack([np.full(n, xi),
                                       hull.y + _section_ring(hull.section, bi, hi, n)[:, 0],
                                       hull.z + _section_ring(hull.section, bi, hi, n)[:, 1]])
                      for xi, bi, hi in zip(xr, br, hr)])
    return closed_loft(rings, [x[0], hull.y, hull.z], [x[-1], hull.y, hull.z])


def _along(axis: str):
    """The rotation (4x4) taking trimesh's z-axis primitives onto body ``axis``."""
    import trimesh

    target = {"x": [1.0, 0.0, 0.0], "y": [0.0, 1.0, 0.0], "z": [0.0, 0.0, 1.0]}[axis]
    return trimesh.geometry.align_vectors([0.0, 0.0, 1.0], target)


def cylinder_mesh(cyl, *, sections: int = DEFAULT_SECTIONS):
    """A vehicle file's cylinder (solid) or duct (``inner_diameter`` > 0: a ring, its
    interior water) as a closed ``trimesh.Trimesh`` [m, body axes], polygons of the circles'
    areas (:func:`equal_area_factor`)."""
    import trimesh

    tf = _along(cyl.axis)
    tf[:3, 3] = np.asarray(cyl.center, float)
    k = equal_area_factor(sections)
    if cyl.inner_diameter > 0:
        return trimesh.creation.annulus(r_min=0.5 * k * cyl.inner_diameter,
                                        r_max=0.5 * k * cyl.diameter, height=cyl.length,
                                        sections=int(sections), transform=tf)
    return trimesh.creation.cylinder(radius=0.5 * k * cyl.diameter, height=cyl.length,
                                     sections=int(sections), transform=tf)


def box_mesh(center, size):
    """An axis-aligned box of ``size`` (lx, ly, lz) [m] centred at ``center`` [m]."""
    import trimesh

    return trimesh.creation.box(extents=np.asarray(size, float),
                                transform=trimesh.transformations.translation_matrix(
                                    np.asarray(center, float)))


def fin_mesh(fin):
    """A fin as the box chord (x) x span (its ``span_axis``) x thickness [m]."""
    size = np.full(3, float(fin.thickness))
    size[0] = fin.chord
    size["xyz".index(fin.span_axis)] = fin.span
    return box_mesh(fin.center, size)


def hole_mesh(hole, hull, reach: float, *, sections: int = DEFAULT_SECTIONS):
    """The solid cylinder a through-hole removes from the hull: diameter d along the hole's
    axis (y or z) through (x, offset), ``reach`` [m] long (beyond the hull on both sides)."""
    import trimesh

    center = np.array([hole.x, hull.y, hull.z], float)
    center[1 if hole.axis == "z" else 2] = hole.offset
    tf = _along(hole.axis)
    tf[:3, 3] = center
    return trimesh.creation.cylinder(radius=0.5 * equal_area_factor(sections) * hole.diameter,
                                     height=reach, sections=int(sections), transform=tf)


def part_meshes(vehicle, *, sections: int = DEFAULT_SECTIONS,
                stations: int = DEFAULT_STATIONS) -> list:
    """The closed meshes of a vehicle's parts, hull first (its holes cut), [m, body axes]."""
    from stripcoef.geometry.bodies import Box, Cylinder, Fin, Hull

    out = []
    for body in vehicle.bodies:
        if isinstance(body, Hull):
            mesh = hull_mesh(body, sections=sections, stations=stations)
            holes = list(getattr(vehicle, "holes", []) or []) if body is vehicle.hull else []
            if holes:
                reach = 4.0 * float(np.ptp(mesh.vertices, axis=0).max())
                cuts = [hole_mesh(h, body, reach, sections=sections) for h in holes]
                mesh = _boolean("difference", [mesh] + cuts, vehicle)
        elif isinstance(body, Cylinder):
            mesh = cylinder_mesh(body, sections=sections)
        elif isinstance(body, Box):
            mesh = box_mesh(body.center, body.size)
        elif isinstance(body, Fin):
            mesh = fin_mesh(body)
        elif hasattr(body, "united"):                     # a mesh appendage (MeshBody)
            mesh = body.united()
        else:  # pragma: no cover - every body type of the schema is above
            raise InputError("a body the surface cannot be built for",
                             file=getattr(vehicle, "source", None) or None,
                             key=getattr(body, "name", "?"), value=type(body).__name__,
                             expected="a hull, box, cylinder, fin or mesh appendage")
        out.append(mesh)
    return out


def _boolean(op: str, meshes, vehicle):
    return manifold_boolean(op, meshes, what="parts of the vehicle",
                            file=getattr(vehicle, "source", None) or None, key="appendages",
                            expected="closed parts (a mesh appendage: stripcoef mesh FILE "
                                     "--repair writes a repaired copy)")


def vehicle_surface(vehicle, *, sections: int = DEFAULT_SECTIONS,
                    stations: int = DEFAULT_STATIONS):
    r"""The wetted surface of a vehicle: its parts united into one watertight mesh.

    .. math:: S = \partial\Big(\big(H \setminus \bigcup_k C_k\big) \cup \bigcup_j P_j\Big)

    H the lofted hull (:func:`hull_mesh`), C_k the through-holes' cylinders
    (:func:`hole_mesh`), P_j the appendages (boxes, fins, cylinders, ducts as rings, mesh
    appendages); union and difference by manifold3d (module docstring).

    Parameters
    ----------
    vehicle : Vehicle
        A vehicle file's :class:`~stripcoef.geometry.vehicle.Vehicle` (or one made of a mesh:
        its bodies united).
    sections : int
        Polygon sides of every round section (at least 8).
    stations : int
        Stations per hull profile segment (at least 2).

    Returns
    -------
    trimesh.Trimesh
        Watertight, outward normals, FRD body axes [m]; ``metadata["overlap"]`` the volume
        the parts shared [m^3] and ``metadata["parts"]`` their number.
    """
    if isinstance(sections, bool) or not isinstance(sections, (int, np.integer)) or sections < 8:
        raise InputError("too few polygon sides", key="sections", value=sections,
                         expected="an integer >= 8")
    if isinstance(stations, bool) or not isinstance(stations, (int, np.integer)) or stations < 2:
        raise InputError("too few hull stations", key="stations", value=stations,
                         expected="an integer >= 2")
    from stripcoef.geometry.mesh import EdgeTopology

    parts = part_meshes(vehicle, sections=sections, stations=stations)
    total = float(sum(p.volume for p in parts))
    out = parts[0] if len(parts) == 1 else _boolean("union", parts, vehicle)
    topo = EdgeTopology(out.faces)
    where = getattr(vehicle, "source", None) or None
    if len(out.faces) == 0 or not topo.consistent or not out.volume > 0:
        raise InputError("the union of the vehicle's parts is not a closed surface",
                         file=where, key="appendages",
                         value=f"{topo.open_edges} open edges",
                         expected="closed parts of positive volume")
    out.metadata["overlap"] = max(total - float(out.volume), 0.0)
    out.metadata["parts"] = len(parts)
    return out


#: Polygon sides tried by :func:`coarsest_within`, finest first [-].
SECTION_LADDER = (64, 48, 32, 24, 16, 12)


def coarsest_within(vehicle, limits):
    r"""The vehicle's surface (:func:`vehicle_surface`) at the finest tessellation of
    :data:`SECTION_LADDER` that meets the first of ``limits`` it can: pairs (most faces, fewest
    sides), tried in turn; else the coarsest.  Hull stations scale with the sides (at least 4
    per curved segment).  The panel method passes its limits
    (:func:`stripcoef.assembly.added_mass.panel_surface`: a surface it refines rather than
    coarsens).  Returns the ``trimesh.Trimesh``; ``metadata["sections"]`` the sides used.

    The union (manifold3d) is the costly step (0.1 to 0.3 s for a 25-part ROV), so the sides
    are chosen on the parts' own face counts, which cost nothing to build, and the union is
    built once: :math:`F_\cup \approx F_{parts}\,F_\cup^{(0)} / F_{parts}^{(0)}` with the
    ratio of the first union built (the seams add faces, hidden parts remove them); only when
    the union then exceeds its limit is the next coarser tessellation built (at most a few
    unions instead of one per rung of the ladder).  The prediction is not a bound: where parts
    hide much of each other a rung whose parts' faces exceed the limit may have a union within
    it, and a coarser rung is then taken than a search uniting every rung would take (the
    shipped files and the tests' vehicles take the same rung, tests/test_vehicle_surface.py)."""
    built = {}
    parts = {}

    def stations(n):
        return max(4, round(DEFAULT_STATIONS * n / DEFAULT_SECTIONS))

    def part_faces(n):
        if n not in parts:
            parts[n] = sum(len(p.faces) for p in part_meshes(vehicle, sections=n,
                                                             stations=stations(n)))
        return parts[n]

    def surface(n):
        if n not in built:
            built[n] = vehicle_surface(vehicle, sections=n, stations=stations(n))
            built[n].metadata["sections"] = n
        return built[n]

    def predicted(n):
        if n in built:
            return len(built[n].faces)
        if not built:                                    # no union yet: the parts' faces
            return part_faces(n)
        m = next(iter(built))
        return part_faces(n) * len(built[m].faces) / max(part_faces(m), 1)

    for most, fewest in limits:
        for n in SECTION_LADDER:
            if n < fewest or predicted(n) > int(most):
                continue
            if len(surface(n).faces) <= int(most):
                return surface(n)
    return surface(SECTION_LADDER[-1])
