r"""Lift: the speed-dependent linear forces of a slender body and its fins.

A vehicle moving at surge speed u with a small sideslip :math:`\beta \approx v/u` or angle
of attack :math:`\alpha \approx w/u` gets a force normal to its path that grows as
:math:`u^2 \beta = u v`: the body's viscous cross-flow lift and the fins' lift.  Both are
collected in one 6x6 matrix L about the model's reference point,

.. math:: \tau_{lift} = -u\,L\,\nu, \qquad -L_{ij} = \{Y_{uv}, Y_{ur}, Z_{uw}, Z_{uq},
          M_{uw}, M_{uq}, N_{uv}, N_{ur}, \dots\}

(SNAME names, force per u times velocity [kg/m, kg, kg m]; Prestero 2001, sec. 3.6).  The
potential-flow (Munk) part of these derivatives is *not* here: it is in
:math:`C_A(\nu)\nu` of the added mass (Fossen 2011, eq. 6.43), as in Prestero's split
:math:`Y_{uv} = Y_{uva} + Y_{uvl} + Y_{uvf}`.

Body lift (Hoerner & Borst 1985, "Fluid-Dynamic Lift", ch. 19, as used by Prestero 2001,
sec. 3.6.1):

.. math:: Y_{uvl} = Z_{uwl} = -\tfrac12 \rho d^2 c_{yd\beta}, \quad
          c_{yd\beta} = 0.003\,(l/d)\ [1/\mathrm{deg}], \quad
          x_{cp} = x_{nose} - 0.65\,l

acting at the centre of pressure :math:`x_{cp}` (a sideslip v gives the force; yaw rate does
not, as in Prestero's model).

Fin lift (Helmbold 1942, the low-aspect-ratio lift slope of DATCOM sec. 4.1.3.2 and of Anderson
1999, eq. 2.18; section efficiency a of Whicker & Fehlner 1958 as used by Prestero 2001,
sec. 3.6.2): each fin of planform area S and span b (root at the hull, which acts as a
reflection plane) has the effective aspect ratio :math:`AR_e = 2 b^2 / S` and the lift-curve
slope

.. math:: c_{L\alpha} = \frac{a_0}{\sqrt{1 + (a_0/\pi AR_e)^2} + a_0/\pi AR_e},
          \quad a_0 = 2\pi a,\ a = 0.9

and the force :math:`\tfrac12 \rho u^2 S c_{L\alpha} \alpha_e` normal to its plane, with
:math:`\alpha_e = \delta - v_f/u` the effective angle of attack, :math:`v_f` the cross
velocity at its quarter chord (the rotation's part at its three-quarter chord,
:func:`rotary_incidence_point`).  A fin of lift direction e at r (relative to the reference
point) adds :math:`k\,c\,a^T` to L, :math:`k = \tfrac12\rho S c_{L\alpha}` [kg/m],
:math:`c = [e;\ r \times e]`, :math:`a = [e;\ r_\omega \times e]`, and a control surface deflected by :math:`\delta` gives
:math:`u^2 k\,c\,\delta` (Prestero 2001, sec. 3.7: :math:`Y_{uu\delta_r}`,
:math:`N_{uu\delta_r}`, ...).  The linear law holds up to the stall angle; beyond it the
lift falls (Hoerner & Borst 1985, ch. 4), which this model does not represent: deflections
are limited below stall.

Fin-hull interference (slender-body theory; Pitts, Nielsen & Kaattari 1957, NACA Report 1307):
a fin on a cylindrical stretch of a hull of radius R, tip at distance s from the axis, sees the
hull's cross-flow upwash and carries lift over onto the hull.  The lift of the exposed fin
(the "wing alone" above) is multiplied by

.. math:: K_{W(B)} + K_{B(W)} = (1 + \tau)^2, \qquad \tau = R / s,

which is 1 for a fin on a wall-less body (R = 0) and 4 when the fin vanishes into the hull.
It is applied to the sideslip/incidence lift of fins whose root lies on a cylindrical stretch
(:data:`CYLINDER_TOLERANCE`), the case the theory is derived for; on a tapering afterbody
the theory's assumptions (cylindrical body, thin boundary layer) fail and the isolated fin is
kept (DARPA SUBOFF: the sail on the parallel middle body within 5 % with the factor, the
stern planes on the afterbody within 21 % without it and 2.2 times too high with it;
docs/validation.md).  A deflected control surface's own interference (the smaller
:math:`k_{W(B)} + k_{B(W)}` of the same report) is not modelled: its deflection force uses
the isolated panel.
"""

from __future__ import annotations

import math

import numpy as np

from stripcoef.conventions import skew
from stripcoef.hull.boundary_layer import (  # noqa: F401  (Head's layer, re-exported here)
    FLAT_PLATE_H,
    HEAD_F,
    HEAD_H1_HIGH,
    HEAD_H1_LOW,
    HEAD_SEPARATION_H,
    LUDWIEG_TILLMANN,
    TRANSITION_REYNOLDS,
    _head_h,
    _head_h1,
    turbulent_boundary_layer,
)
from stripcoef.hull.lamb import lamb_k_factors
from stripcoef.hull.memo import array_memo

#: Section efficiency a = a_0 / 2 pi of the fin lift slope, Whicker & Fehlner's value
#: (Prestero 2001, sec. 3.6.2) [-].
FIN_EFFICIENCY = 0.9
#: Hoerner's body lift slope per degree per unit slenderness, c_ydb = 0.003 l/d [1/deg]
#: (Hoerner & Borst 1985, ch. 19; Prestero 2001, sec. 3.6.1) [-].
BODY_LIFT_PER_DEG = 0.003
#: Centre of pressure of the body lift, as a fraction of the length aft of the nose
#: (Hoerner & Borst 1985, ch. 19; Prestero 2001, sec. 3.6.1) [-].
BODY_CP_FRACTION = 0.65
#: Smallest length/diameter for which the slender-body lift above is used (assumption:
#: Hoerner's correlation is for slender bodies; a sphere has no lift by symmetry) [-].
MIN_SLENDERNESS = 4.0
#: Largest relative change of the hull radius along a fin's root chord for which the root
#: counts as cylindrical and the fin-hull interference factor applies, (r_max - r_min)/r_max
#: (assumption: 5 % changes (1 + R/s)^2 by less than 5 %, inside the lift tolerance) [-].
CYLINDER_TOLERANCE = 0.05


