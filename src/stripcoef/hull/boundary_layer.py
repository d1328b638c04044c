r"""Head's turbulent boundary layer along a body of revolution in axial flow
(:func:`turbulent_boundary_layer`): the layer the stern fins and a ring wing sit in under the
slender-body rule of :mod:`stripcoef.hull.lift`, and the shape factor of its separation.

Moved out of :mod:`stripcoef.hull.lift` (which re-exports every name) so that the solved
layer can be kept in the per-process memo (:func:`stripcoef.hull.memo.array_memo`) without
that module passing its 1000 lines.

References: Head (1958), ARC R&M 3152; Ludwieg & Tillmann (1949); Cebeci & Bradshaw (1977),
*Momentum Transfer in Boundary Layers*; Schlichting (1979), *Boundary-Layer Theory*, chs. XVI,
XXI.

Depends on: hull.memo.
"""

from __future__ import annotations

import math

import numpy as np

from stripcoef.hull.memo import array_memo

#: Head's entrainment method: F(H1) = 0.0306 (H1 - 3)^-0.6169 (Head 1958, ARC R&M 3152, as the
#: fit of Cebeci & Bradshaw 1977 gives his curve; the same constants are coded in SUAVE,
#: suavecode/SUAVE trunk/SUAVE/Methods/Aerodynamics/Airfoil_Panel_Method/heads_method.py,
#: commit 0bc749a11557fdfd7a1166e69bff95591bb13be2) [-].
HEAD_F = (0.0306, -0.6169)
#: Head's mass-flow shape factor H1 = (delta - delta*)/theta = 3.3 + a (H - b)^c, (a, b, c)
#: for H <= 1.6 and for H > 1.6 (the same sources) [-].
HEAD_H1_LOW, HEAD_H1_HIGH = (0.8234, 1.1, -1.287), (1.5501, 0.6778, -3.064)
#: Ludwieg & Tillmann's skin friction c_f = 0.246 x 10^(-0.678 H) Re_theta^-0.268
#: (Ludwieg & Tillmann 1949; the same sources) [-].
LUDWIEG_TILLMANN = (0.246, -0.678, -0.268)
#: Shape factor H at which Head's method calls the turbulent layer separated (Cebeci &
#: Bradshaw 1977: separation is taken at H between 1.8 and 2.4; the lower end is used here,
#: the earliest separation the criterion allows; on SUBOFF H stays below 1.61 ahead of 0.999 l,
#: so any value in the range gives the same answer) [-].
HEAD_SEPARATION_H = 1.8
#: Flat-plate critical Reynolds number Re_x at which the layer is taken turbulent from
#: (Schlichting 1979, ch. XVI: 3.5e5 - 1e6; assumption: 5e5, the textbook value; on SUBOFF
#: the layer at the stern planes changes by < 2 % between transition at 0.05 and 0.10 l) [-].
TRANSITION_REYNOLDS = 5.0e5
#: Initial shape factor of the turbulent layer at transition (flat plate, 1/7-power
#: profile: H = 9/7; Schlichting 1979, ch. XXI) [-].
FLAT_PLATE_H = 9.0 / 7.0


def _head_h1(h: float) -> float:
    """Head's mass-flow shape factor H1(H) (:data:`HEAD_H1_LOW`, :data:`HEAD_H1_HIGH`)."""
    a, b, c = HEAD_H1_LOW if h <= 1.6 else HEAD_H1_HIGH
    return 3.3 + a * (h - b) ** c


def _head_h(h1: float) -> float:
    """Inverse of :func:`_head_h1`, branch by branch: H = b + ((H1 - 3.3)/a)^(1/c), the
    H <= 1.6 branch for H1 >= H1(1.6) of that branch (5.310), clipped to H in (1.1, 10)."""
    a, b, c = HEAD_H1_LOW if h1 >= _head_h1(1.6) else HEAD_H1_HIGH
    h = b + (max(h1 - 3.3, 1e-9) / a) ** (1.0 / c)
    return min(max(h, 1.1 + 1e-6), 10.0)


