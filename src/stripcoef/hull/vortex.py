r"""Trailing vortices of lifting appendages and the sidewash they induce at surfaces behind them.

A fin (or a sail) ahead of a tail surface sheds its lift as a trailing vortex that the stream
carries aft; the surface behind it meets the vortex's sidewash and lifts on the sum of its own
incidence and that sidewash. The method is the wing-body-tail interference of Pitts, Nielsen &
Kaattari (1957, NACA Report 1307, the section on wing-tail interference), in its linear form:

- the panel's trailing vorticity is rolled up into one line vortex at the centroid of its span
  loading, :math:`f = r_{root} + (\pi/4)\,b` from the body axis (the elliptic loading's
  centroid, :data:`ROLLED_UP_CENTROID`; Spreiter & Sacks 1951), which in the linear limit trails
  straight aft, parallel to the body axis;
- its strength :math:`\Gamma` follows from the panel's own lift L (in presence of the body,
  the :math:`K_{W(B)}` part) by the Kutta-Joukowski theorem with the vortex's image in the body
  section (radius a, image at :math:`a^2/f`, of opposite sign):

  .. math:: L = \rho\,U\,\Gamma\,\big(f - a^2/f\big)

- at the tail's station the vortex and its image in the local body section (radius
  :math:`a_t`, image at :math:`a_t^2/f`) induce the two-dimensional cross-flow velocity

  .. math:: \mathbf{u}(P) = \sum_k \frac{\Gamma_k}{2\pi\,|P - P_k|^2}\,J\,(P - P_k),
            \qquad J(y, z) = (-z, y)

- the tail panel lifts on the sidewash averaged over its span by strip theory (each strip's
  lift in proportion with its chord and incidence; a panel of constant chord: the plain
  mean), with the same lift slope and wing-body factors as its own incidence; a ring wing lifts
  on the first circumferential harmonic of the radial velocity,
  :math:`\bar w = \frac1\pi\oint (\mathbf{u}\cdot\hat r)\,\hat r\,d\theta` (the uniform
  cross-flow's is the cross-flow itself).

Everything is linear in the source panel's incidence, so the interference adds a term
:math:`k_t\,g\,\bar h\;c_t\,a_s^T` to the lift matrix (force :math:`-uL\nu`), with
:math:`g = k_s/(\rho (f - a_s^2/f))` [m] the circulation per unit cross-flow at the source and
:math:`\bar h` [1/m] the tail's mean sidewash per unit circulation (``stripcoef.assembly.sidewash``).
"""

from __future__ import annotations

import math

import numpy as np

#: Spanwise centroid of a rolled-up trailing vortex, as a fraction of the (semi-)span from the
#: root: pi/4, the centroid of the elliptic span loading's trailing vorticity (Spreiter, J. R. &
#: Sacks, A. H. 1951, "The rolling up of the trailing vortex sheet and its effect on the
#: downwash behind wings", J. Aero. Sci. 18, p. 21; the fully rolled-up vortex of Pitts, Nielsen
#: & Kaattari 1957, NACA Report 1307, wing-tail interference) [-].
ROLLED_UP_CENTROID = math.pi / 4.0
#: Points round a ring wing at which the sidewash's first harmonic is integrated (midpoint rule;
#: assumption: the integrand is smooth away from the vortex, 64 and 512 points differ by
#: < 0.1 % on SUBOFF's ring) [-].
RING_POINTS = 64
#: Strips along a tail panel's span at which its sidewash is averaged (midpoint rule;
#: assumption: 32 and 256 strips differ by < 1 % on SUBOFF's planes) [-].
SPAN_STRIPS = 32


def vortex_position(root: float, span: float) -> float:
    r"""Distance from the body axis of a panel's rolled-up trailing vortex [m].

    .. math:: f = r_{root} + \tfrac{\pi}{4}\,b

    Parameters
    ----------
    root : float
        Root radius: the body's radius at the panel's root [m], >= 0
    span : float
        Exposed span b, root to tip [m], > 0

    References
    ----------
    Spreiter & Sacks 1951 (the elliptic loading's vorticity centroid, pi/4 of the semi-span);
    the panel on the body taken as a half-wing on a reflection plane, as its effective aspect
    ratio 2 b^2/S does (:func:`stripcoef.hull.lift.effective_aspect_ratio`).
    """
    if root < 0.0 or span <= 0.0:
        raise ValueError(f"vortex_position needs root >= 0 and span > 0, got {root}, {span}")
    return root + ROLLED_UP_CENTROID * span


def circulation_per_crossflow(k_own: float, f: float, body_radius: float, *, rho: float) -> float:
    r"""Circulation of a panel's trailing vortex per unit cross-flow at the panel [m].

    .. math:: g = \frac{\Gamma}{w} = \frac{k}{\rho\,(f - a^2/f)},\qquad L = k\,U\,w
              = \rho\,U\,\Gamma\,(f - a^2/f)

    Parameters
    ----------
    k_own : float
        The panel's own lift per unit speed and cross-flow, :math:`\tfrac12\rho S c_{L\alpha}
        K_{W(B)}\bar q/q` [kg/m]
    f : float
        The vortex's distance from the axis [m] (:func:`vortex_position`)
    body_radius : float
        a, the body's radius at the panel [m], 0 <= a < f
    rho : float
        Fluid density [kg/m^3]

    References
    ----------
    Pitts, Nielsen & Kaattari 1957, NACA Report 1307 (the wing panel's vortex strength from its
    lift with the vortex's image in the body); Kutta-Joukowski theorem for a vortex pair's
    impulse.
    """
    if not 0.0 <= body_radius < f:
        raise ValueError(f"circulation_per_crossflow needs 0 <= a < f, got a = {body_radius}, "
                         f"f = {f}")
    return k_own / (rho * (f - body_radius ** 2 / f))