def effective_aspect_ratio(span, area):
    r"""Effective aspect ratio of a fin mounted on a hull (the hull is a reflection plane).

    .. math:: AR_e = 2\,b^2 / S

    Parameters
    ----------
    span : float or array
        b, root (hull surface) to tip [m]
    area : float or array
        S, planform area of the fin [m^2]

    Returns
    -------
    float or array
        AR_e [-]

    References
    ----------
    Prestero 2001, sec. 3.6.2 (REMUS: b = 8.57e-2 m, S = 6.65e-3 m^2, AR_e = 2.21);
    Hoerner & Borst 1985, ch. 3 (image of a wing on a wall).
    """
    return 2.0 * np.asarray(span, dtype=float) ** 2 / np.asarray(area, dtype=float)


def fin_lift_slope(aspect_ratio, *, efficiency: float = FIN_EFFICIENCY):
    r"""Lift-curve slope of a low-aspect-ratio fin (Helmbold's equation).

    .. math:: c_{L\alpha} = \frac{a_0}{\sqrt{1 + x^2} + x},\qquad x = \frac{a_0}{\pi AR_e},
              \quad a_0 = 2\pi a

    It has both exact limits: Jones's slender-wing value :math:`\pi AR_e / 2` as
    :math:`AR_e \to 0` and the section's :math:`a_0` as :math:`AR_e \to \infty`.  Prandtl's
    lifting-line form :math:`[1/a_0 + 1/(\pi AR_e)]^{-1}` that Whicker & Fehlner and Prestero
    use tends to :math:`\pi AR_e`, twice Jones's value, and is 11-71 % above measured
    flat-plate slopes at AR 0.57-3.1 (reference_tables/flat_plate_lift, docs/validation.md).

    Parameters
    ----------
    aspect_ratio : float or array
        AR_e, effective aspect ratio [-] (:func:`effective_aspect_ratio`), > 0
    efficiency : float
        a, ratio of the 2D section slope to 2 pi [-] (0.9, Whicker & Fehlner's value)

    Returns
    -------
    float or array
        c_Lalpha [1/rad]

    References
    ----------
    Helmbold, H. B. (1942), Jahrbuch der deutschen Luftfahrtforschung, I 111-113; USAF DATCOM
    (Finck 1978) sec. 4.1.3.2 (the same with a = kappa, incompressible, unswept); Anderson,
    *Aircraft Performance and Design* (1999), eq. 2.18 (low-aspect-ratio straight wing); Jones
    (1946), NACA Report 835 (slender wing, pi AR / 2).  REMUS (Prestero 2001): AR_e = 2.21
    gives 2.687 [1/rad], where Prestero's lifting-line form gives 3.12.
    """
    ar = np.asarray(aspect_ratio, dtype=float)
    a0 = 2.0 * math.pi * efficiency
    x = a0 / (math.pi * ar)
    return a0 / (np.sqrt(1.0 + x * x) + x)


def lifting_line_slope(aspect_ratio, *, efficiency: float = FIN_EFFICIENCY):
    r"""Prandtl's lifting-line slope as Whicker & Fehlner and Prestero use it (for comparison).

    .. math:: c_{L\alpha} = \left[\frac{1}{2 a \pi} + \frac{1}{\pi AR_e}\right]^{-1}

    Not used by the model (:func:`fin_lift_slope` is): kept to reproduce Prestero's printed
    intermediate values (AR_e = 2.21 gives 3.1165, printed 3.12) and for the comparison with
    measured slopes.  ``aspect_ratio`` [-], ``efficiency`` a [-]; returns [1/rad].

    References
    ----------
    Whicker & Fehlner 1958, DTMB report 933; Prestero 2001, sec. 3.6.2.
    """
    ar = np.asarray(aspect_ratio, dtype=float)
    return 1.0 / (1.0 / (2.0 * efficiency * math.pi) + 1.0 / (math.pi * ar))


def interference_factor(root_radius, tip_radius):
    r"""Fin-hull interference factor of slender-body theory, :math:`(1 + R/s)^2`.

    .. math:: K = K_{W(B)} + K_{B(W)} = (1 + \tau)^2,\qquad \tau = R/s

    the lift of a fin (or fin pair) on a cylinder of radius R, tip at s from the axis, over
    the lift of the exposed fin alone (span s - R, the hull a reflection plane).  It follows
    from the apparent mass per unit length of the cross-section at the trailing edge,
    :math:`m = \pi\rho(s^2 - R^2 + R^4/s^2)` for a cylinder with a fin pair
    (:func:`stripcoef.sections.added_mass.circle_with_fins`): slender-body lift is
    :math:`q\,2\alpha\,m/\rho`, so the fins add :math:`\pi(s^2 - 2R^2 + R^4/s^2) =
    \pi(s - R)^2 (1 + \tau)^2` to the body's :math:`\pi R^2`, against :math:`\pi(s - R)^2`
    for the exposed pair alone.  A single fin (a sail) is given the same factor: its exact
    2D value is 4 % lower at R/s = 0.55 (thin-fin limit of the 2D panel method,
    tests/test_lift_control.py), the hull's image acting almost like the fin's mirror.

    Parameters
    ----------
    root_radius : float or array
        R, hull radius at the fin root [m], >= 0
    tip_radius : float or array
        s, distance of the fin tip from the hull axis [m], > R

    Returns
    -------
    float or array
        K [-], from 1 (R = 0) towards 4 (R -> s)

    References
    ----------
    Pitts, Nielsen & Kaattari (1957), NACA Report 1307, "Lift and center of pressure of
    wing-body-tail combinations at subsonic, transonic, and supersonic speeds" (slender-body
    K_W(B), K_B(W)); Nielsen (1988), *Missile Aerodynamics*, ch. 5; Newman (1977), *Marine
    Hydrodynamics*, sec. 4.13 (the finned circle's apparent mass) and ch. 7 (slender-body
    lift from the apparent mass).
    """
    r = np.asarray(root_radius, dtype=float)
    s = np.asarray(tip_radius, dtype=float)
    if np.any(r < 0.0) or np.any(s <= r):
        raise ValueError(f"interference_factor needs 0 <= root radius < tip radius, "
                         f"got R = {root_radius}, s = {tip_radius}")
    out = (1.0 + r / s) ** 2
    return float(out) if out.ndim == 0 else out


