r"""Body and fin lift of a vehicle, and its control surfaces, about the reference point.

The formulas are in :mod:`stripcoef.hull.lift` (Hoerner & Borst 1985; Helmbold 1942; Whicker & Fehlner
1958; Prestero 2001, secs. 3.6-3.7); this module walks the vehicle's hull, fin appendages
and control surfaces and sums them:

.. math:: L = L_{body} + \sum_{fins} \tfrac12\rho S_f c_{L\alpha,f} K_f\, c_f a_f^T,
          \qquad b_s = \sum_{panels\ of\ s} \tfrac12\rho S_p c_{L\alpha,p}\, c_p\, \sigma_s

with :math:`c = [e;\ r\times e]` at the panel's quarter chord (:math:`a_f` the same at its
three-quarter chord, where the rotation's incidence is taken), :math:`K_f` the fin-hull
interference factor (Pitts, Nielsen & Kaattari 1957) of a fin on a cylindrical stretch of a
round hull (1 elsewhere) and :math:`\sigma_s` the sign
of the deflection convention (Prestero 2001: a positive rudder gives +Y, a positive
elevator gives -Z).

A fin's Munk moment is counted once, in its lift (:func:`munk_lift_matrix`): the lift at the
quarter chord is the fin's whole potential-flow force and moment, and C_A(nu) of the model's
M_A (Fossen 2011, eq. 3.46) would add the fins' share of the Munk moment a second time, so
:func:`fin_munk_compensation` takes it off (given the model's M_A and how it was computed):

.. math:: \Delta L = -L_{Munk}(M_A - M_A^{without\ lifting\ fins}),

kept beside L as the model's ``fin_munk_lift`` (:mod:`stripcoef.assembly.fin_munk`), counted
with C_A's Munk moment and dropped with it.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from stripcoef.conventions import skew
from stripcoef.errors import InputError, ModelWarning
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
    munk_factor,
    wing_body_factors,
    boundary_layer_pressure_ratio,
    boundary_layer_thickness,
    axial_velocity_ratio,
    power_law_exponent,
    ring_wing_lift_matrix,
    ring_wing_lift_slope,
    rotary_incidence_point,
    surface_speed_ratio,
    turbulent_boundary_layer,
    TRANSITION_REYNOLDS,
)
from stripcoef.hull.axisymmetric import axial_surface_speed, smooth_radius
from stripcoef.hull.separation import PEAK_SEARCH, stratford_separation
from stripcoef.model import ControlSurface

#: Stations sampling the hull for the slender-body lift (assumption: on the SUBOFF hull's
#: tabulated profile the matrix changes by 0.7 % between 2001 and 8001 stations, because the
#: steepest-closing station of a piecewise-linear profile moves with the sampling) [-].
SLENDER_STATIONS = 2001

#: Fractions of a fin's span (root to tip) at which the body's axial potential flow is averaged
#: for its dynamic pressure under the slender-body rule (midpoint rule, 8 strips; assumption:
#: on SUBOFF's stern planes 8 and 64 strips differ by < 0.1 %) [-].
STREAM_SPAN_POINTS = tuple((i + 0.5) / 8 for i in range(8))

#: Force direction of a positive deflection (Prestero 2001, sec. 3.7: Y_uudr > 0, Z_uuds < 0).
DEFLECTION_FORCE = {"rudder": np.array([0.0, 1.0, 0.0]), "elevator": np.array([0.0, 0.0, -1.0])}


def _panel_terms(panel: SurfacePanel, ref, rho: float, round_hull: bool, slender=None):
    """(L (6, 6), k c (6,), info) of one panel at its quarter chord (module docstring).

    Default: L = 1/2 rho S c_La K c a^T [kg/m, kg, kg m]
    (:func:`~stripcoef.hull.lift.fin_lift_matrix`; a the incidence column at the three-quarter
    chord, :func:`~stripcoef.hull.lift.rotary_incidence_point`: the rotation's incidence), with K the fin-hull interference factor
    (1 + R/s)^2 of a panel on a cylindrical stretch of a round hull and 1 elsewhere
    (:func:`~stripcoef.hull.lift.interference_factor`); k c = 1/2 rho S c_La c, the force per
    u^2 per rad of deflection [kg/m, kg] (Prestero 2001, sec. 3.7).

    ``slender`` (the slender-body rule, ``body_lift: auto`` or ``slender``; a dict with the nose x, the separation station x_0,
    the hull axis, speed and viscosity): the slender-body factors of Pitts, Nielsen & Kaattari
    (1957) at tau = R/s of the root's mid chord on any round hull
    (:func:`~stripcoef.hull.lift.wing_body_factors`), the fin's own force at its quarter chord
    and the carry-over on the hull axis at the same station,

        L = q_r k (F_W c_f + F_B c_b) a_f^T,   b = q_r k (k_W(B) c_f + k_B(W) c_b),

    F_W, F_B = K_W(B), K_B(W) for a fin ahead of x_0 (the body's potential upwash) and
    k_W(B), k_B(W) behind it (the body's cross-flow separated there gives no upwash: the
    premise of Hopkins's x_0), q_r the fin's mean dynamic pressure in the hull's turbulent
    boundary layer at the root's mid chord (:func:`~stripcoef.hull.lift.boundary_layer_pressure_ratio`
    with the thickness and power-law profile of Head's layer, :func:`_hull_boundary_layer`)
    times the body's axial potential flow
    (u/U)^2 averaged over the span (:func:`~stripcoef.hull.lift.axial_velocity_ratio`). The
    same ratio scales the fin's sideslip lift: its incidence is taken as v/U (assumption: a
    cross-flow slowed in proportion with the axial flow; with the cross-flow at its free-stream
    value the incidence would be v/u_local and the sideslip force would take the square root
    of the axial-flow ratio instead of the ratio, 8 % more on SUBOFF's stern planes, where
    Roddy's plane lifts 13 % less in drift than deflected).
    """
    ar = float(effective_aspect_ratio(panel.span, panel.area))
    cla = float(fin_lift_slope(ar))
    point = np.asarray(panel.center, float) + np.array([0.25 * panel.chord, 0.0, 0.0]) \
        - np.asarray(ref, float)
    e = np.zeros(3)
    e["xyz".index(panel.normal)] = 1.0
    turning = rotary_incidence_point(point, panel.chord)    # the rotation's incidence at 3c/4
    if slender is None:
        on_cylinder = round_hull and cylindrical_root(panel.root_radii)
        factor = interference_factor(panel.root, panel.root + panel.span) if on_cylinder else 1.0
        column = 0.5 * rho * panel.area * cla * lift_column(e, point)
        return (fin_lift_matrix(panel.area, cla * factor, e, point, rho=rho,
                                incidence_point=turning), column,
                {"aspect_ratio": ar, "lift_slope": cla, "area": panel.area,
                 "interference": factor})
    tau = panel.root / (panel.root + panel.span) if round_hull else 0.0
    f = wing_body_factors(tau) if tau > 0.0 else {"K_WB": 1.0, "K_BW": 0.0, "k_WB": 1.0,
                                                   "k_BW": 0.0}
    x_q = float(panel.center[0]) + 0.25 * panel.chord
    upwash = x_q >= slender["x_separation"]
    fw, fb = (f["K_WB"], f["K_BW"]) if upwash else (f["k_WB"], f["k_BW"])
    delta, profile, method = _hull_boundary_layer(slender, slender["x_nose"]
                                                  - float(panel.center[0]))
    stream = float(np.mean([axial_velocity_ratio(slender["s"], slender["area"],
                                                 slender["x_nose"] - float(panel.center[0]),
                                                 panel.root + t * panel.span) ** 2
                            for t in STREAM_SPAN_POINTS]))
    q_ratio = boundary_layer_pressure_ratio(panel.span, delta, profile) * stream
    k = 0.5 * rho * panel.area * cla * q_ratio
    c_f = lift_column(e, point)
    c_b = lift_column(e, np.array([x_q, slender["y"], slender["z"]]) - np.asarray(ref, float))
    return (k * np.outer(fw * c_f + fb * c_b, lift_column(e, turning)),
            k * (f["k_WB"] * c_f + f["k_BW"] * c_b),
            {"aspect_ratio": ar, "lift_slope": cla, "area": panel.area,
             "interference": fw + fb, "tau": tau, "body_upwash": upwash,
             "boundary_layer": delta, "boundary_layer_profile": profile,
             "boundary_layer_method": method, "stream_ratio": stream,
             "pressure_ratio": q_ratio, **f})


def _hull_boundary_layer(slender: dict, run: float):
    """(delta [m], power-law exponent p [-], method) of the hull's boundary layer at ``run`` [m]
    from the nose: Head's method on the hull in axial flow (``slender["layer"]``,
    :func:`~stripcoef.hull.lift.turbulent_boundary_layer`; delta = theta (H1 + H), p = (H - 1)/2)
    where it was integrated; ahead of transition, or on a hull shorter than the laminar run
    (``layer`` None), none (0, 1/7: the thin laminar layer is neglected); behind its last station (a
    separated or closing tail) the flat plate's 1/7-power layer
    (:func:`~stripcoef.hull.lift.boundary_layer_thickness`)."""
    layer = slender["layer"]
    if layer is None or run < layer["s"][0]:     # laminar there (or along the whole hull)
        return 0.0, 1.0 / 7.0, "laminar"
    s = layer["s"]
    if run > s[-1]:
        return (boundary_layer_thickness(run, slender["speed"], slender["viscosity"]),
                1.0 / 7.0, "flat plate")
    h = float(np.interp(run, s, layer["H"]))
    return float(np.interp(run, s, layer["delta"])), power_law_exponent(h), "Head"


def munk_lift_matrix(mass_matrix, *, surge: bool = True) -> np.ndarray:
    r"""The Munk moment of an added mass written as a lift matrix (force :math:`-uL\nu`).

    The moments of :math:`-C_A(\nu)\nu` from the added mass's linear momentum
    :math:`a = M_{11}\nu_1 + M_{12}\nu_2` (C_A's lower-left block, Fossen 2011 eq. 3.46; what
    ``HydroModel.coriolis(munk=False)`` drops) are :math:`a \times \nu_1`, e.g.
    :math:`N = -(m_{22} - m_{11})uv - m_{26}ur`: the Munk moment (Newman 1977, ch. 4). At
    forward speed u they are :math:`-uL_M\nu` to first order in the cross velocities, with

    .. math:: L_M = \begin{bmatrix} 0 & 0 \\ S(e_1)M_{11} - S(M_{11}e_1) & S(e_1)M_{12}
              \end{bmatrix},\qquad L_M[3{:}6, 0] = S(e_1)M_{11}e_1

    (S the cross-product matrix; the surge column exact at pure surge, zero for a body with
    a mirror plane y = 0 or z = 0). Terms of second order in the cross velocities (the roll
    moment :math:`(m_{33} - m_{22})vw`) are not of this form. ``surge=False`` keeps only the
    moment of the linear momentum carried at the surge speed, :math:`u\,e_1 \times a`
    (:math:`L_M = [0;\ S(e_1)M_{11},\ S(e_1)M_{12}]`: the :math:`m_{22}` of
    :math:`(m_{22} - m_{11})`), leaving out that of the surge added mass carried at the cross
    velocities (:math:`-S(M_{11}e_1)`, the :math:`m_{11}`); a is the same about every point, so
    that part is a couple, the same about every reference point.

    Parameters
    ----------
    mass_matrix : (6, 6)
        Symmetric added mass about the reference point [kg, kg m, kg m^2]
    surge : bool
        With the surge added mass's part (the whole Munk moment)

    Returns
    -------
    (6, 6) array
        L_M [kg, kg m] in the moment rows (zero force rows)

    References
    ----------
    Fossen, T. I. (2011), *Handbook of Marine Craft Hydrodynamics and Motion Control*,
    Theorem 3.2 (eq. 3.46) and eq. 6.43; Newman, J. N. (1977), *Marine Hydrodynamics*, ch. 4
    (the moment :math:`(m_{11} - m_{22})U^2\sin\alpha\cos\alpha` of a body in steady
    translation).
    """
    m = np.asarray(mass_matrix, dtype=float)
    e1 = np.array([1.0, 0.0, 0.0])
    a0 = m[:3, :3] @ e1
    out = np.zeros((6, 6))
    out[3:, :3] = skew(e1) @ m[:3, :3] - (skew(a0) if surge else 0.0)
    out[3:, 0] = skew(e1) @ a0
    out[3:, 3:] = skew(e1) @ m[:3, 3:]
    return out


def lifting_fins(vehicle) -> dict:
    """The fin appendages whose lift the model carries, by the axis their lift is along:
    {"y": names of the fins spanning z, "z": names of those spanning y}. Those of the control
    surfaces and the other fins with a panel outside the hull (:func:`vehicle_lift`; a fin on
    another appendage has none)."""
    out: dict = {}
    if vehicle.hull is None:
        return out
    in_surface = {n for s in vehicle.control_surfaces for n in s.fins}
    for b in vehicle.bodies:
        if not isinstance(b, Fin):
            continue
        if b.name not in in_surface:
            try:
                exposed_panels(vehicle.hull, b.center, b.span, b.chord, b.span_axis,
                               path=f"appendages[{b.name}]")
            except InputError:
                continue
        out.setdefault("y" if b.span_axis == "z" else "z", []).append(b.name)
    return out


#: Entries of the fins' share of M_A below this fraction of M_A's largest are round-off of the
#: difference (set to zero, as :func:`stripcoef.conventions.clean_roundoff`) [-].
ROUNDOFF = 1e-12

#: The moment row of the lift matrix that a fin's lift along each axis makes (yaw for a
#: sway force, pitch for a heave force) [-].
_MOMENT_ROW = {"y": 5, "z": 4}


def fin_munk_compensation(added_mass, added_mass_of, vehicle,
                          fins: dict | None = None) -> tuple[np.ndarray, dict]:
    r"""The lift matrix that takes the lifting fins' Munk moment off C_A: each fin's Munk
    moment counted once, in its lift.

    .. math:: \Delta L_{k,:} = -L_M(M_A - M_A^{-})_{k,:},\qquad k = 5\ \text{if a fin
              lifts along y},\quad k = 4\ \text{if one lifts along z},

    :math:`L_M` of :func:`munk_lift_matrix` without the surge added mass's part
    (``surge=False``), :math:`M_A^{-}` the added mass of the vehicle without its lifting fins
    (:func:`lifting_fins`) by the same method about the same point: the difference is their
    share, their interference with the hull included; the moment row k is the one a lift
    along y (spanning z: rudders, a sail) or z makes (the yaw moment of the sway force), so a
    fin's added mass along its span (the sail's in heave), which makes no lift, keeps its
    Munk moment where no other fin lifts that way. [assumption] In a cruciform the fins
    lifting along y take the whole share in sway, the other pair's edgewise part with it
    (second order in its thickness: 0.45 of 14.8 kg on SUBOFF's NACA 0020 planes, by removing
    one pair at a time, which costs a 3D fin solve per pair: about 2 s of CPU on REMUS). The
    fins' surge added mass (:math:`m_{11}` of :math:`(m_{22} - m_{11})`, second order in
    their thickness, zero for the plate below) keeps its part in C_A: so :math:`\Delta L` is
    a couple, the same whichever reference point the model is estimated about.

    Why: a lifting surface's lift at its aerodynamic centre (the quarter chord,
    :func:`_panel_terms`) is its whole potential-flow force and moment, the Munk moment
    included. For the flat plate of thin-airfoil theory, c_l = 2 pi alpha at the quarter
    chord, the moment about the mid chord is

    .. math:: L'\frac c4 = \pi\rho U^2 \frac{c^2}{4}\alpha = (m_{22} - m_{11})\,U^2\alpha,
              \qquad m_{22} = \rho\pi(c/2)^2,\ m_{11} = 0,

    exactly the plate's Munk moment: in Theodorsen's (1935) solution the apparent-mass
    (non-circulatory) terms hold no term in :math:`U^2\alpha`, which is all in the circulatory
    lift at the quarter chord. C_A(nu) of M_A (Fossen 2011, eq. 3.46), which holds the fins'
    added mass, adds that moment again, with the fins' whole share of M_A (their
    finned-circle sections with the hull's interference,
    :func:`stripcoef.assembly.added_mass.fin_share_corrections`): several times the lift's own
    quarter-chord moment on a low-aspect-ratio fin (6.7 times on SUBOFF's stern planes, whose
    centre of pressure the double count put 1.7 chords ahead of their quarter chord,
    docs/validation.md). Keeping the
    lift and taking the fins' Munk part off C_A (not the reverse) keeps the fin's centre of
    pressure where the lift puts it and leaves M_A whole for the accelerations; it is kept as
    the model's ``fin_munk_lift``, beside L (:mod:`stripcoef.assembly.fin_munk`): every
    consumer of M_A with its Munk moment (simulate, limits, the exports, whose simulators build
    C_A from M_A) counts it once, with L, and drops it with the Munk moment. The body's own Munk moment stays in C_A
    (the body lift is the potential force behind the separation station taken from it,
    :func:`_body_lift`).

    Not modelled (assumption): the quasi-steady rotation's moment about the quarter chord
    beyond the 3/4-chord incidence (Theodorsen's :math:`-\pi\rho b^3 U\dot\alpha/2`, the
    camber moment of the curved cross-flow, :math:`-k(c/4)^2 q` for a lift k per unit
    incidence velocity), of the order :math:`(c/4x)^2` of a fin's rotary moment at the lever
    arm x (1e-3 on SUBOFF's stern planes).

    Parameters
    ----------
    added_mass : (6, 6)
        The model's M_A about the reference point [kg, kg m, kg m^2]
    added_mass_of : callable
        ``f(vehicle) -> (6, 6)``: M_A of a vehicle by the same method, options, point,
        volume and centre
    vehicle : Vehicle
    fins : dict, optional
        Its lifting fins (:func:`lifting_fins`, computed when not given)

    Returns
    -------
    (6, 6) array, dict
        :math:`\Delta L` [kg/m, kg, kg m] and a summary (per axis the fins and their share's
        added mass along it [kg]); zeros and {} without lifting fins

    References
    ----------
    Theodorsen, T. (1935), NACA Report 496 (the circulatory and apparent-mass parts of the
    thin aerofoil's force and moment); Katz, J. & Plotkin, A. (2001), *Low-Speed
    Aerodynamics*, 2nd ed., sec. 5.3 (the flat plate's c_m about the quarter chord is 0);
    Newman 1977, ch. 4 (the Munk moment; table 4.2, the plate's added mass); Fossen 2011,
    eq. 3.46.
    """
    out = np.zeros((6, 6))
    fins = lifting_fins(vehicle) if fins is None else fins
    if not fins:
        return out, {}
    names = {n for group in fins.values() for n in group}
    m_a = np.asarray(added_mass, dtype=float)
    without = dataclasses.replace(vehicle, control_surfaces=[],
                                  bodies=[b for b in vehicle.bodies if b.name not in names])
    share = m_a - np.asarray(added_mass_of(without), dtype=float)
    share[np.abs(share) < ROUNDOFF * np.abs(m_a).max()] = 0.0   # the difference's round-off
    lm = munk_lift_matrix(share, surge=False)
    info: dict = {}
    for axis, group in fins.items():
        out[_MOMENT_ROW[axis]] = -lm[_MOMENT_ROW[axis]]
        i = " yz".index(axis)
        info[axis] = {"fins": list(group), "added_mass": float(share[i, i])}
    return out, info


def vehicle_lift(vehicle, rho: float, ref, *, center=None, speed: float | None = None,
                 viscosity: float | None = None) -> tuple[np.ndarray, tuple, dict]:
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
    speed, viscosity : float, optional
        Reference speed [m/s] and kinematic viscosity [m^2/s] of the fins' boundary-layer
        reduction under the slender-body rule (default: the vehicle's reference speed and
        fluid)

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
    body = _body_lift(vehicle, rho, ref, ref if center is None else center, speed=speed,
                      viscosity=viscosity)
    slender = _stern_flow(vehicle, body, speed, viscosity)
    fins = [b for b in vehicle.bodies if isinstance(b, Fin) and b.name not in in_surface]
    lifting = lifting_fins(vehicle)        # the one rule of which fins lift
    lifts = {n for group in lifting.values() for n in group}
    fin_info = []
    no_lift = []
    for fin in fins:
        if fin.name not in lifts:
            no_lift.append(fin.name)     # on another appendage, not on the hull
            continue
        for p in exposed_panels(hull, fin.center, fin.span, fin.chord, fin.span_axis,
                                path=f"appendages[{fin.name}]"):
            m, _, pinfo = _panel_terms(p, ref, rho, round_, slender)
            lift += m
            fin_info.append({"name": fin.name, **pinfo})
    surfaces = []
    for s in vehicle.control_surfaces:
        b = np.zeros(6)
        for p in s.panels:
            m, column, pinfo = _panel_terms(p, ref, rho, round_, slender)
            lift += m
            b += column * float(DEFLECTION_FORCE[s.kind] @ column[:3] / abs(column[:3]).max())
            fin_info.append({"name": s.name, **pinfo})
        surfaces.append(ControlSurface(name=s.name, kind=s.kind, derivative=b,
                                       max_deflection=s.max_deflection,
                                       stall_angle=s.stall_angle))
    if body is not None:
        lift += body[0]
        info["body_lift"] = body[1]
    if fin_info:
        info["fin_lift"] = fin_info
    if no_lift:
        info["fins_without_lift"] = no_lift
    return lift, tuple(surfaces), info


def _stern_flow(vehicle, body, speed, viscosity):
    """The hull's flow that the fins (and a ring wing) sit in under the slender-body rule
    (``body_lift: auto`` or ``slender``): a dict with the nose x, Hopkins's separation station,
    the sections (s from the nose, S), the hull axis, speed, viscosity and Head's boundary
    layer (:func:`_hull_boundary_layer`); None under Hoerner's rule (``on``) or without body
    lift (the fins then see the free stream)."""
    if body is None or body[1].get("method") not in STERN_FLOW_RULES:
        return None
    hull = vehicle.hull
    slender = {"x_nose": hull.x_extent()[1], "x_separation": body[1]["separation_x"],
               "s": body[2][0], "area": body[2][1],
               "y": hull.y, "z": hull.z,
               "speed": float(vehicle.reference_speed if speed is None else speed),
               "viscosity": float(vehicle.fluid.kinematic_viscosity if viscosity is None
                                  else viscosity)}
    s_nose, area = slender["s"], slender["area"]
    try:
        rule = body[1]["method"]
        slender["layer"] = turbulent_boundary_layer(
            s_nose, _layer_radius(rule, s_nose, area, hull),
            _surface_speed(rule, s_nose, area, hull),
            speed=slender["speed"], viscosity=slender["viscosity"])
    except ValueError:        # the hull is shorter than the laminar run: no turbulent layer
        slender["layer"] = None
    return slender


#: Body-lift rules under which the fins (and a ring wing) sit in the hull's stern flow.
STERN_FLOW_RULES = ("slender", "datcom", "stratford", "stratford_panel")


def _surface_speed(rule: str, s, area, hull) -> np.ndarray:
    """U_e/U [-] along the (round) ``hull`` in axial potential flow at stations ``s`` [m] from
    the nose with sections ``area`` [m^2], as body-lift ``rule`` computes it: the axisymmetric
    panel solution under ``stratford_panel``, on the smooth body through the hull's offsets
    (:func:`_hull_offsets`; :func:`~stripcoef.hull.axisymmetric.axial_surface_speed`, Hess &
    Smith 1967), the line sources of slender-body theory on the sections otherwise
    (:func:`~stripcoef.hull.lift.surface_speed_ratio`)."""
    if rule == "stratford_panel":
        return axial_surface_speed(*_hull_offsets(hull), at=s)
    return surface_speed_ratio(s, area)


def _hull_offsets(hull) -> tuple[np.ndarray, np.ndarray]:
    """A round hull's offsets from the nose: s [m] from the nose, non-decreasing, and r [m]
    (:meth:`~stripcoef.geometry.profiles.Profile.offsets`: a table's own points, an analytic
    segment's exact values)."""
    x, r = hull.half_breadth.offsets()
    return hull.x_extent()[1] - x[::-1], r[::-1]


def _layer_radius(rule: str, s, area, hull) -> np.ndarray:
    """r [m] of the hull at stations ``s`` [m] from the nose that Head's layer is computed on
    under body-lift ``rule``: the smooth interpolant of the offsets the panel solution sees
    under ``stratford_panel`` (:func:`~stripcoef.hull.axisymmetric.smooth_radius`), the
    sections' sqrt(S/pi) otherwise."""
    if rule == "stratford_panel":
        return smooth_radius(*_hull_offsets(hull), s)
    return np.sqrt(area / np.pi)


def ring_wing_lift(vehicle, rho: float, ref, *, x_le: float, x_te: float, r_le: float,
                   r_te: float, speed: float | None = None,
                   viscosity: float | None = None,
                   wake: bool = False) -> tuple[np.ndarray, dict]:
    r"""Lift matrix of a ring wing around the vehicle's hull (force :math:`-uL\nu`) and a summary.

    The ring's chord line runs from (x_le, r_le) to (x_te, r_te) (body axes, x forward [m];
    radii from the hull axis [m]); it lifts as an isolated ring of its mean radius
    R = (r_le + r_te)/2 and chord c = |(x_le - x_te, r_le - r_te)|
    (:func:`~stripcoef.hull.lift.ring_wing_lift_matrix`; Weissinger's lift slope,
    :func:`~stripcoef.hull.lift.ring_wing_lift_slope`) at its quarter chord, with

    - **the hull inside it**, attached flow: in the wake far behind the ring (Trefftz plane)
      the fluid inside the ring's vortex cylinder moves with the ring and the hull that closes
      inside it leaves no impulse of its own, so the pair lifts as the isolated ring
      (slender-body theory, Newman 1977 sec. 7.8; Pitts, Nielsen & Kaattari 1957): interference
      factor 1. The body's upwash ahead of the separation station is left out (assumption,
      ``info["body_upwash"]``). The struts inside the ring add nothing (the same section);
    - **the hull's separated wake** (``wake``, an option, not the default; the slender-body rules
      only): behind the body rule's separation station x_0 the body's potential lift stops,
      i.e. the rule
      carries the section's cross-flow impulse rho S(x_0) w(x_0) into the wake unchanged
      (Hopkins 1951; USAF DATCOM sec. 4.2.1.1): that wake moves with the body's cross-velocity
      at x_0, w_0 = v + x_0 r. A ring behind x_0 and inside the wake's section
      (pi R^2 <= S(x_0)) turns only the cross-flow relative to it, w - w_0: no force in
      drift or heave (w = w_0), a force (x_r - x_0) r in yaw rotation (pitch alike). The
      fraction f = min(1, S(x_0)/(pi R^2)) of w_0 is taken off (``wake_fraction`` of
      :func:`~stripcoef.hull.lift.ring_wing_lift_matrix`): 1 inside the wake, tending to the
      undisturbed ring (0) for a ring much wider than the wake; between the two the
      interpolation is an assumption. ``wake=False`` is the ring in the undisturbed cross-flow
      (the model before issue 34's ring pass);
    - **the stern flow** (the slender-body rule only, as for the fins): the dynamic pressure
      of the hull's boundary layer at the ring's mid chord, :math:`(y/\delta)^{2p}` at the
      ring's height y = R - r_hull above the surface (Head's layer, :func:`_hull_boundary_layer`;
      1 above the layer), times the body's axial potential flow :math:`(u/U)^2` there
      (:func:`~stripcoef.hull.lift.axial_velocity_ratio`);
    - not modelled: the sidewash of the stern planes' and the body's trailing vortices at the
      ring (the ring sits inside the planes' span behind their trailing edge), the ring's
      added mass, and the ring's own effect on the planes.

    Parameters
    ----------
    vehicle : Vehicle
        With a round hull (``hull.profile``)
    rho : float
        Fluid density [kg/m^3]
    ref : (3,)
        Reference point [m]
    x_le, x_te, r_le, r_te : float
        The chord line's ends [m], x_le > x_te, radii > 0
    speed, viscosity : float, optional
        As :func:`vehicle_lift`
    wake : bool
        The ring answers the cross-flow relative to the hull's separated wake (above)

    Returns
    -------
    L : (6, 6) [kg/m, kg, kg m]
    info : dict
        radius, chord, aspect ratio, lift slope, pressure ratio and its parts, the wake
        fraction f and the separation station's radius

    References
    ----------
    :func:`~stripcoef.hull.lift.ring_wing_lift_slope`; Pitts, Nielsen & Kaattari (1957), NACA
    Report 1307 (slender-body interference from the cross-section's apparent mass); Newman
    1977, sec. 7.8; Hoerner & Borst 1985, ch. 8 (tails in the stern's reduced dynamic pressure).
    """
    hull = vehicle.hull
    if hull is None or not _round(hull):
        raise InputError("a ring wing needs a round hull", file=vehicle.source, key="hull",
                         value="none or not round", expected="a hull 'profile' (circular)")
    lo, hi = hull.x_extent()
    if not hi >= x_le > x_te >= lo or min(r_le, r_te) <= 0.0:
        raise InputError("ring wing outside the hull's length", file=vehicle.source,
                         key="ring_wing", value=f"x = {x_te:.4g}..{x_le:.4g} m, "
                         f"r = {r_le:.4g}, {r_te:.4g} m",
                         expected=f"x_le > x_te within {lo:.4g}..{hi:.4g} m, radii > 0")
    radius = 0.5 * (r_le + r_te)
    chord = float(np.hypot(x_le - x_te, r_le - r_te))
    x_mid = 0.5 * (x_le + x_te)
    r_hull = float(hull.half_breadth(np.array([x_mid]))[0]) if lo <= x_mid <= hi else 0.0
    if radius <= r_hull:
        raise InputError("ring wing inside the hull", file=vehicle.source, key="ring_wing",
                         value=f"R = {radius:.4g} m at x = {x_mid:.4g} m",
                         expected=f"a mean radius above the hull's {r_hull:.4g} m")
    body = _body_lift(vehicle, rho, ref, ref, speed=speed, viscosity=viscosity)
    slender = _stern_flow(vehicle, body, speed, viscosity)
    info = {"radius": radius, "chord": chord, "aspect_ratio": 2.0 * radius / chord,
            "lift_slope": float(ring_wing_lift_slope(2.0 * radius / chord)),
            "x_quarter_chord": x_le - 0.25 * (x_le - x_te), "height": radius - r_hull}
    q_ratio, wake_fraction, wake_point = 1.0, 0.0, None
    if slender is not None:
        delta, profile, method = _hull_boundary_layer(slender, slender["x_nose"] - x_mid)
        height = radius - r_hull
        layer = (height / delta) ** (2.0 * profile) if 0.0 < height < delta else 1.0
        stream = axial_velocity_ratio(slender["s"], slender["area"], slender["x_nose"] - x_mid,
                                      radius) ** 2
        q_ratio = layer * stream
        info.update({"boundary_layer": delta, "boundary_layer_profile": profile,
                     "boundary_layer_method": method, "layer_ratio": layer,
                     "stream_ratio": stream,
                     "body_upwash": info["x_quarter_chord"] >= slender["x_separation"]})
        x_0 = slender["x_separation"]
        s_0 = float(np.interp(slender["x_nose"] - x_0, slender["s"], slender["area"]))
        info["separation_radius"] = math.sqrt(max(s_0, 0.0) / math.pi)
        if wake and info["x_quarter_chord"] < x_0:
            wake_fraction = min(1.0, s_0 / (math.pi * radius ** 2))
            wake_point = np.array([x_0, hull.y, hull.z]) - np.asarray(ref, float)
    info["pressure_ratio"] = q_ratio
    info["wake_fraction"] = wake_fraction
    point = np.array([info["x_quarter_chord"], hull.y, hull.z]) - np.asarray(ref, float)
    return ring_wing_lift_matrix(radius, chord, point, rho=rho, pressure_ratio=q_ratio,
                                 wake_point=wake_point, wake_fraction=wake_fraction), info


def _round(hull) -> bool:
    """A hull of circular sections (one radius profile): where body lift and the fin-hull
    interference of slender-body theory apply."""
    return hull.half_breadth is hull.half_height and shape_geometry(hull.section).elliptic


def _body_lift(vehicle, rho: float, ref, center, *, speed: float | None = None,
               viscosity: float | None = None):
    """Body lift of a slender hull of revolution.

    Three rules: the slender-body lift ahead of Hopkins's separation station (Hopkins 1951, NACA
    RM A51C14; USAF DATCOM sec. 4.2.1.1; :func:`~stripcoef.hull.lift.slender_body_lift_matrix`:
    it answers the local cross-flow, so a yaw or pitch rate gives rotary terms), with the fins
    in the hull's stern flow (:func:`_stern_flow`), or Hoerner's point force at 0.65 l
    answering the sideslip at the centre of buoyancy (Hoerner & Borst 1985, ch. 19; Prestero
    2001 sec. 3.6.1) with isolated fins in the free stream. ``body_lift: auto`` (default)
    takes the DATCOM rule when the vehicle has fins or control surfaces and a circular hull
    with l/d >= :data:`MIN_SLENDERNESS`, and no body lift otherwise: the slender-body rule with
    the potential lift times Munk's factor k2 - k1 of the body's fineness, the USAF DATCOM's
    body method as published (sec. 4.2.1.1, :func:`~stripcoef.hull.lift.munk_factor`; the fins
    as under ``slender``). The factor also keeps the lift consistent with C_A: L is the
    potential force of the stretch behind x_0 taken from the whole body's, whose Munk moment
    C_A(nu) nu holds with the finite body's added mass (about k2 - k1 times the slender
    sections'), not the slender sections'. ``datcom`` asks for that rule, ``slender`` for the
    slender-body rule without the factor and ``on`` for Hoerner's (a hull that is not slender
    and round is then an error); ``off`` leaves body lift out. ``stratford`` is the DATCOM rule
    with the separation station from the hull's own boundary layer instead of Hopkins's
    correlation: where Stratford's turbulent separation criterion (Stratford 1959) is met in
    the pressure recovery of the hull's axial potential flow (line sources,
    :func:`~stripcoef.hull.lift.surface_speed_ratio`) at the reference speed (or ``speed``,
    ``viscosity``), the layer turbulent from Re_x = :data:`~stripcoef.hull.lift.TRANSITION_REYNOLDS`
    (:func:`~stripcoef.hull.separation.stratford_separation`); no separation ahead of the tail
    cap puts the station at the tail (no potential lift left but the base's; a ModelWarning
    says so). ``stratford_panel`` is the
    same criterion on the exact axisymmetric potential flow of the hull (the surge mode of the
    panel method, :func:`~stripcoef.hull.axisymmetric.axial_surface_speed`; Hess & Smith
    1967) instead of the line sources, for the station and for the fins' stern flow (Head's
    layer) alike: Stratford's criterion is stated on the body's actual pressure distribution,
    whose suction peak at the afterbody's shoulder the line sources underestimate (SUBOFF: 1.07
    against 1.12). An option, measured in docs/validation.md. ``auto`` follows the DATCOM
    rule because on the measured SUBOFF captive-model data (Roddy 1990, Table 4 and Appendix
    B) it is the best of the three (docs/validation.md, 'Every configuration and
    derivative'; ``python -m benchmarks.lift_band --method datcom``). Returns
    (L [kg/m, kg, kg m], info) or None; under the slender-body rules also (s from the nose [m],
    S(s) [m^2]), the sections the fins' stern flow is computed from.
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
        if mode in ("on", *STERN_FLOW_RULES):
            raise InputError("body lift needs a slender round hull", file=vehicle.source,
                             key="body_lift", value=f"l/d = {length / d:.3g}",
                             expected=f"a hull 'profile' (circular) with l/d >= {MIN_SLENDERNESS:g}")
        return None
    if mode in ("auto", *STERN_FLOW_RULES):
        xs = np.linspace(lo, hi, SLENDER_STATIONS)
        area = np.pi * hull.half_breadth(xs) * hull.half_height(xs)
        info = {"method": {"auto": "datcom"}.get(mode, mode), "length": length, "diameter": d}
        if mode in ("stratford", "stratford_panel"):
            s_nose, a_nose = hi - xs[::-1], area[::-1]
            u = float(vehicle.reference_speed if speed is None else speed)
            nu = float(vehicle.fluid.kinematic_viscosity if viscosity is None else viscosity)
            sep = stratford_separation(s_nose, _surface_speed(mode, s_nose, a_nose, hull), speed=u,
                                       viscosity=nu, transition=TRANSITION_REYNOLDS * nu / u)
            x0 = lo if sep["separation"] is None else hi - sep["separation"]
            info["stratford"] = sep
            if sep["limit"] == "cp":
                warnings.warn(f"body_lift: {mode}: the afterbody's pressure rise reaches "
                              "C_p' = 4/7, the end of Stratford's criterion's range, before the "
                              "criterion is met; the separation station is put at the tail "
                              "(no body lift)", ModelWarning, stacklevel=3)
            elif sep["limit"] == "end":
                # e.g. REMUS 100's truncated Myring tail, Myring tails of 15 deg or less
                # (benchmarks/body_lift_default.py): the body lift all but vanishes, say so
                warnings.warn(f"body_lift: {mode}: Stratford's criterion is not met ahead of "
                              f"{PEAK_SEARCH[1]:g} l at {u:.3g} m/s: the afterbody's layer is "
                              "taken attached to the tail, which keeps only its base's potential "
                              "lift (body_lift: datcom puts Hopkins's station on it)",
                              ModelWarning, stacklevel=3)
        else:
            x0 = separation_station(xs, area)
        info["separation_x"] = x0
        # datcom (and auto, since issue 34; stratford): the same potential lift times Munk's
        # k2 - k1 (USAF DATCOM sec. 4.2.1.1)
        datcom = mode != "slender"
        factor = munk_factor(length, d) if datcom else 1.0
        if datcom:
            info["munk_factor"] = factor
        return (factor * slender_body_lift_matrix(xs, area, x0, rho=rho, y=hull.y, z=hull.z,
                                                  ref=ref),
                info, (hi - xs[::-1], area[::-1]))
    x_cp = hi - BODY_CP_FRACTION * length
    cp = np.array([x_cp, hull.y, hull.z]) - np.asarray(ref, float)
    return (body_lift_matrix(length, d, cp, rho=rho,
                             velocity_point=np.asarray(center, float) - np.asarray(ref, float)),
            {"length": length, "diameter": d, "center_of_pressure_x": x_cp})
