"""Sections: 2D coefficients per strip, one registry per family.

- :data:`ADDED_MASS` maps a :class:`~stripcoef.strips.Part` shape to a function
  ``f(part, rho, panels) -> (k, 3, 3)`` giving the per-unit-length added mass (sway, heave,
  roll) about the part's centre (``panels``: the panel method's count, polygons only).
- :data:`CROSS_FLOW_DRAG` maps a shape to ``f(part, reynolds_y, reynolds_z) -> (cd_y, cd_z)``,
  the 2D drag coefficients for flow along y and along z (reference heights: 2h and 2b);
  ``cd_y`` depends on ``reynolds_y`` only and ``cd_z`` on ``reynolds_z`` only (the damping's
  power-law exponents perturb both in one call).

An unknown shape is an error listing the registered ones.
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import unknown_name
from stripcoef.sections import added_mass as am
from stripcoef.sections import drag


def _added_mass_ellipse(part, rho, panels=None):
    m22, m33, m44 = am.ellipse(part.half_breadth, part.half_height, rho=rho)
    return _diag3(m22, m33, m44)


def _added_mass_rectangle(part, rho, panels=None):
    m22, m33, m44 = am.rectangle(part.half_breadth, part.half_height, rho=rho)
    return _diag3(m22, m33, m44)


def _added_mass_polygon(part, rho, panels=None):
    from stripcoef.sections.panel import added_mass_sections, part_rings  # noqa: PLC0415 (mesh path only)
    # the part's rings, cleaned and oriented once (shared with the cross-flow drag)
    mats = added_mass_sections(part_rings(part), rho=rho, about=None, panels=panels)
    return np.asarray(mats, dtype=float)


def _diag3(a, b, c):
    out = np.zeros((np.size(a), 3, 3))
    out[:, 0, 0], out[:, 1, 1], out[:, 2, 2] = a, b, c
    return out


ADDED_MASS = {
    "ellipse": _added_mass_ellipse,
    "rectangle": _added_mass_rectangle,
    "polygon": _added_mass_polygon,
}


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
    from stripcoef.sections.polygon_drag import cross_flow_cd  # noqa: PLC0415 (mesh path only)
    return cross_flow_cd(part, re_y, re_z)


CROSS_FLOW_DRAG = {
    "ellipse": _drag_ellipse,
    "rectangle": _drag_rectangle,
    "polygon": _drag_polygon,
}


def section_added_mass(part, rho: float, panels: int | None = None) -> np.ndarray:
    r"""(k, 3, 3) added mass per unit length of ``part`` about its centre [kg/m, kg, kg m].

    Registry dispatch on ``part.shape`` (``rho`` [kg/m^3]; ``panels``: panels per section of
    the polygon panel method, default adaptive, :func:`panel.discretise`): ellipse
    :math:`m_{22} = \rho\pi h^2,\ m_{33} = \rho\pi b^2` (:func:`added_mass.ellipse`), rectangle
    :math:`m_{22} = C_A\rho\pi h^2` (:func:`added_mass.rectangle`), polygon: 2D panel method
    (:func:`panel.added_mass_sections`); each function carries its own reference
    (Newman 1977, sec. 4.13 and table 4.2; DNV-RP-C205 table A-1).
    """
    try:
        fn = ADDED_MASS[part.shape]
    except KeyError:
        raise unknown_name("section shape", part.shape, ADDED_MASS) from None
    return fn(part, rho, panels)


def section_drag(part, re_y, re_z):
    r"""2D drag coefficients (cd_y, cd_z) of ``part`` for flow along y and along z [-].

    Used as :math:`f_k = \tfrac12\rho C_{D,k} H_k |V_k| V_k` per unit length, with
    reference heights :math:`H_y = 2h`, :math:`H_z = 2b` [m]; ``re_y``, ``re_z`` [-] on those
    heights. Dispatch on ``part.shape``: ellipse (circle: :func:`drag.circle_cd`, else
    :func:`drag.ellipse_cd` of d/h), rectangle (:func:`drag.rectangle_cd`), polygon
    (:func:`polygon_drag.cross_flow_cd`). Cross-flow principle: Hoerner (1965), ch. 3
    (see :mod:`stripcoef.sections.drag`).
    """
    try:
        fn = CROSS_FLOW_DRAG[part.shape]
    except KeyError:
        raise unknown_name("section shape", part.shape, CROSS_FLOW_DRAG) from None
    return fn(part, re_y, re_z)