def cylindrical_root(radii) -> bool:
    """True if hull radii [m] sampled along a fin's root chord vary by at most
    :data:`CYLINDER_TOLERANCE` of their largest value (the fin sits on a cylinder); False for
    no samples (a root reaching past the hull's ends)."""
    r = np.asarray(radii, dtype=float)
    return bool(r.size and r.min() > 0.0 and (r.max() - r.min()) <= CYLINDER_TOLERANCE * r.max())


def body_lift_slope(length: float, diameter: float) -> float:
    r"""Body lift slope of a slender body of revolution, per radian.

    .. math:: c_{yd\beta} = 0.003\,\frac{l}{d}\ [1/\mathrm{deg}] = 0.003\,\frac{l}{d}\,\frac{180}{\pi}\ [1/\mathrm{rad}]

    Parameters
    ----------
    length, diameter : float
        l and the largest diameter d [m]

    Returns
    -------
    float
        c_ydbeta [1/rad], based on d^2

    References
    ----------
    Hoerner & Borst 1985, ch. 19; Prestero 2001, sec. 3.6.1 (REMUS, l/d = 6.97: 1.2).
    """
    return BODY_LIFT_PER_DEG * (length / diameter) * 180.0 / math.pi


def lift_column(direction, point) -> np.ndarray:
    r"""Generalized force of a unit force along ``direction`` at ``point``: :math:`c = [e;\ r \times e]`.

    ``direction`` e [-] and ``point`` r [m] relative to the reference point, FRD body axes;
    returns c [-, m]. Moment of a point force, Fossen 2011, eq. 3.2 (:math:`M = r \times F`).
    """
    e = np.asarray(direction, dtype=float)
    return np.concatenate([e, skew(np.asarray(point, dtype=float)) @ e])


#: Chord fraction, from the leading edge, at which a lifting surface's incidence from the body's
#: rotation is taken: the three-quarter-chord point (thin-airfoil theory: Pistolesi's theorem;
#: the control point of Weissinger's 1947 lifting-surface method, NACA TM 1120, and of the
#: vortex-lattice method, Katz & Plotkin 2001, sec. 12.1) [-].
ROTARY_CHORD_FRACTION = 0.75


def rotary_incidence_point(point, chord: float) -> np.ndarray:
    r"""Where a fin's (or ring wing's) incidence from the body's rotation is taken: its
    three-quarter-chord point, half a chord aft of the quarter-chord ``point`` (x forward).

    .. math:: r_\omega = r_{c/4} - \tfrac12 c\,\hat x

    A surface in the rotation :math:`\omega` meets the curved cross-flow
    :math:`v + \omega\times r`, varying linearly along its chord: a flow a flat plate meets as a
    parabolic camber line, whose lift (thin-airfoil theory) is that of the incidence at the
    three-quarter chord, acting at the quarter chord (Pistolesi's theorem; the 3/4-chord rule of
    Weissinger's lifting-surface method and of the vortex lattice).  The sideslip incidence
    :math:`e^T v` is the same at every point, and the force stays at the quarter chord.  A
    planar vortex lattice of rectangular wings (``validation.lift.rotary_point_lattice``) puts
    the point at 0.50 c aft of the quarter chord for AR 20, 0.55 c at AR 1.5, 0.58 c at AR 1,
    tending to the trailing edge (0.75 c, slender-wing theory) as AR -> 0: the rule is the
    large-aspect-ratio limit, a little forward for the low-aspect-ratio fins.  The wing term of
    Roskam (1985, *Airplane Design* VI, sec. 10.2.7), :math:`C_{Lq} = (\tfrac12 + 2\bar x_w/
    \bar c)\,C_{L\alpha}` on :math:`q\bar c/2U`, has this arm term :math:`2\bar x_w/\bar c`
    (the quarter chord :math:`\bar x_w` aft of the reference point) but an own term 1/2 that
    puts the incidence at the half chord, which the lattice does not give at any aspect ratio.

    Parameters
    ----------
    point : (3,)
        Quarter-chord point at mid span [m] (body axes, x forward)
    chord : float
        Mean chord c [m], >= 0

    Returns
    -------
    (3,) array
        :math:`r_\omega` [m]

    References
    ----------
    Katz, J. & Plotkin, A. (2001), *Low-Speed Aerodynamics*, 2nd ed., sec. 5.3-5.4 (thin
    airfoil: the lift of a cambered plate; the lumped vortex with its collocation point at the
    three-quarter chord) and sec. 12.1 (vortex lattice); Weissinger, J. (1947), "The lift
    distribution of swept-back wings", NACA TM 1120 (the 3/4-chord rule on finite wings).
    """
    if chord < 0.0:
        raise ValueError(f"rotary_incidence_point needs a chord >= 0, got {chord}")
    out = np.array(point, dtype=float)
    out[0] -= (ROTARY_CHORD_FRACTION - 0.25) * chord
    return out


