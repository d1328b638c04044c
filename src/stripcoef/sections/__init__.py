"""Sections: 2D coefficients per strip, and the registry of section shapes.

:data:`SHAPES` maps the name of a :class:`~stripcoef.strips.Part`'s shape to its
:class:`SectionShape`: the functions that give one run of sections of that shape

- ``added_mass(part, rho, panels) -> (k, 3, 3)``: the per-unit-length added mass (sway, heave,
  roll) about the part's centre (``panels``: the panel method's count, polygons only);
- ``cross_flow_drag(part, reynolds_y, reynolds_z) -> (cd_y, cd_z)``: the 2D drag coefficients
  for flow along y and along z (reference heights: 2h and 2b); ``cd_y`` depends on
  ``reynolds_y`` only and ``cd_z`` on ``reynolds_z`` only (the damping's power-law exponents
  perturb both in one call);
- ``wetted_perimeter(part) -> (k,)``: the wetted perimeter of each section [m] (friction drag);

and, from its :class:`~stripcoef.geometry.shapes.ShapeGeometry` in
:data:`stripcoef.geometry.shapes.GEOMETRY` (the layer below, which the geometry reads), its
outline, section properties, chord, outer area and the flags that select formulas in
``hull`` and ``assembly`` (``contoured``, ``elliptic``, ``plate``, ``corner_roll``). A new
shape is one entry in each of the two tables (a test checks they name the same shapes).

An unknown shape is an error listing the registered ones (:func:`get_shape`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Callable

import numpy as np

from stripcoef.errors import unknown_name
from stripcoef.geometry.shapes import GEOMETRY, ShapeGeometry
from stripcoef.sections import added_mass as am
from stripcoef.sections import drag
from stripcoef.sections.panel import added_mass_sections, part_rings
from stripcoef.sections.polygon_drag import cross_flow_cd


def _added_mass_ellipse(part, rho, panels=None):
    m22, m33, m44 = am.ellipse(part.half_breadth, part.half_height, rho=rho)
    return _diag3(m22, m33, m44)


def _added_mass_rectangle(part, rho, panels=None):
    m22, m33, m44 = am.rectangle(part.half_breadth, part.half_height, rho=rho)
    return _diag3(m22, m33, m44)


def _added_mass_polygon(part, rho, panels=None):
    # the part's rings, cleaned and oriented once (shared with the cross-flow drag)
    mats = added_mass_sections(part_rings(part), rho=rho, about=None, panels=panels)
    return np.asarray(mats, dtype=float)


def _diag3(a, b, c):
    out = np.zeros((np.size(a), 3, 3))
    out[:, 0, 0], out[:, 1, 1], out[:, 2, 2] = a, b, c
    return out


def _drag_ellipse(part, re_y, re_z):
    b, h = part.half_breadth, part.half_height
    circ = np.isclose(b, h, rtol=1e-6)
    cd_y = np.where(circ, drag.circle_cd(re_y), drag.ellipse_cd(b / np.maximum(h, 1e-300), re_y))
    cd_z = np.where(circ, drag.circle_cd(re_z), drag.ellipse_cd(h / np.maximum(b, 1e-300), re_z))
    return cd_y, cd_z


def _drag_rectangle(part, re_y, re_z):
    b, h = part.half_breadth, part.half_height
    return drag.rectangle_cd(b / h, re_y), drag.rectangle_cd(h / b, re_z)


def _drag_polygon(part, re_y, re_z):
    return cross_flow_cd(part, re_y, re_z)


def _perimeter_ellipse(part):
    return drag.ellipse_perimeter(part.half_breadth, part.half_height)


def _perimeter_rectangle(part):
    r"""Perimeter of a 2b x 2h rectangle: :math:`P = 4(b + h)` [m]."""
    return 4.0 * (part.half_breadth + part.half_height)


def _perimeter_polygon(part):
    r"""Sum of the edge lengths of the section's rings,
    :math:`P = \sum_{rings}\sum_i |p_{i+1} - p_i|` [m] (outer rings and holes: a duct's inner
    wall is wetted too), from the ring set :func:`panel.part_rings` the section solvers
    share."""
    if not part.contours:
        return np.zeros(part.index.size)
    rs = part_rings(part)
    return np.bincount(rs.section, rs.perimeters(), part.index.size)


@dataclass(frozen=True, kw_only=True)
class SectionShape(ShapeGeometry):
    """One section shape of the registry :data:`SHAPES`: its geometry
    (:class:`~stripcoef.geometry.shapes.ShapeGeometry`, all of whose fields it carries) and
    its 2D coefficients.

    Attributes
    ----------
    added_mass : callable
        ``f(part, rho, panels) -> (k, 3, 3)`` added mass per unit length about the part's
        centre [kg/m, kg, kg m]
    cross_flow_drag : callable
        ``f(part, re_y, re_z) -> (cd_y, cd_z)`` 2D drag coefficients [-]
    wetted_perimeter : callable
        ``f(part) -> (k,)`` wetted perimeter of each section [m]
    description : str
        What the functions use (for docs and error messages)
    """

    added_mass: Callable
    cross_flow_drag: Callable
    wetted_perimeter: Callable
    description: str = ""


def _shape(name, added_mass, cross_flow_drag, wetted_perimeter, description):
    """The :class:`SectionShape` of ``name``: its geometry from
    :data:`~stripcoef.geometry.shapes.GEOMETRY` and these coefficient functions."""
    geo = GEOMETRY[name]
    return SectionShape(**{f.name: getattr(geo, f.name) for f in fields(ShapeGeometry)},
                        added_mass=added_mass, cross_flow_drag=cross_flow_drag,
                        wetted_perimeter=wetted_perimeter, description=description)


#: The registry of section shapes: name -> :class:`SectionShape`.
SHAPES = {s.name: s for s in (
    _shape("ellipse", _added_mass_ellipse, _drag_ellipse, _perimeter_ellipse,
           "closed-form ellipse added mass; circle / ellipse cross-flow drag curves"),
    _shape("rectangle", _added_mass_rectangle, _drag_rectangle, _perimeter_rectangle,
           "DNV rectangle added mass; rectangle cross-flow drag curve"),
    _shape("polygon", _added_mass_polygon, _drag_polygon, _perimeter_polygon,
           "2D panel method; cross-flow drag of the polygon's parts"),
)}


def get_shape(name: str) -> SectionShape:
    """The :class:`SectionShape` of ``name``; an unknown name is an error listing the valid
    ones."""
    try:
        return SHAPES[name]
    except (KeyError, TypeError):
        raise unknown_name("section shape", name, SHAPES) from None


def section_added_mass(part, rho: float, panels: int | None = None) -> np.ndarray:
    r"""(k, 3, 3) added mass per unit length of ``part`` about its centre [kg/m, kg, kg m].

    Registry dispatch on ``part.shape`` (``rho`` [kg/m^3]; ``panels``: panels per section of
    the polygon panel method, default adaptive, :func:`panel.discretise`): ellipse
    :math:`m_{22} = \rho\pi h^2,\ m_{33} = \rho\pi b^2` (:func:`added_mass.ellipse`), rectangle
    :math:`m_{22} = C_A\rho\pi h^2` (:func:`added_mass.rectangle`), polygon: 2D panel method
    (:func:`panel.added_mass_sections`); each function carries its own reference
    (Newman 1977, sec. 4.13 and table 4.2; DNV-RP-C205 table A-1).
    """
    return get_shape(part.shape).added_mass(part, rho, panels)


def section_drag(part, re_y, re_z):
    r"""2D drag coefficients (cd_y, cd_z) of ``part`` for flow along y and along z [-].

    Used as :math:`f_k = \tfrac12\rho C_{D,k} H_k |V_k| V_k` per unit length, with
    reference heights :math:`H_y = 2h`, :math:`H_z = 2b` [m]; ``re_y``, ``re_z`` [-] on those
    heights. Dispatch on ``part.shape``: ellipse (circle: :func:`drag.circle_cd`, else
    :func:`drag.ellipse_cd` of d/h), rectangle (:func:`drag.rectangle_cd`), polygon
    (:func:`polygon_drag.cross_flow_cd`). Cross-flow principle: Hoerner (1965), ch. 3
    (see :mod:`stripcoef.sections.drag`).
    """
    return get_shape(part.shape).cross_flow_drag(part, re_y, re_z)
