r"""The sidewash of the appendages' trailing vortices at the appendages behind them (an option).

The lift matrix of ``stripcoef.assembly.lift`` lets every fin lift on its own incidence in the
body's flow. A fin behind another (a stern plane behind the sail, a ring wing behind the stern
planes) also meets the trailing vortex of the one ahead: Pitts, Nielsen & Kaattari's (1957, NACA
Report 1307) wing-tail interference, in the linear form of :mod:`stripcoef.hull.vortex`. This
module adds it as a separate lift matrix,

.. math:: \Delta L = \sum_{s,\,t} k_t\,g_s\,\bar h_{st}\;c_t\,a_s^T

over every source panel s whose trailing edge lies ahead of the tail surface t's leading edge:
:math:`k_t c_t` the tail's force column per unit incidence as the lift model builds it (its
lift slope, wing-body factors and stern-flow dynamic pressure,
``stripcoef.assembly.lift._panel_terms``), :math:`g_s` the source's circulation per unit
cross-flow from its own lift (:func:`stripcoef.hull.vortex.circulation_per_crossflow`),
:math:`\bar h_{st}` the tail's mean sidewash per unit circulation with the vortex's image in the
tail station's body section (:func:`stripcoef.hull.vortex.panel_sidewash`,
:func:`stripcoef.hull.vortex.ring_sidewash`) and :math:`a_s` the source's incidence column (its
three-quarter chord's for the rotation). Not in the default model: the validation and
``python -m benchmarks.lift_band --sidewash`` add it to measure it on Roddy's SUBOFF data.
"""

from __future__ import annotations

import numpy as np

from stripcoef.assembly.lift import (_body_lift, _panel_terms, _round, _stern_flow,
                                     ring_wing_lift)
from stripcoef.errors import InputError
from stripcoef.geometry.vehicle import Fin, exposed_panels
from stripcoef.hull.lift import lift_column, rotary_incidence_point
from stripcoef.hull.vortex import (circulation_per_crossflow, panel_sidewash, ring_sidewash,
                                   vortex_position)

_AXES = {"y": np.array([1.0, 0.0]), "z": np.array([0.0, 1.0])}


def _panels(vehicle):
    """Every lifting panel on the hull: free fins and control-surface panels, as the lift model
    takes them."""
    hull = vehicle.hull
    in_surface = {n for s in vehicle.control_surfaces for n in s.fins}
    out = []
    for fin in vehicle.bodies:
        if isinstance(fin, Fin) and fin.name not in in_surface:
            try:
                out += [(fin.name, p) for p in exposed_panels(
                    hull, fin.center, fin.span, fin.chord, fin.span_axis,
                    path=f"appendages[{fin.name}]")]
            except InputError:
                continue          # on another appendage: no lift in the model either
    for s in vehicle.control_surfaces:
        out += [(s.name, p) for p in s.panels]
    return out


def _panel_record(name, panel, hull, ref, rho, round_, slender):
    """Geometry and force terms of one panel (cross-flow plane relative to the hull axis)."""
    _, _, info = _panel_terms(panel, ref, rho, round_, slender)
    q = info.get("pressure_ratio", 1.0)
    k = 0.5 * rho * panel.area * info["lift_slope"] * q
    if slender is None:
        fw, fb = info["interference"], 0.0
    elif info["body_upwash"]:
        fw, fb = info["K_WB"], info["K_BW"]
    else:
        fw, fb = info["k_WB"], info["k_BW"]
    lift_axis = panel.normal
    span_axis = "z" if lift_axis == "y" else "y"
    axis = np.array([hull.y, hull.z])
    offset = float(panel.center["xyz".index(span_axis)]) - axis["yz".index(span_axis)]
    span_dir = np.sign(offset) * _AXES[span_axis]
    e3 = np.zeros(3)
    e3["xyz".index(lift_axis)] = 1.0
    x = float(panel.center[0])
    point = np.asarray(panel.center, float) + np.array([0.25 * panel.chord, 0.0, 0.0]) \
        - np.asarray(ref, float)
    c_f = lift_column(e3, point)
    if slender is None:
        column = c_f
    else:
        c_b = lift_column(e3, np.array([x + 0.25 * panel.chord, hull.y, hull.z])
                          - np.asarray(ref, float))
        column = (fw * c_f + fb * c_b) / (fw + fb) if fw + fb > 0.0 else c_f
    side = {("z", -1.0): "top", ("z", 1.0): "bottom", ("y", -1.0): "port",
            ("y", 1.0): "starboard"}[(span_axis, float(np.sign(offset)))]
    return {"name": f"{name} ({side})", "x_le": x + 0.5 * panel.chord, "x_te": x - 0.5 * panel.chord,
            "root": panel.root, "span": panel.span, "span_dir": span_dir,
            "lift_dir": _AXES[lift_axis], "k_own": k * fw, "k_tail": k * (fw + fb),
            "column": column, "incidence": lift_column(e3, rotary_incidence_point(point,
                                                                                  panel.chord))}


