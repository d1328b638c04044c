r"""The geometry of each section shape: what the code below the coefficients asks of a shape.

:data:`GEOMETRY` maps a :class:`~stripcoef.strips.Part`'s ``shape`` to its
:class:`ShapeGeometry`: how a section of that shape is drawn (its outline rings), its section
properties when it is built from half sizes (a vehicle file's hull), its chord at an offset
(a through-hole's depth), the area inside its outer outline (an appendage's frontal area),
and the flags that select a formula elsewhere (``contoured``: the section is its polygon
rings; ``elliptic``: a circle where b = h, for the finned-circle and slender-body formulas;
``plate``: a thin part of this shape is a flat plate; ``corner_roll``: the flat sides of the
section give roll drag about its own centre).

The 2D coefficients of a shape (added mass, cross-flow drag, wetted perimeter) sit one layer
up in :data:`stripcoef.sections.SHAPES`, whose :class:`~stripcoef.sections.SectionShape`
carries these fields too: a shape is one entry here and one there (a test checks that the
two registries name the same shapes). The geometry layer sits below ``sections`` and reads
this table; ``hull`` and ``assembly`` read ``sections.SHAPES``.

Section properties (half-axes b along y, h along z [m]):

- ellipse: area :math:`\pi b h`, :math:`\int (y-y_c)^2 dA = \pi b^3 h / 4`,
  :math:`\int (z-z_c)^2 dA = \pi b h^3/4`;
- rectangle 2b x 2h: area 4bh, second moments :math:`4 b^3 h/3` and :math:`4 b h^3 / 3`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from stripcoef.errors import unknown_name


def ellipse_section(b, h):
    """Area [m^2] and second moments iyy, izz [m^4] of an ellipse with half-axes b (y), h (z).

    A = pi b h, iyy = int y^2 dA = pi b^3 h / 4, izz = int z^2 dA = pi b h^3 / 4 (b, h [m];
    the naming of :class:`stripcoef.strips.Part`). Reference: standard second moments of
    area of an ellipse about its axes (elementary integration).
    """
    return np.pi * b * h, np.pi * b**3 * h / 4.0, np.pi * b * h**3 / 4.0


def rectangle_section(b, h):
    """Area [m^2] and second moments iyy, izz [m^4] of a 2b x 2h rectangle.

    A = 4 b h, iyy = int y^2 dA = (2h)(2b)^3/12 = 4 b^3 h / 3, izz = 4 b h^3 / 3 (b, h [m];
    the naming of :class:`stripcoef.strips.Part`). Reference: standard second moments of
    area of a rectangle about its centroidal axes (elementary integration).
    """
    return 4.0 * b * h, 4.0 * b**3 * h / 3.0, 4.0 * b * h**3 / 3.0


def _ellipse_half_chord(half_across, half_along, offset):
    r"""Half chord of an ellipse of half-axes b (across) and h (along) at ``offset`` d [m]:

    .. math:: h\sqrt{1 - (d/b)^2}\quad(0 \text{ for } |d| \ge b)

    Reference: the ellipse's equation :math:`(y/b)^2 + (z/h)^2 = 1`.
    """
    frac = np.clip(1.0 - (offset / np.maximum(half_across, 1e-300)) ** 2, 0.0, 1.0)
    return half_along * np.sqrt(frac)


def _box_half_chord(half_across, half_along, offset):
    """Half chord of a rectangle (and of a polygon's bounding box): its half-side h [m]."""
    return half_along * np.ones_like(np.asarray(offset, dtype=float))


def ellipse_rings(yc, zc, b, h, points):
    r"""Closed rings (..., points + 1, 2) of ellipses centred at (yc, zc), half-axes b, h [m]
    (scalars or arrays of one shape): :math:`(y_c + b\cos a_j,\ z_c + h\sin a_j)`,
    :math:`a_j = 2\pi j/n`, the first point repeated at the end."""
    a = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    yc, zc, b, h = (np.asarray(v, dtype=float)[..., None] for v in (yc, zc, b, h))
    ring = np.stack(np.broadcast_arrays(yc + b * np.cos(a), zc + h * np.sin(a)), axis=-1)
    return np.concatenate([ring, ring[..., :1, :]], axis=-2)


def _ellipse_ring(yc, zc, b, h, points):
    """Closed (points + 1, 2) ring of an ellipse centred at (yc, zc), half-axes b, h [m]."""
    return ellipse_rings(yc, zc, b, h, points)


def _outline_ellipse(part, k, points):
    return [_ellipse_ring(part.y[k], part.z[k], part.half_breadth[k], part.half_height[k], points)]


def _outlines_ellipse(part, points):
    return ellipse_rings(part.y, part.z, part.half_breadth, part.half_height, points)


def _outline_rectangle(part, k, points):
    yc, zc, b, h = part.y[k], part.z[k], part.half_breadth[k], part.half_height[k]
    return [np.array([[yc - b, zc - h], [yc + b, zc - h], [yc + b, zc + h],
                      [yc - b, zc + h], [yc - b, zc - h]])]


def _outline_polygon(part, k, points):
    if part.contours is None:        # no rings: drawn as the ellipse of its half sizes
        return _outline_ellipse(part, k, points)
    return [np.asarray(ring, float) for ring in part.contours[k]]


def _filled_area(part):
    return part.area + part.entrained_area


def _box_area(part):
    return 4.0 * part.half_breadth * part.half_height


@dataclass(frozen=True)
class ShapeGeometry:
    """The geometry of one section shape of the registry :data:`GEOMETRY`.

    Attributes
    ----------
    name : str
        The shape's name (``Part.shape``)
    outline : callable
        ``f(part, k, points) -> list of (n, 2) arrays``: the closed (y, z) rings [m] of the
        part's k-th section (outer rings counter-clockwise, holes clockwise; ``points``: the
        vertices of a curved outline)
    half_chord : callable
        ``f(half_across, half_along, offset) -> half chord`` [m] along one axis at ``offset``
        from the centre across it (the depth of a through-hole)
    outer_area : callable
        ``f(part) -> (k,)``: the area inside the section's outer outline [m^2] (what an
        appendage presents to the axial flow)
    properties : callable or None
        ``f(b, h) -> (area, iyy, izz)`` [m^2, m^4, m^4] of a section built from its half
        sizes; None for a shape that only comes from a mesh (a vehicle file's hull
        ``section`` may name the shapes that have it)
    rounded : bool
        A hull of this section has rounded edges (Re-dependent drag, ``Part.rounded``)
    contoured : bool
        The section is its polygon rings (``Part.contours``): the shapely and ring-based
        formulas apply (members and junctions, bores, roll modes)
    elliptic : bool
        An ellipse, a circle where b = h: the finned-circle, fin-sheet and slender-body
        formulas apply to a round hull of this shape
    plate : bool
        A fin of this shape is a flat plate (fin axial added mass, the fin sheet)
    corner_roll : bool
        The section's flat sides give roll drag about its own centre
    outlines : callable or None
        ``f(part, points) -> (k, m, 2)``: every section's outline at once, for a shape whose
        outline is one ring of the same vertex count on every strip (``outline`` of each k,
        stacked); None where it is not
    """

    name: str
    outline: Callable
    half_chord: Callable
    outer_area: Callable
    properties: Callable | None = None
    rounded: bool = False
    contoured: bool = False
    elliptic: bool = False
    plate: bool = False
    corner_roll: bool = False
    outlines: Callable | None = None


#: The geometry of the section shapes: name -> :class:`ShapeGeometry`.
GEOMETRY = {g.name: g for g in (
    ShapeGeometry("ellipse", _outline_ellipse, _ellipse_half_chord, _filled_area,
                  properties=ellipse_section, rounded=True, elliptic=True,
                  outlines=_outlines_ellipse),
    ShapeGeometry("rectangle", _outline_rectangle, _box_half_chord, _box_area,
                  properties=rectangle_section, plate=True, corner_roll=True),
    ShapeGeometry("polygon", _outline_polygon, _box_half_chord, _filled_area, contoured=True),
)}


def shape_geometry(name: str) -> ShapeGeometry:
    """The :class:`ShapeGeometry` of ``name``; an unknown name is an error listing the valid
    ones."""
    try:
        return GEOMETRY[name]
    except (KeyError, TypeError):
        raise unknown_name("section shape", name, GEOMETRY) from None


def built_from_half_sizes() -> tuple[str, ...]:
    """The shapes a vehicle file's hull ``section`` may name (those with ``properties``)."""
    return tuple(n for n, g in GEOMETRY.items() if g.properties is not None)


def has_rings(part) -> bool:
    """True when ``part`` is of a contoured shape and carries its rings (``Part.contours``)."""
    return shape_geometry(part.shape).contoured and part.contours is not None


def section_half_chord(shape: str, half_across, half_along, offset):
    r"""Half the length [m] of a section's chord along one of its axes, at ``offset`` [m] from the
    centre across it: an ellipse of half-axes b (across) and h (along) gives

    .. math:: h\sqrt{1 - (d/b)^2}\quad(0 \text{ for } |d| \ge b),

    a rectangle (and a polygon's box) its half-side h (``half_across`` b, ``half_along`` h
    [m], scalars or arrays; ``shape`` a name of :data:`GEOMETRY`).  Reference: the ellipse's
    equation :math:`(y/b)^2 + (z/h)^2 = 1`.
    """
    return shape_geometry(shape).half_chord(half_across, half_along, offset)