def fin_lift_matrix(area: float, lift_slope: float, direction, point, *, rho: float,
                    incidence_point=None) -> np.ndarray:
    r"""Lift matrix of one fin: :math:`L = \tfrac12 \rho S c_{L\alpha}\, c\, a^T` (force :math:`-uL\nu`).

    :math:`c = [e;\ r \times e]` at the force's point r (the quarter chord) and
    :math:`a = [e;\ r_\omega \times e]` at ``incidence_point`` :math:`r_\omega`, where the
    rotation's incidence is taken (:func:`rotary_incidence_point`, the three-quarter chord;
    default r: :math:`a = c`).

    Parameters
    ----------
    area : float
        S, planform area [m^2]
    lift_slope : float
        c_Lalpha [1/rad] (:func:`fin_lift_slope`)
    direction : (3,)
        Unit normal of the fin's plane (y for a vertical fin, z for a horizontal one) [-]
    point : (3,)
        Quarter-chord point at mid span, relative to the reference point [m]
    rho : float
        Fluid density [kg/m^3]
    incidence_point : (3,), optional
        :math:`r_\omega` relative to the reference point [m] (default ``point``)

    Returns
    -------
    (6, 6) array
        [kg/m, kg, kg m]

    References
    ----------
    Prestero 2001, sec. 3.6.2 (Y_uvf = -rho c_La S_fin for a fin pair, Y_urf, N_uvf,
    N_urf from the fin's lever arm); the cross velocity at the fin is
    :math:`e^T(v + \omega \times r) = c^T \nu` (module docstring); the rotation's incidence at
    the three-quarter chord (:func:`rotary_incidence_point`).
    """
    c = lift_column(direction, point)
    a = c if incidence_point is None else lift_column(direction, incidence_point)
    return 0.5 * rho * area * lift_slope * np.outer(c, a)


def body_lift_matrix(length: float, diameter: float, center_of_pressure, *,
                     rho: float, velocity_point=(0.0, 0.0, 0.0)) -> np.ndarray:
    r"""Lift matrix of a slender body of revolution (force :math:`-uL\nu`).

    .. math:: L = k\,(c_y a_y^T + c_z a_z^T),\quad k = \tfrac12 \rho d^2 c_{yd\beta},\quad
              c_e = [e;\ r_{cp} \times e],\quad a_e = [e;\ r_v \times e]

    the force of the sideslip (angle of attack) :math:`a_e^T\nu = e^T(v + \omega\times r_v)`
    at the body's centre ``velocity_point`` r_v, acting at the centre of pressure r_cp. About
    the centre itself this is :math:`L_{22} = L_{33} = k`, :math:`L_{62} = x_{cp} k`,
    :math:`L_{53} = -x_{cp} k` (Prestero's form, which takes v at his origin, the CB).

    Parameters
    ----------
    length, diameter : float
        l, d [m]
    center_of_pressure : (3,)
        Centre of pressure relative to the reference point [m]
    rho : float
        Fluid density [kg/m^3]
    velocity_point : (3,)
        Where the sideslip is measured (the centre of buoyancy), relative to the reference
        point [m]; makes the matrix move between reference points like D_L

    Returns
    -------
    (6, 6) array
        [kg/m, kg, kg m]

    References
    ----------
    Hoerner & Borst 1985, ch. 19; Prestero 2001, sec. 3.6.1 (Y_uvl, Z_uwl, M_uwl, N_uvl).
    """
    k = 0.5 * rho * diameter ** 2 * body_lift_slope(length, diameter)
    out = np.zeros((6, 6))
    for e in ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]):
        out += k * np.outer(lift_column(e, center_of_pressure), lift_column(e, velocity_point))
    return out


#: Hopkins's correlation for the station x_0 (from the nose) behind which a body's cross-flow
#: stops being potential: x_0 = a l + b x_1, x_1 the station of the most negative dS/dx
#: (Hopkins 1951, NACA RM A51C14, as USAF DATCOM sec. 4.2.1.1 uses it) [-].
SEPARATION_A, SEPARATION_B = 0.378, 0.527


def separation_station(x, area) -> float:
    r"""Station x_0 [m] behind which a slender body's cross-flow lift stops (Hopkins's correlation).

    .. math:: s_0 = 0.378\,l + 0.527\,s_1

    with s measured aft from the nose, l the body length and :math:`s_1` the station where the
    cross-section area S decreases fastest (most negative dS/ds).  Returned as a body-axes x
    (forward positive): :math:`x_0 = x_{nose} - s_0`.

    Parameters
    ----------
    x : (n,) array
        Stations along the body, increasing [m] (body axes, x forward)
    area : (n,) array
        Cross-section area S(x) [m^2]

    Returns
    -------
    float
        x_0 [m]

    References
    ----------
    Hopkins, E. J. (1951), "A semiempirical method for calculating the pitching moment of bodies
    of revolution at low Mach numbers", NACA RM A51C14, eq. (13) and fig. 4; USAF DATCOM (Finck
    1978) sec. 4.2.1.1 (the same x_0 for the body's lift).
    """
    x = np.asarray(x, dtype=float)
    s = np.asarray(area, dtype=float)
    nose, tail = float(x[-1]), float(x[0])
    x1 = float(x[np.argmax(np.gradient(s, x))])   # dS/dx > 0 in x forward = S falling aft
    s0 = SEPARATION_A * (nose - tail) + SEPARATION_B * (nose - x1)
    return nose - s0