def turbulent_boundary_layer(s, radius, speed_ratio, *, speed: float, viscosity: float):
    r"""Turbulent boundary layer along a body of revolution in axial flow (Head's method).

    The axisymmetric momentum-integral and entrainment equations (thin layer, r the body's
    radius; Head 1958, written for bodies of revolution as in Cebeci & Bradshaw 1977,
    Head's own definitions):

    .. math::
       \frac{1}{r}\frac{d(r\theta)}{ds} &= \frac{c_f}{2} - (H + 2)\frac{\theta}{U_e}
                                             \frac{dU_e}{ds} \\
       \frac{1}{r U_e}\frac{d(r U_e \theta H_1)}{ds} &= F(H_1) = 0.0306\,(H_1 - 3)^{-0.6169}

    with :math:`H_1(H)` Head's shape-factor relation and Ludwieg & Tillmann's
    :math:`c_f = 0.246\times10^{-0.678H} Re_\theta^{-0.268}`, from the station where
    :math:`Re_s` = :data:`TRANSITION_REYNOLDS` with the flat plate's
    :math:`\theta = 0.036\,s\,Re_s^{-1/5}` and H = 9/7 (Schlichting 1979, ch. XXI).
    Integrated until H reaches :data:`HEAD_SEPARATION_H` (the station interpolated between the
    two steps that bracket it), the body ends or r falls below 2 % of its largest value (the
    thin-layer equations fail at the tail), by the classical fourth-order Runge-Kutta rule with
    fixed steps on the intervals between the given stations (:func:`_runge_kutta_layer`):
    :math:`U_e` and r are the linear interpolants of the tabulated values, so the right-hand
    side is smooth inside each interval and its :math:`dU_e/ds`, :math:`dr/ds` are the
    interpolants' own slopes there.

    Why not an adaptive solver: tabulated data have a kink at every station (a hull tabulated
    as a polyline has a jump of dr/ds at each vertex, so the surface speed, which holds dr/ds,
    has a step there), which the central differences used before (``np.gradient``) turned into
    a spike of :math:`dU_e/ds` two stations wide; ``solve_ivp``'s adaptive RK45 (rtol 1e-6)
    placed its steps across those spikes by round-off. On the SUBOFF hull a relative change of
    1e-13 in the radii moved theta by 2 % at 0.95 l, and a new machine (numpy 2.4.6, scipy
    1.17.1) moved Head's displacement-body lift in docs/validation.md by 3.5 % (issue 34). With
    fixed steps the same change moves theta by < 1e-10, and halving every step by < 1e-7 at
    0.95 l (2e-6 at 0.97 l, where the hull closes; tests/test_lift_slender.py).

    Parameters
    ----------
    s : (n,) array
        Stations from the nose, increasing [m]; they stand for the arc length along the
        meridian (a slender body: the arc is sqrt(1 + r'^2) ds, 4 % longer where the SUBOFF
        afterbody is steepest)
    radius : (n,) array
        r(s) [m]
    speed_ratio : (n,) array
        U_e/U at the surface [-] (:func:`surface_speed_ratio`)
    speed : float
        U [m/s] > 0
    viscosity : float
        Kinematic viscosity [m^2/s] > 0

    Returns
    -------
    dict
        ``s`` [m], ``theta`` [m], ``H`` [-] along the integrated stretch, ``delta`` [m] the
        layer's thickness from Head's definition :math:`\delta = \theta\,(H_1 + H)`;
        ``separation`` the station [m] where H reached :data:`HEAD_SEPARATION_H`, or None;
        ``end`` the last station [m]

    References
    ----------
    Head, M. R. (1958), "Entrainment in the turbulent boundary layer", ARC R&M 3152;
    Ludwieg, H. & Tillmann, W. (1949), Ing.-Arch. 17; Cebeci, T. & Bradshaw, P. (1977),
    *Momentum Transfer in Boundary Layers* (the fits of H1(H) and F(H1), the separation range
    H = 1.8-2.4; its axisymmetric form with r); Schlichting 1979, chs. XVI, XXI (transition,
    flat plate).
    """
    s = np.asarray(s, dtype=float)
    r = np.asarray(radius, dtype=float)
    ue = np.asarray(speed_ratio, dtype=float)
    t, theta, h, delta, sep, end = _layer(s, r, ue, float(speed), float(viscosity))
    return {"s": t, "theta": theta, "H": h, "delta": delta, "separation": sep, "end": end}


#: Largest Runge-Kutta step as a fraction of the integrated stretch: an interval between two
#: given stations longer than this is cut into equal steps (assumption: on SUBOFF at 2001
#: stations every interval is shorter; 200 steps was the former solver's ``max_step``) [-].
MAX_STEP_FRACTION = 1.0 / 200.0


