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
three-quarter chord's for the rotation). ``body_vortices``: the body's separated pair behind
the body-lift rule's separation station too (:func:`_body_pair`; its position is an assumption
of this model, not a published body-vortex method). Not in the default model: the validation and
``python -m benchmarks.lift_band --sidewash`` add it to measure it on Roddy's SUBOFF data.
"""

from __future__ import annotations

import numpy as np

from stripcoef.assembly.lift import (_body_lift, _panel_terms, _round, _stern_flow,
                                     lifting_fins, ring_wing_lift)
from stripcoef.geometry.vehicle import Fin, exposed_panels
from stripcoef.hull.lift import lift_column, rotary_incidence_point
from stripcoef.hull.vortex import (circulation_per_crossflow, panel_sidewash, ring_sidewash,
                                   vortex_position)

def _axis(name: str) -> np.ndarray:
    """The unit vector of body axis ``name`` ('y' or 'z') in the cross-flow plane (y, z)."""
    return np.array([1.0, 0.0]) if name == "y" else np.array([0.0, 1.0])


def _panels(vehicle):
    """Every lifting panel on the hull: free fins and control-surface panels, as the lift model
    takes them."""
    hull = vehicle.hull
    in_surface = {n for s in vehicle.control_surfaces for n in s.fins}
    lifts = {n for group in lifting_fins(vehicle).values() for n in group}
    out = []
    for fin in vehicle.bodies:       # a fin on another appendage has no lift in the model
        if isinstance(fin, Fin) and fin.name not in in_surface and fin.name in lifts:
            out += [(fin.name, p) for p in exposed_panels(
                hull, fin.center, fin.span, fin.chord, fin.span_axis,
                path=f"appendages[{fin.name}]")]
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
    span_dir = np.sign(offset) * _axis(span_axis)
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
    return {"name": f"{name} ({side})", "x_le": x + 0.5 * panel.chord,
            "x_te": x - 0.5 * panel.chord,
            "root": panel.root, "span": panel.span, "span_dir": span_dir,
            "lift_dir": _axis(lift_axis), "k_own": k * fw, "k_tail": k * (fw + fb),
            "column": column, "incidence": lift_column(e3, rotary_incidence_point(point,
                                                                                  panel.chord))}


def _body_pair(info: dict, hull, ref) -> list[dict]:
    r"""The body's separated vortex pair as two sources (a cross-flow along y and along z):
    behind the separation station :math:`x_0` the body's cross-flow impulse
    :math:`\rho\,k\,S_0\,w(x_0)` (the body lift's first term,
    :func:`stripcoef.hull.lift.slender_body_lift_matrix`, with the DATCOM rule's Munk factor k)
    leaves the body as a trailing vortex system. Assumption: it is that of the flat plate of the
    body's width at x_0, normal to the cross-flow (the plate of semi-span :math:`a_0` and the
    circle of radius :math:`a_0` have the same cross-flow apparent mass :math:`\rho\pi a_0^2`,
    Newman 1977, table 4.2), elliptically loaded with root circulation
    :math:`\Gamma_0 = 2 k a_0 w` and rolled up (Spreiter & Sacks 1951) into a pair at
    :math:`\pm(\pi/4)\,a_0` of strength :math:`\Gamma_0` (impulse :math:`\rho\Gamma_0\,
    2 (\pi/4) a_0 = \rho k \pi a_0^2 w`, the same), trailing straight aft in the plane normal
    to the cross-flow."""
    x0 = float(info["separation_x"])
    a0 = float(hull.half_breadth(np.array([x0]))[0])
    if a0 <= 0.0:
        return []
    k = float(info.get("munk_factor", 1.0))
    f = vortex_position(0.0, a0)
    out = []
    for lift_axis, span_axis in (("y", "z"), ("z", "y")):
        e3 = np.zeros(3)
        e3["xyz".index(lift_axis)] = 1.0
        out.append({"name": f"body (cross-flow {lift_axis})", "x_te": x0, "f": f,
                    "vortices": [f * _axis(span_axis), -f * _axis(span_axis)],
                    "lift_dir": _axis(lift_axis), "g": 2.0 * k * a0,
                    "incidence": lift_column(e3, np.array([x0, hull.y, hull.z])
                                             - np.asarray(ref, float))})
    return out


def appendage_sidewash(vehicle, rho: float, ref, *, ring: dict | None = None,
                       body_vortices: bool = False, speed: float | None = None,
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
        ``stripcoef.assembly.lift.ring_wing_lift``): a tail surface too, its own stiffness
        that of the ring in the undisturbed cross-flow (``wake=False`` there: add this dL to a
        model whose ring has ``wake=False``)
    body_vortices : bool
        Also the body's separated vortex pair behind the separation station
        (:func:`_body_pair`), at the surfaces behind that station (slender-body rules only)
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
    sources = []
    for s in recs:
        f = vortex_position(s["root"], s["span"])
        sources.append({"name": s["name"], "x_te": s["x_te"], "f": f,
                        "vortices": [f * s["span_dir"]], "lift_dir": s["lift_dir"],
                        "g": circulation_per_crossflow(s["k_own"], f, s["root"], rho=rho),
                        "incidence": s["incidence"], "record": s})
    if body_vortices and body is not None and "separation_x" in body[1]:
        sources += _body_pair(body[1], hull, ref)
    ring_terms = None
    if ring is not None:
        # the ring's own sideslip stiffness, in the undisturbed cross-flow: the vortices'
        # sidewash here replaces ring_wing_lift's separated-wake rule (not added to it)
        ring_l, ring_info = ring_wing_lift(vehicle, rho, ref, speed=speed, viscosity=viscosity,
                                           wake=False, **ring)
        x_mid = 0.5 * (ring["x_le"] + ring["x_te"])
        ring_terms = {"k": ring_l[1, 1], "radius": 0.5 * (ring["r_le"] + ring["r_te"]),
                      "a": float(hull.half_breadth(np.array([x_mid]))[0]),
                      "point": np.array([ring_info["x_quarter_chord"], hull.y, hull.z])
                      - np.asarray(ref, float)}
    pairs = []
    for s in sources:
        f, g = s["f"], s["g"]
        for t in recs:
            if t is s.get("record") or s["x_te"] < t["x_le"] or f <= t["root"]:
                continue      # not behind the source, or the vortex inside the tail's section
            h = sum(panel_sidewash(v, s["lift_dir"], t["root"], root=t["root"], span=t["span"],
                                   span_direction=t["span_dir"], direction=t["lift_dir"])
                    for v in s["vortices"])
            out += t["k_tail"] * g * h * np.outer(t["column"], s["incidence"])
            pairs.append({"source": s["name"], "tail": t["name"], "f": f, "g": g,
                          "sidewash": g * h})
        if ring_terms is not None and s["x_te"] >= ring["x_le"] and f > ring_terms["a"]:
            w = g * sum(ring_sidewash(v, s["lift_dir"], ring_terms["a"],
                                      radius=ring_terms["radius"]) for v in s["vortices"])
            for i, e3 in ((0, np.array([0.0, 1.0, 0.0])), (1, np.array([0.0, 0.0, 1.0]))):
                out += ring_terms["k"] * w[i] * np.outer(lift_column(e3, ring_terms["point"]),
                                                         s["incidence"])
            pairs.append({"source": s["name"], "tail": "ring wing", "f": f, "g": g,
                          "sidewash": float(w @ s["lift_dir"])})
    return out, {"pairs": pairs}