def slender_body_lift_matrix(x, area, x_separation: float, *, rho: float, y: float = 0.0,
                             z: float = 0.0, ref=(0.0, 0.0, 0.0)) -> np.ndarray:
    r"""Lift matrix of a body of revolution whose cross-flow stays potential ahead of x_0 only.

    Slender-body theory (Munk 1924) gives each station the force per unit length
    :math:`f(x) = U\,\mathrm{d}[m(x)\,V(x)]/\mathrm{d}x` along a cross direction e, with
    :math:`m = \rho S(x)` the section's added mass (circle) and :math:`V = e^T(v + \omega\times
    r)` the local cross-flow velocity (:math:`v + x r` in sway, :math:`w - x q` in heave).  Over
    the whole closed body this integrates to no force and the Munk moment, which the model has
    in :math:`C_A(\nu)\nu`.  Behind the station x_0 the cross-flow separates and the sections
    give nothing back (Hopkins 1951; DATCOM 4.2.1.1); the lift matrix is the difference, the
    potential force of the stretch behind x_0 taken away:

    .. math:: L = \rho\,\Big[S_0\, c_0 c_0^T - \int_{x_{tail}}^{x_0} S(x)\, c'(x)\, c(x)^T dx\Big]

    with :math:`c(x) = [e;\ r(x)\times e]`, :math:`c' = \mathrm{d}c/\mathrm{d}x =
    [0;\ \hat x \times e]` and the force :math:`-u L \nu`.  In sway about a point at x = 0:
    :math:`Y_{uv} = -\rho S_0`, :math:`Y_{ur} = -\rho S_0 x_0`, :math:`N_{uv} = -\rho(S_0 x_0
    - \int S\,dx)`, :math:`N_{ur} = -\rho(S_0 x_0^2 - \int S\,x\,dx)` (integrals over the
    stretch behind x_0): a yaw rate gives the rotary terms through the local cross-flow.

    Parameters
    ----------
    x : (n,) array
        Stations, increasing [m] (body axes)
    area : (n,) array
        S(x) [m^2]
    x_separation : float
        x_0 [m] (:func:`separation_station`)
    rho : float
        Fluid density [kg/m^3]
    y, z : float
        The body's axis [m]
    ref : (3,)
        Reference point [m]

    Returns
    -------
    (6, 6) array
        [kg/m, kg, kg m]

    References
    ----------
    Munk, M. M. (1924), NACA Report 184; Newman, *Marine Hydrodynamics* (1977), sec. 7.8
    (slender-body force per unit length, :math:`-\frac{D}{Dt}(m V)`); Hopkins (1951), NACA RM
    A51C14 (potential lift only ahead of x_0); USAF DATCOM sec. 4.2.1.1; Nielsen, *Missile
    Aerodynamics* (1988), ch. 3.
    """
    x = np.asarray(x, dtype=float)
    s = np.asarray(area, dtype=float)
    ref = np.asarray(ref, dtype=float)
    x0 = float(x_separation)
    s0 = float(np.interp(x0, x, s))
    aft = x <= x0
    xa = np.append(x[aft], x0)
    sa = np.append(s[aft], s0)
    out = np.zeros((6, 6))
    for e in (np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])):
        c0 = lift_column(e, np.array([x0, y, z]) - ref)
        out += rho * s0 * np.outer(c0, c0)
        dc = np.concatenate([np.zeros(3), np.cross([1.0, 0.0, 0.0], e)])
        cols = np.array([lift_column(e, np.array([t, y, z]) - ref) for t in xa])
        integral = np.trapezoid(sa[:, None] * cols, xa, axis=0) if xa.size > 1 else np.zeros(6)
        out -= rho * np.outer(dc, integral)
    return out


def munk_factor(length: float, diameter: float) -> float:
    r"""Munk's apparent-mass factor :math:`k_2 - k_1` of a body of fineness l/d.

    .. math:: k_2 - k_1 \quad\text{of Lamb's prolate spheroid with } a/b = l/d

    the factor by which the USAF DATCOM's body method (sec. 4.2.1.1, after Munk 1924 and
    Hopkins 1951) multiplies slender-body theory's sectional apparent mass
    :math:`\rho S(x)` in the potential lift ahead of the separation station,
    :math:`C_{N\alpha} = 2 (k_2 - k_1) S(x_0)/S_{ref}`: the finite body's cross-flow is
    weaker than the slender sections' (k2 -> 1, k1 -> 0 as l/d -> infinity).  DATCOM
    Fig. 4.2.1.1-20a tabulates the same factor; Digital DATCOM (subroutine BODYRT) takes it
    from the fineness ratio as here.  SUBOFF (l/d = 8.575): 0.924; REMUS (6.98): 0.897.

    Parameters
    ----------
    length, diameter : float
        l and the largest diameter d [m], l/d >= 1

    Returns
    -------
    float
        k2 - k1 [-]

    References
    ----------
    Munk, M. M. (1924), NACA Report 184 (the (k2 - k1) correction of the airship's moment);
    Hopkins, E. J. (1951), NACA RM A51C14; USAF DATCOM (Finck 1978) sec. 4.2.1.1;
    Lamb (1932), *Hydrodynamics*, sec. 373 (:func:`stripcoef.hull.lamb.lamb_k_factors`).
    """
    if not length >= diameter > 0.0:
        raise ValueError(f"munk_factor needs l >= d > 0, got l = {length}, d = {diameter}")
    k1, k2, _ = lamb_k_factors(length / diameter)
    return float(k2 - k1)