@array_memo(maxsize=32)
def _layer(s, r, ue, speed, viscosity) -> tuple:
    """:func:`turbulent_boundary_layer` as a tuple (s, theta, H, delta, separation, end) of
    float arrays and floats: a pure function of them, solved once per process for each hull
    and speed (every estimate of a finned vehicle under the slender-body rule asks it for
    its stern; the memo's key, :func:`stripcoef.hull.memo.array_memo`)."""
    if speed <= 0.0 or viscosity <= 0.0:
        raise ValueError(f"turbulent_boundary_layer needs speed and viscosity > 0, got "
                         f"{speed}, {viscosity}")
    s0 = float(s[0]) + TRANSITION_REYNOLDS * viscosity / speed
    r_min = 0.02 * float(r.max())
    aft = s[(s > s0) & (r < r_min)]
    s_end = float(aft[0]) if aft.size else float(s[-1])
    if s0 >= s_end:
        raise ValueError("turbulent_boundary_layer: the body is shorter than the laminar run "
                         f"({s0 - s[0]:.3g} m at Re_x = {TRANSITION_REYNOLDS:g})")
    stations = np.concatenate([[s0], s[(s > s0) & (s < s_end)], [s_end]])
    step = MAX_STEP_FRACTION * (s_end - s0)
    knots = [stations[:1]]
    for a, b in zip(stations[:-1], stations[1:]):
        n = max(int(math.ceil((b - a) / step - 1e-9)), 1)
        knots.append(a + (b - a) * np.arange(1, n + 1) / n)
    knots = np.concatenate(knots)
    knots[-1] = s_end
    run = s0 - s[0]
    theta0 = 0.036 * run * (speed * run / viscosity) ** -0.2
    t, y, sep = _runge_kutta_layer(knots, np.interp(knots, s, ue), np.interp(knots, s, r),
                                   theta0, _head_h1(FLAT_PLATE_H), r_min, speed, viscosity)
    h = np.array([_head_h(v) for v in y[:, 1]])
    delta = y[:, 0] * (np.array([_head_h1(v) for v in h]) + h)
    return t, y[:, 0], h, delta, sep, float(t[-1])


def _layer_rates(t, theta, h1, t0, u0, du, r0, dr, r_min, speed, viscosity):
    """(d theta/ds, d H1/ds) of Head's equations (:func:`turbulent_boundary_layer`) at ``t``
    [m] inside one interval from ``t0``, where U_e/U = u0 + du (t - t0) and
    r = max(r0 + dr (t - t0), r_min) [m]."""
    theta = max(theta, 1e-12)           # a layer thinner than this does not occur on a hull
    h = _head_h(h1)
    u = u0 + du * (t - t0)
    rs = dr / max(r0 + dr * (t - t0), r_min)
    cf0, cfh, cfr = LUDWIEG_TILLMANN
    cf = cf0 * 10.0 ** (cfh * h) * (speed * u * theta / viscosity) ** cfr
    dtheta = 0.5 * cf - (h + 2.0) * theta * du / u - theta * rs
    f = HEAD_F[0] * max(h1 - 3.0, 1e-6) ** HEAD_F[1]
    return dtheta, (f - h1 * (theta * du / u + dtheta + theta * rs)) / theta


def _runge_kutta_layer(knots, ue, r, theta0, h10, r_min, speed, viscosity):
    """Head's layer stepped from knot to knot (classical fourth-order Runge-Kutta, Hairer,
    Norsett & Wanner 1993, *Solving Ordinary Differential Equations I*, sec. II.1) with U_e/U
    and r linear inside each step (their values ``ue``, ``r`` at the ``knots`` [m]): returns
    (s [m], (theta [m], H1 [-]) rows, separation station [m] or None), stopped at the station
    where H reaches :data:`HEAD_SEPARATION_H`, interpolated linearly in H between the two
    knots that bracket it."""
    theta, h1 = float(theta0), float(h10)
    out_s, out_y = [float(knots[0])], [(theta, h1)]
    h_prev = _head_h(h1)
    for i in range(len(knots) - 1):
        a, b = float(knots[i]), float(knots[i + 1])
        w = b - a
        du, dr = (ue[i + 1] - ue[i]) / w, (r[i + 1] - r[i]) / w
        args = (a, float(ue[i]), du, float(r[i]), dr, r_min, speed, viscosity)
        k1 = _layer_rates(a, theta, h1, *args)
        k2 = _layer_rates(a + 0.5 * w, theta + 0.5 * w * k1[0], h1 + 0.5 * w * k1[1], *args)
        k3 = _layer_rates(a + 0.5 * w, theta + 0.5 * w * k2[0], h1 + 0.5 * w * k2[1], *args)
        k4 = _layer_rates(b, theta + w * k3[0], h1 + w * k3[1], *args)
        theta_b = theta + w / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0])
        h1_b = h1 + w / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1])
        h_b = _head_h(h1_b)
        if h_b >= HEAD_SEPARATION_H > h_prev:
            f = (HEAD_SEPARATION_H - h_prev) / (h_b - h_prev)
            sep = a + f * w
            out_s.append(sep)
            out_y.append((theta + f * (theta_b - theta), h1 + f * (h1_b - h1)))
            return np.array(out_s), np.array(out_y), sep
        theta, h1, h_prev = theta_b, h1_b, h_b
        out_s.append(b)
        out_y.append((theta, h1))
    return np.array(out_s), np.array(out_y), None