def appendage_sidewash(vehicle, rho: float, ref, *, ring: dict | None = None,
                       speed: float | None = None,
                       viscosity: float | None = None) -> tuple[np.ndarray, dict]:
    r"""The lift matrix of the appendages' trailing-vortex sidewash, :math:`\Delta L`
    (module docstring), and a summary.

    Parameters
    ----------
    vehicle : Vehicle
        With a round hull and fins (other vehicles: zero)
    rho : float
        Fluid density [kg/m^3]
    ref : (3,)
        Reference point [m]
    ring : dict, optional
        A ring wing's chord line, ``x_le``, ``x_te``, ``r_le``, ``r_te`` [m] (as
        ``stripcoef.assembly.lift.ring_wing_lift``): a tail surface too
    speed, viscosity : float, optional
        As ``stripcoef.assembly.lift.vehicle_lift``

    Returns
    -------
    dL : (6, 6) [kg/m, kg, kg m]
    info : dict
        ``pairs``: per source and tail, the source's vortex distance f [m], circulation per
        unit cross-flow g [m] and the tail's mean sidewash per unit incidence at the source
        g h [-] (negative: against the source's incidence)

    References
    ----------
    Pitts, Nielsen & Kaattari 1957, NACA Report 1307; :mod:`stripcoef.hull.vortex`.
    """
    out = np.zeros((6, 6))
    hull = vehicle.hull
    if hull is None or not _round(hull):
        return out, {"pairs": []}
    body = _body_lift(vehicle, rho, ref, ref, speed=speed, viscosity=viscosity)
    slender = _stern_flow(vehicle, body, speed, viscosity)
    round_ = _round(hull)
    recs = [_panel_record(n, p, hull, ref, rho, round_, slender) for n, p in _panels(vehicle)]
    pairs = []
    for s in recs:
        f = vortex_position(s["root"], s["span"])
        g = circulation_per_crossflow(s["k_own"], f, s["root"], rho=rho)
        vortex = f * s["span_dir"]
        for t in recs:
            if t is s or s["x_te"] < t["x_le"]:
                continue
            a_t = t["root"]
            if f <= a_t:
                continue          # the vortex inside the tail's body section: no field there
            h = panel_sidewash(vortex, s["lift_dir"], a_t, root=t["root"], span=t["span"],
                               span_direction=t["span_dir"], direction=t["lift_dir"])
            out += t["k_tail"] * g * h * np.outer(t["column"], s["incidence"])
            pairs.append({"source": s["name"], "tail": t["name"], "f": f, "g": g,
                          "sidewash": g * h})
        if ring is not None and s["x_te"] >= ring["x_le"]:
            radius = 0.5 * (ring["r_le"] + ring["r_te"])
            x_mid = 0.5 * (ring["x_le"] + ring["x_te"])
            a_t = float(hull.half_breadth(np.array([x_mid]))[0])
            if f <= a_t:
                continue
            w = g * ring_sidewash(vortex, s["lift_dir"], a_t, radius=radius)
            ring_l, ring_info = ring_wing_lift(vehicle, rho, ref, speed=speed,
                                               viscosity=viscosity, **ring)
            k_ring = ring_l[1, 1]
            point = np.array([ring_info["x_quarter_chord"], hull.y, hull.z]) \
                - np.asarray(ref, float)
            for i, e3 in ((0, np.array([0.0, 1.0, 0.0])), (1, np.array([0.0, 0.0, 1.0]))):
                out += k_ring * w[i] * np.outer(lift_column(e3, point), s["incidence"])
            pairs.append({"source": s["name"], "tail": "ring wing", "f": f, "g": g,
                          "sidewash": float(w @ s["lift_dir"])})
    return out, {"pairs": pairs}