def wing_body_factors(tau) -> dict:
    r"""Slender-body wing-body interference factors of Pitts, Nielsen & Kaattari (1957).

    A fin pair (or one fin with its image) on a circular body of radius a, tip at s from the
    axis, :math:`\tau = a/s`; each factor is a lift over the exposed fin pair's lift alone
    (the "wing alone", span 2(s - a), at the same angle):

    .. math::
       K_{W(B)} &= \frac{2}{\pi}\,\frac{(1+\tau^4)\left[\tfrac12\arctan\tfrac12(\tau^{-1}-\tau)
                   + \tfrac{\pi}{4}\right] - \tau^2\left[(\tau^{-1}-\tau) + 2\arctan\tau\right]}
                   {(1-\tau)^2} \\
       K_{B(W)} &= (1+\tau)^2 - K_{W(B)} \\
       k_{W(B)} &= \frac{1}{\pi^2}\Big[\frac{\pi^2}{4}\frac{(\lambda+1)^2}{\lambda^2}
                   + \pi B A - 2\pi C + B A^2 - 4 C A
                   + \frac{8}{(\lambda-1)^2}\ln\frac{\lambda^2+1}{2\lambda}\Big] \\
       k_{B(W)} &= K_{W(B)} - k_{W(B)}

    with :math:`\lambda = 1/\tau`, :math:`A = \arcsin\frac{\lambda^2-1}{\lambda^2+1}`,
    :math:`B = \frac{(\lambda^2+1)^2}{\lambda^2(\lambda-1)^2}`,
    :math:`C = \frac{\lambda+1}{\lambda(\lambda-1)}`.  K: the combination at angle of attack
    (the fin in the body's upwash, K_W(B); the lift carried onto the body, K_B(W)); k: the fin
    deflected on a body at zero angle (its own lift k_W(B), the carry-over k_B(W), from the
    reciprocity K_W(B) = k_W(B) + k_B(W)).  Limits: all K, k -> 1, 0, 1, 0 as tau -> 0;
    K_W(B), K_B(W) -> 2, 2 and k_W(B), k_B(W) -> 1, 1 as tau -> 1.

    Parameters
    ----------
    tau : float
        a/s [-], 0 < tau < 1

    Returns
    -------
    dict
        ``K_WB``, ``K_BW``, ``k_WB``, ``k_BW`` [-]

    References
    ----------
    Pitts, W. C., Nielsen, J. N. & Kaattari, G. E. (1957), NACA Report 1307, the slender-body
    expressions for K_W(B) and k_W(B), K_W(B) + K_B(W) = (1 + a/s)^2 and the reciprocity
    k_W(B) + k_B(W) = K_W(B) (the equation numbers of the report were not at hand: the forms
    are checked against these identities and limits in tests/test_lift_control.py); Nielsen,
    *Missile Aerodynamics* (1988), ch. 5.
    """
    t = float(tau)
    if not 0.0 < t < 1.0:
        raise ValueError(f"wing_body_factors needs 0 < a/s < 1, got {tau}")
    kwb_cap = 2.0 / math.pi * ((1.0 + t ** 4) * (0.5 * math.atan(0.5 * (1.0 / t - t)) + math.pi / 4)
                               - t * t * ((1.0 / t - t) + 2.0 * math.atan(t))) / (1.0 - t) ** 2
    lam = 1.0 / t
    a = math.asin((lam * lam - 1.0) / (lam * lam + 1.0))
    b = (lam * lam + 1.0) ** 2 / (lam * lam * (lam - 1.0) ** 2)
    c = (lam + 1.0) / (lam * (lam - 1.0))
    kwb = (math.pi ** 2 / 4 * (lam + 1.0) ** 2 / lam ** 2 + math.pi * b * a - 2 * math.pi * c
           + b * a * a - 4 * c * a + 8.0 / (lam - 1.0) ** 2
           * math.log((lam * lam + 1.0) / (2 * lam))) / math.pi ** 2
    return {"K_WB": kwb_cap, "K_BW": (1.0 + t) ** 2 - kwb_cap, "k_WB": kwb, "k_BW": kwb_cap - kwb}


#: Turbulent flat-plate boundary layer, delta / x = 0.37 Re_x^(-1/5) (Prandtl's 1/7-power law
#: with the Blasius friction law; Schlichting 1979, ch. XXI) [-].
BL_COEFFICIENT, BL_EXPONENT = 0.37, 0.2
#: Exponent of the power-law velocity profile u/U = (y/delta)^(1/7) (Schlichting 1979,
#: ch. XXI) [-].
BL_PROFILE = 1.0 / 7.0


def boundary_layer_thickness(x: float, speed: float, viscosity: float) -> float:
    r"""Thickness of a turbulent boundary layer run from the nose, as on a flat plate.

    .. math:: \delta = 0.37\,x\,Re_x^{-1/5},\qquad Re_x = U x / \nu

    Parameters
    ----------
    x : float
        Run length from the nose [m], >= 0
    speed : float
        U [m/s], > 0
    viscosity : float
        Kinematic viscosity nu [m^2/s]

    Returns
    -------
    float
        delta [m]

    References
    ----------
    Schlichting, *Boundary-Layer Theory*, 7th ed. (1979), ch. XXI (turbulent flat plate with
    the 1/7-power profile); the closing afterbody thickens it further, which this does not
    represent.
    """
    if x <= 0.0:
        return 0.0
    return BL_COEFFICIENT * x * (speed * x / viscosity) ** (-BL_EXPONENT)


def boundary_layer_pressure_ratio(span: float, delta: float, profile: float = BL_PROFILE) -> float:
    r"""Mean dynamic pressure over a fin's span rising out of a power-law boundary layer, over q.

    .. math:: \bar q / q = \frac{1}{b}\Big[\int_0^{\min(b,\delta)} (y/\delta)^{2p}\,dy
              + \max(b - \delta, 0)\Big]
              = \frac{\delta}{b}\,\frac{1}{1 + 2p} + 1 - \frac{\delta}{b} \quad (b \ge \delta)

    each strip of the fin lifting with its local :math:`\tfrac12\rho u(y)^2` (strip
    assumption), :math:`u/U = (y/\delta)^p`, p = 1/7 by default (7/9 for b = delta).
    ``span`` b [m] > 0, ``delta`` [m] >= 0, ``profile`` p [-] > 0 (:func:`power_law_exponent`
    of a computed boundary layer); returns the ratio [-] in (0, 1].

    References
    ----------
    Schlichting 1979, ch. XXI (the profile); the strip-wise reduction of a tail's dynamic
    pressure in a body's boundary layer as in Pitts, Nielsen & Kaattari 1957 (NACA Report 1307,
    the wing's lift taken at the local dynamic pressure) and Hoerner & Borst 1985, ch. 8.
    """
    if span <= 0.0:
        raise ValueError(f"boundary_layer_pressure_ratio needs a span > 0, got {span}")
    if delta <= 0.0:
        return 1.0
    p = 2.0 * profile
    inside = min(span, delta)
    return (delta * (inside / delta) ** (p + 1.0) / (p + 1.0) + max(span - delta, 0.0)) / span


