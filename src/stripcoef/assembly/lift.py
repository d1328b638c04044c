r"""Body and fin lift of a vehicle, and its control surfaces, about the reference point.

The formulas are in :mod:`stripcoef.hull.lift` (Hoerner & Borst 1985; Helmbold 1942; Whicker & Fehlner
1958; Prestero 2001, secs. 3.6-3.7); this module walks the vehicle's hull, fin appendages
and control surfaces and sums them:

.. math:: L = L_{body} + \sum_{fins} \tfrac12\rho S_f c_{L\alpha,f} K_f\, c_f c_f^T,
          \qquad b_s = \sum_{panels\ of\ s} \tfrac12\rho S_p c_{L\alpha,p}\, c_p\, \sigma_s

with :math:`c = [e;\ r\times e]` at the panel's quarter chord, :math:`K_f` the fin-hull
interference factor (Pitts, Nielsen & Kaattari 1957) of a fin on a cylindrical stretch of a
round hull (1 elsewhere) and :math:`\sigma_s` the sign
of the deflection convention (Prestero 2001: a positive rudder gives +Y, a positive
elevator gives -Z).
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.bodies import Fin
from stripcoef.geometry.shapes import shape_geometry
from stripcoef.geometry.vehicle import SurfacePanel, exposed_panels
from stripcoef.hull.lift import (
    BODY_CP_FRACTION,
    MIN_SLENDERNESS,
    body_lift_matrix,
    cylindrical_root,
    separation_station,
    slender_body_lift_matrix,
    effective_aspect_ratio,
    fin_lift_matrix,
    fin_lift_slope,
    interference_factor,
    lift_column,
)
from stripcoef.model import ControlSurface

#: Stations sampling the hull for the slender-body lift (assumption: on the SUBOFF hull's
#: tabulated profile the matrix changes by 0.7 % between 2001 and 8001 stations, because the
#: steepest-closing station of a piecewise-linear profile moves with the sampling) [-].
SLENDER_STATIONS = 2001

#: Force direction of a positive deflection (Prestero 2001, sec. 3.7: Y_uudr > 0, Z_uuds < 0).
DEFLECTION_FORCE = {"rudder": np.array([0.0, 1.0, 0.0]), "elevator": np.array([0.0, 0.0, -1.0])}


def _panel_terms(panel: SurfacePanel, ref, rho: float, round_hull: bool):
    """(L (6, 6), k c (6,), info) of one panel at its quarter chord (module docstring).

    L = 1/2 rho S c_La K c c^T [kg/m, kg, kg m] (:func:`~stripcoef.hull.lift.fin_lift_matrix`),
    with K the fin-hull interference factor (1 + R/s)^2 of a panel on a cylindrical stretch of
    a round hull and 1 elsewhere (:func:`~stripcoef.hull.lift.interference_factor`);
    k c = 1/2 rho S c_La c, the force per u^2 per rad of deflection [kg/m, kg] (Prestero 2001,
    sec. 3.7; the deflection's own interference is not modelled).
    """
    ar = float(effective_aspect_ratio(panel.span, panel.area))
    cla = float(fin_lift_slope(ar))
    on_cylinder = round_hull and cylindrical_root(panel.root_radii)
    factor = interference_factor(panel.root, panel.root + panel.span) if on_cylinder else 1.0
    point = np.asarray(panel.center, float) + np.array([0.25 * panel.chord, 0.0, 0.0]) \
        - np.asarray(ref, float)
    e = np.zeros(3)
    e["xyz".index(panel.normal)] = 1.0
    column = 0.5 * rho * panel.area * cla * lift_column(e, point)
    return (fin_lift_matrix(panel.area, cla * factor, e, point, rho=rho), column,
            {"aspect_ratio": ar, "lift_slope": cla, "area": panel.area,
             "interference": factor})


def vehicle_lift(vehicle, rho: float, ref, *, center=None) -> tuple[np.ndarray, tuple, dict]:
    """Lift matrix L (force -u L nu), control surfaces and a summary, about ``ref`` [m].

    Parameters
    ----------
    vehicle : Vehicle
    rho : float
        Fluid density [kg/m^3]
    ref : (3,)
        Reference point [m]
    center : (3,), optional
        Centre of buoyancy [m], where the body lift's sideslip is measured (default ``ref``)

    Returns
    -------
    L : (6, 6) [kg/m, kg, kg m]
    surfaces : tuple of :class:`~stripcoef.model.ControlSurface`
    info : dict
        What was included (for ``conditions``)

    References
    ----------
    Prestero 2001, secs. 3.6-3.7; module docstring.
    """
    if vehicle.hull is None:            # a mesh: no fins, no surfaces known to the model
        return np.zeros((6, 6)), (), {}
    lift = np.zeros((6, 6))
    info: dict = {}
    in_surface = {n for s in vehicle.control_surfaces for n in s.fins}
    hull = vehicle.hull
    round_ = _round(hull)
    fins = [b for b in vehicle.bodies if isinstance(b, Fin) and b.name not in in_surface]
    fin_info = []
    no_lift = []
    for fin in fins:
        try:
            panels = exposed_panels(hull, fin.center, fin.span, fin.chord, fin.span_axis,
                                    path=f"appendages[{fin.name}]")
        except InputError:
            no_lift.append(fin.name)     # on another appendage, not on the hull
            continue
        for p in panels:
            m, _, pinfo = _panel_terms(p, ref, rho, round_)
            lift += m
            fin_info.append({"name": fin.name, **pinfo})
    surfaces = []
    for s in vehicle.control_surfaces:
        b = np.zeros(6)
        for p in s.panels:
            m, column, pinfo = _panel_terms(p, ref, rho, round_)
            lift += m
            b += column * float(DEFLECTION_FORCE[s.kind] @ column[:3] / abs(column[:3]).max())
            fin_info.append({"name": s.name, **pinfo})
        surfaces.append(ControlSurface(name=s.name, kind=s.kind, derivative=b,
                                       max_deflection=s.max_deflection,
                                       stall_angle=s.stall_angle))
    body = _body_lift(vehicle, rho, ref, ref if center is None else center)
    if body is not None:
        lift += body[0]
        info["body_lift"] = body[1]
    if fin_info:
        info["fin_lift"] = fin_info
    if no_lift:
        info["fins_without_lift"] = no_lift
    return lift, tuple(surfaces), info


def _round(hull) -> bool:
    """A hull of circular sections (one radius profile): where body lift and the fin-hull
    interference of slender-body theory apply."""
    return hull.half_breadth is hull.half_height and shape_geometry(hull.section).elliptic


def _body_lift(vehicle, rho: float, ref, center):
    """Body lift of a slender hull of revolution (Hoerner & Borst 1985; Prestero 2001 sec. 3.6.1).

    ``body_lift: auto`` (default) includes it when the vehicle has fins or control surfaces
    and a circular hull with l/d >= :data:`MIN_SLENDERNESS`; ``on`` asks for it (a hull that
    is not slender and round is then an error), ``off`` leaves it out; ``slender`` asks for
    the slender-body lift ahead of Hopkins's separation station instead of Hoerner's point
    force (:func:`~stripcoef.hull.lift.slender_body_lift_matrix`: it answers the local
    cross-flow, so a yaw or pitch rate gives rotary terms). Returns
    (L [kg/m, kg, kg m], info) or None.
    """
    hull = vehicle.hull
    mode = vehicle.body_lift
    if mode == "off" or hull is None:
        return None
    has_fins = bool(vehicle.control_surfaces) or any(isinstance(b, Fin) for b in vehicle.bodies)
    if mode == "auto" and not has_fins:
        return None
    lo, hi = hull.x_extent()
    length = hi - lo
    d = hull.max_diameter()
    if not _round(hull) or length / d < MIN_SLENDERNESS:
        if mode in ("on", "slender"):
            raise InputError("body lift needs a slender round hull", file=vehicle.source,
                             key="body_lift", value=f"l/d = {length / d:.3g}",
                             expected=f"a hull 'profile' (circular) with l/d >= {MIN_SLENDERNESS:g}")
        return None
    if mode == "slender":
        xs = np.linspace(lo, hi, SLENDER_STATIONS)
        area = np.pi * hull.half_breadth(xs) * hull.half_height(xs)
        x0 = separation_station(xs, area)
        return (slender_body_lift_matrix(xs, area, x0, rho=rho, y=hull.y, z=hull.z, ref=ref),
                {"method": "slender", "length": length, "diameter": d, "separation_x": x0})
    x_cp = hi - BODY_CP_FRACTION * length
    cp = np.array([x_cp, hull.y, hull.z]) - np.asarray(ref, float)
    return (body_lift_matrix(length, d, cp, rho=rho,
                             velocity_point=np.asarray(center, float) - np.asarray(ref, float)),
            {"length": length, "diameter": d, "center_of_pressure_x": x_cp})
