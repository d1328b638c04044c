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
:math:`\bar h` [1/m] the tail's mean sidewash per unit circulation
(``stripcoef.assembly.sidewash``).
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
    out = np.zeros_like(p)
    for pos, gamma in _images(vortex, lift_direction, body_radius):
        d = p - pos
        d2 = np.einsum("ij,ij->i", d, d)
        out += (gamma / (2.0 * math.pi)) * np.column_stack([-d[:, 1], d[:, 0]]) / d2[:, None]
    return out


def _images(vortex, lift_direction, body_radius: float):
    """[(position (2,), circulation per unit)] of a vortex in the sense of
    :func:`induced_velocity` and its image (counter-clockwise positive in (y, z))."""
    v = np.asarray(vortex, float)
    r2 = float(v @ v)
    if body_radius < 0.0 or r2 <= body_radius ** 2:
        raise ValueError(f"induced_velocity needs the vortex outside the body: |P_v| = "
                         f"{math.sqrt(r2):.4g}, a = {body_radius}")
    span_dir = v / math.sqrt(r2)
    sense = float(np.array([-span_dir[1], span_dir[0]]) @ np.asarray(lift_direction, float))
    out = [(v, sense)]
    if body_radius > 0.0:
        out.append(((body_radius ** 2 / r2) * v, -sense))
    return out


def panel_sidewash(vortex, lift_direction, body_radius: float, *, root: float, span: float,
                   span_direction, direction) -> float:
    r"""Strip-theory mean sidewash per unit circulation over a tail panel's span [1/m].

    .. math:: \bar h = \frac1b \int_{r_1}^{r_2} \mathbf e_t\cdot\mathbf u(r\,\hat s_t)\,dr
              = \sum_k \frac{\Gamma_k\,\sigma}{4\pi b}
              \ln\frac{(r_2 - \zeta_k)^2 + h_k^2}{(r_1 - \zeta_k)^2 + h_k^2}

    (a constant chord: strip theory's chord weighting is uniform), in closed form: each vortex
    k (the source's and its image, :func:`induced_velocity`) at :math:`\zeta_k` along the
    panel's span line and :math:`h_k` off it, :math:`\sigma = \mathbf e_t\cdot J\hat s_t =
    \pm 1`; a vortex on the span line (h = 0) gives the integral's principal value.

    Parameters
    ----------
    vortex, lift_direction, body_radius
        The source's vortex (:func:`induced_velocity`), the image in the tail's body section of
        radius ``body_radius`` [m]
    root, span : float
        The tail panel's root radius r_1 and span b = r_2 - r_1 [m]
    span_direction, direction : (2,)
        Unit vectors (y, z): the tail panel's span (root to tip) and its lift direction e_t

    References
    ----------
    Pitts, Nielsen & Kaattari 1957, NACA Report 1307 (the tail interference factor by strip
    theory).
    """
    s_hat = np.asarray(span_direction, float)
    e_t = np.asarray(direction, float)
    sigma = float(e_t @ np.array([-s_hat[1], s_hat[0]]))
    r1, r2 = root, root + span
    total = 0.0
    for pos, gamma in _images(vortex, lift_direction, body_radius):
        zeta, h = float(pos @ s_hat), float(pos @ e_t)
        num, den = (r2 - zeta) ** 2 + h * h, (r1 - zeta) ** 2 + h * h
        if num == 0.0 or den == 0.0:
            raise ValueError("panel_sidewash: a vortex at the panel's root or tip")
        total += gamma * sigma * math.log(num / den) / (4.0 * math.pi * span)
    return total


def ring_sidewash(vortex, lift_direction, body_radius: float, *, radius: float) -> np.ndarray:
    r"""A ring wing's effective cross-flow per unit circulation of a vortex (and its image) [1/m]:
    the first circumferential harmonic of the radial velocity at its radius R,

    .. math:: \bar{\mathbf w} = \frac1\pi \oint (\mathbf u\cdot\hat r)\,\hat r\,d\theta,
              \qquad \bar w_y + i\,\bar w_z = -\frac{i\Gamma}{2\pi}\times
              \begin{cases} z_0/R^2 & |z_0| \le R \\ 1/\bar z_0 & |z_0| \ge R\end{cases}

    for a counter-clockwise vortex Γ at :math:`z_0 = y_0 + i z_0` (the Laurent series of its
    velocity on the circle; continuous at :math:`|z_0| = R`), summed over the vortex and its
    image. A uniform cross-flow's harmonic is the cross-flow itself.

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
    out = 0j
    for pos, gamma in _images(vortex, lift_direction, body_radius):
        z0 = complex(pos[0], pos[1])
        factor = z0 / radius ** 2 if abs(z0) <= radius else 1.0 / z0.conjugate()
        out += -1j * gamma / (2.0 * math.pi) * factor
    return np.array([out.real, out.imag])