def axial_velocity_ratio(s, area, s_point, r_point):
    r"""Local axial speed over the free stream near a body of revolution in axial potential flow.

    The body as a line of sources of strength :math:`U\,dS/ds` per unit length along its axis
    (s from the nose, aft positive; Munk's slender-body source distribution), whose axial
    perturbation velocity at (s, r) is

    .. math:: \frac{u}{U} = 1 + \frac{1}{4\pi}\int_0^l \frac{dS}{d\sigma}\,
              \frac{s - \sigma}{[(s - \sigma)^2 + r^2]^{3/2}}\,d\sigma

    below 1 over a closing afterbody (the flow slows towards the tail's stagnation point), just
    above 1 along the middle body.

    Parameters
    ----------
    s : (n,) array
        Stations from the nose, increasing [m]
    area : (n,) array
        Cross-section area S(s) [m^2]
    s_point, r_point : float or arrays of one shape
        Where [m]: distance from the nose and from the axis (r > 0)

    Returns
    -------
    float or array of that shape
        u/U [-]

    References
    ----------
    Newman, *Marine Hydrodynamics* (1977), sec. 7.3-7.4 (slender body in axial flow: source
    strength U S'(x)); Thwaites (ed.), *Incompressible Aerodynamics* (1960), ch. IX (line
    source distributions for bodies of revolution); Hoerner & Borst 1985, ch. 8 (tail surfaces
    in the reduced dynamic pressure at a body's stern).
    """
    s = np.asarray(s, dtype=float)
    ds = np.gradient(np.asarray(area, dtype=float), s)
    s_point, r_point = np.broadcast_arrays(np.asarray(s_point, float), np.asarray(r_point, float))
    d = s_point[..., None] - s
    kernel = ds * d / (d * d + r_point[..., None] ** 2) ** 1.5
    u = 1.0 + np.trapezoid(kernel, s, axis=-1) / (4.0 * math.pi)
    return float(u) if u.ndim == 0 else u


def surface_speed_ratio(s, area) -> np.ndarray:
    r"""Potential-flow speed along the surface of a body of revolution in axial flow, U_e/U.

    .. math:: \frac{U_e}{U} = \sqrt{\Big(\frac{u}{U}\Big)^2 + \Big(\frac{dr}{ds}\Big)^2}

    with u/U the line-source axial velocity at the surface (:func:`axial_velocity_ratio`,
    r = sqrt(S/pi)) and the radial velocity :math:`U\,dr/ds` of the surface's tangency
    (slender-body theory: the source :math:`U\,S'/(2\pi r)` at the surface).  On the SUBOFF
    afterbody it is within 7 % of the axisymmetric panel solution
    (:mod:`stripcoef.hull.axisymmetric`), lower at the shoulder's suction peak (1.07 against
    1.12 at 0.78 l).

    Parameters
    ----------
    s : (n,) array
        Stations from the nose, increasing [m]
    area : (n,) array
        S(s) [m^2]

    Returns
    -------
    (n,) array
        U_e/U [-] (at the two ends, where r = 0, the axial value)

    References
    ----------
    Newman 1977, sec. 7.3-7.4 (slender body in axial flow); Thwaites 1960, ch. IX.
    """
    return _surface_speed_ratio(np.asarray(s, dtype=float), np.asarray(area, dtype=float))


@array_memo(maxsize=32)
def _surface_speed_ratio(s, area) -> np.ndarray:
    """:func:`surface_speed_ratio` of float arrays: a pure function of them, an n x n line-
    source integral computed once per process for each hull (every estimate of a vehicle
    under the slender-body rule asks it; the memo's key, :func:`stripcoef.hull.memo.array_memo`)."""
    r = np.sqrt(np.maximum(area, 0.0) / math.pi)
    slope = np.gradient(r, s)
    floor = 1e-3 * max(float(r.max()), 1e-300)
    u = axial_velocity_ratio(s, area, s, np.maximum(r, floor))
    return np.hypot(u, np.where(r > floor, slope, 0.0))


def power_law_exponent(shape_factor: float) -> float:
    r"""Exponent p of the power-law profile :math:`u/U = (y/\delta)^p` with shape factor H.

    .. math:: H = \frac{\delta^*}{\theta} = 1 + 2p, \qquad p = \frac{H - 1}{2},
              \qquad \frac{\delta^*}{\delta} = \frac{p}{1 + p}

    (p = 1/7: H = 9/7, delta*/delta = 1/8).  ``shape_factor`` H [-] > 1; returns p [-].

    References
    ----------
    Schlichting 1979, ch. XXI (power-law profiles and their thicknesses).
    """
    if shape_factor <= 1.0:
        raise ValueError(f"power_law_exponent needs H > 1, got {shape_factor}")
    return 0.5 * (shape_factor - 1.0)