def induced_velocity(points, vortex, lift_direction, body_radius: float) -> np.ndarray:
    r"""Cross-flow velocity per unit circulation of a panel's trailing vortex and its image [1/m].

    The vortex at ``vortex`` P_v (a point of the cross-flow plane relative to the body axis,
    (y, z) [m]) with the sense of a panel lifting along ``lift_direction`` e (the downwash of
    its own span, between the vortex and the body, is along -e), and its image of opposite sign
    at :math:`(a^2/|P_v|^2) P_v` inside the body section of radius a
    (module docstring: :math:`\mathbf u = \sum_k \Gamma_k J(P - P_k) / 2\pi|P - P_k|^2`).

    Parameters
    ----------
    points : (n, 2)
        Field points (y, z) relative to the axis [m]
    vortex : (2,)
        P_v [m], |P_v| > a
    lift_direction : (2,)
        e, unit, normal to P_v
    body_radius : float
        a [m], >= 0 (0: no image)

    Returns
    -------
    (n, 2) array
        u per unit circulation [1/m]

    References
    ----------
    Milne-Thomson 1968, *Theoretical Hydrodynamics*, sec. 13.60 (the circle theorem: a vortex
    outside a circular cylinder and its image at the inverse point); Pitts, Nielsen & Kaattari
    1957 (the same images at the tail's station).
    """
    p = np.atleast_2d(np.asarray(points, float))
    v = np.asarray(vortex, float)
    e = np.asarray(lift_direction, float)
    r2 = float(v @ v)
    if body_radius < 0.0 or r2 <= body_radius ** 2:
        raise ValueError(f"induced_velocity needs the vortex outside the body: |P_v| = "
                         f"{math.sqrt(r2):.4g}, a = {body_radius}")
    span_dir = v / math.sqrt(r2)
    sense = float(np.array([-span_dir[1], span_dir[0]]) @ e)   # (J s) . e = +-1
    out = np.zeros_like(p)
    for pos, gamma in ((v, sense), ((body_radius ** 2 / r2) * v, -sense)):
        if gamma == 0.0 or (pos is not v and body_radius == 0.0):
            continue
        d = p - pos
        d2 = np.einsum("ij,ij->i", d, d)
        out += (gamma / (2.0 * math.pi)) * np.column_stack([-d[:, 1], d[:, 0]]) / d2[:, None]
    return out


def panel_sidewash(vortex, lift_direction, body_radius: float, *, root: float, span: float,
                   span_direction, direction) -> float:
    r"""Strip-theory mean sidewash per unit circulation over a tail panel's span [1/m].

    .. math:: \bar h = \frac1b \int_{r_t}^{r_t + b} \mathbf e_t\cdot
              \mathbf u\big(r\,\hat s_t\big)\,dr

    (a constant chord: strip theory's chord weighting is uniform), midpoint rule on
    :data:`SPAN_STRIPS` strips.

    Parameters
    ----------
    vortex, lift_direction, body_radius
        The source's vortex (:func:`induced_velocity`), the image in the tail's body section of
        radius ``body_radius`` [m]
    root, span : float
        The tail panel's root radius and span [m]
    span_direction, direction : (2,)
        Unit vectors (y, z): the tail panel's span (root to tip) and its lift direction e_t

    References
    ----------
    Pitts, Nielsen & Kaattari 1957, NACA Report 1307 (the tail interference factor by strip
    theory).
    """
    t = (np.arange(SPAN_STRIPS) + 0.5) / SPAN_STRIPS
    pts = (root + t * span)[:, None] * np.asarray(span_direction, float)[None, :]
    u = induced_velocity(pts, vortex, lift_direction, body_radius)
    return float(np.mean(u @ np.asarray(direction, float)))


def ring_sidewash(vortex, lift_direction, body_radius: float, *, radius: float) -> np.ndarray:
    r"""A ring wing's effective cross-flow per unit circulation of a vortex outside or inside it
    [1/m]: the first circumferential harmonic of the radial velocity at its radius R,

    .. math:: \bar{\mathbf w} = \frac1\pi \oint (\mathbf u\cdot\hat r)\,\hat r\,d\theta

    which is the cross-flow itself for a uniform one (the ring's lift answers it as it answers a
    uniform cross-flow, :func:`stripcoef.hull.lift.ring_wing_lift_matrix`); midpoint rule on
    :data:`RING_POINTS` points.

    Returns
    -------
    (2,) array
        (y, z) [1/m]

    References
    ----------
    Derived here by strip theory round the ring, as :func:`panel_sidewash` along a panel: each
    chordwise strip lifts on its own normal incidence; a uniform cross-flow's first harmonic is
    the cross-flow, so the ring's lift slope (:func:`stripcoef.hull.lift.ring_wing_lift_slope`)
    applies to :math:`\bar{\mathbf w}`. Not checked against a lifting-surface solution of a
    ring in a vortex's field.
    """
    theta = 2.0 * math.pi * (np.arange(RING_POINTS) + 0.5) / RING_POINTS
    rhat = np.column_stack([np.cos(theta), np.sin(theta)])
    u = induced_velocity(radius * rhat, vortex, lift_direction, body_radius)
    radial = np.einsum("ij,ij->i", u, rhat)
    return (2.0 / RING_POINTS) * (radial[:, None] * rhat).sum(axis=0)