def ring_wing_lift_slope(aspect_ratio):
    r"""Lift-curve slope of a thin ring (annular) wing of diameter D and chord c, on the area D c.

    .. math:: C_{L\alpha} = \frac{\pi^2}{1 + \tfrac{\pi}{2}\lambda
              + \lambda \arctan(1.2\,\lambda)},\qquad \lambda = \frac{c}{D} = \frac1A

    Weissinger's approximation to his lifting-surface solution of the thin ring wing
    (Weissinger 1955; the closed form as quoted by Wagner 2021, eq. 15), published for
    lambda < 5 and with both exact limits:

    - short chord (A -> infinity): :math:`\pi^2`, Ribner's (1947) lifting-line result for the
      ring (twice the lift of the elliptic wing of span D at the same induced velocity);
    - long chord (A -> 0): :math:`\pi A` (:math:`\arctan(1.2\lambda) \to \pi/2 - 1/(1.2\lambda)`),
      slender-body theory's ring, whose cross-section carries the apparent mass of the circle
      outside it plus the enclosed fluid, :math:`2\rho\pi R^2`: :math:`L = q\,\pi D^2\alpha`,
      Hoerner's ring of small aspect ratio (*Fluid-Dynamic Lift*, 1985, p. 7-13), twice the
      solid body of the same diameter.

    Measured: Fletcher's five annular airfoils (NACA TN 4117, 1957, Fig. 11, p. 19; A = 1/3 to
    3, Mach 0.13) lie within 2.3 % of it (tests/test_lift_ring.py); a vortex lattice of the
    thin ring (``validation.lift.ring_vortex_lattice``) within 1.2 % from A = 0.3 to 10. No
    section-efficiency factor: Fletcher's thick rings meet the thin-ring formula as published.
    A converging ring is taken at its mean radius.

    Parameters
    ----------
    aspect_ratio : float or array
        A = D/c [-], > 0

    Returns
    -------
    float or array
        C_Lalpha [1/rad] on the projected area D c

    References
    ----------
    Weissinger, J. (1955), "Zur Aerodynamik des Ringflügels I. Die Druckverteilung dünner, fast
    drehsymmetrischer Flügel in Unterschallströmung", DVL Bericht 2 (the closed form as quoted
    by Wagner 2021, eq. 15; read second-hand); Ribner, H. S. (1947), "The ring airfoil in
    nonaxial flow", J. Aeronaut. Sci. 14 (the lifting-line limit, Wagner 2021 eq. 13);
    Fletcher, H. S. (1957), NACA TN 4117, Fig. 11 (the measured slopes); Hoerner & Borst 1985,
    p. 7-13 (the slender limit).
    """
    ar = np.asarray(aspect_ratio, dtype=float)
    if np.any(ar <= 0.0):
        raise ValueError(f"ring_wing_lift_slope needs D/c > 0, got {aspect_ratio}")
    lam = 1.0 / ar
    out = math.pi ** 2 / (1.0 + 0.5 * math.pi * lam + lam * np.arctan(1.2 * lam))
    return float(out) if out.ndim == 0 else out


def ring_wing_lift_matrix(radius: float, chord: float, point, *, rho: float,
                          pressure_ratio: float = 1.0, wake_point=None,
                          wake_fraction: float = 0.0) -> np.ndarray:
    r"""Lift matrix of a ring wing coaxial with the body x axis (force :math:`-uL\nu`).

    .. math:: L = k\,(c_y a_y^T + c_z a_z^T),\qquad
              k = \tfrac12\rho\,(2Rc)\,C_{L\alpha}\,\frac{\bar q}{q},\qquad
              c_e = [e;\ r \times e],\quad a_e = [e;\ r_\omega \times e]
              - f\,[e;\ r_0 \times e]

    the ring's lift (:func:`ring_wing_lift_slope`, A = 2R/c) at its quarter chord r on the
    axis, answering the cross-flow in sway and in heave alike (an axisymmetric wing), the
    rotation's at the three-quarter chord :math:`r_\omega` half a chord aft of r
    (:func:`rotary_incidence_point`; a converging ring's chord taken along x), at the local
    dynamic pressure :math:`\bar q` (the body's stern flow and boundary layer; 1 in the free
    stream). ``wake_fraction`` f in [0, 1] and ``wake_point`` r_0 (relative to the reference
    point [m]): the ring answers the cross-flow relative to a fluid that moves with the body's
    cross-velocity at r_0 (the separated wake, :func:`stripcoef.assembly.lift.ring_wing_lift`);
    f = 0 (default) is the ring in undisturbed cross-flow.

    Parameters
    ----------
    radius, chord : float
        R (mean radius of the chord line) and c [m], > 0
    point : (3,)
        Quarter-chord point on the ring's axis, relative to the reference point [m]
    rho : float
        Fluid density [kg/m^3]
    pressure_ratio : float
        q_bar / q [-] in (0, 1]
    wake_point : (3,), optional
        r_0 [m], needed when ``wake_fraction`` > 0
    wake_fraction : float
        f [-] in [0, 1]

    Returns
    -------
    (6, 6) array
        [kg/m, kg, kg m]

    References
    ----------
    :func:`ring_wing_lift_slope`; :func:`fin_lift_matrix` (the same point-force form);
    Prestero 2001, sec. 3.6.2.
    """
    if radius <= 0.0 or chord <= 0.0:
        raise ValueError(f"ring_wing_lift_matrix needs R, c > 0, got R = {radius}, c = {chord}")
    k = 0.5 * rho * 2.0 * radius * chord * ring_wing_lift_slope(2.0 * radius / chord) \
        * pressure_ratio
    if not 0.0 <= wake_fraction <= 1.0 or (wake_fraction > 0.0 and wake_point is None):
        raise ValueError(f"ring_wing_lift_matrix needs 0 <= f <= 1 (and r_0 when f > 0), got "
                         f"f = {wake_fraction}")
    out = np.zeros((6, 6))
    turning = rotary_incidence_point(point, chord)
    for e in ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]):
        answer = lift_column(e, turning)
        if wake_fraction > 0.0:
            answer = answer - wake_fraction * lift_column(e, wake_point)
        out += k * np.outer(lift_column(e, point), answer)
    return out
